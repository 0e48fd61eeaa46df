// Throughput benchmark of the engine's stepping loop (World::step), printed as markdown tables.
//
//  a) shared: the specimen of benchmarks/specimens/README.md, on which Yade, ESyS-Particle and LAMMPS were
//     timed; our figures beside theirs: unbonded linear contacts, parallel bonds beside them (the peers'
//     6-DOF bonds), and the Concrete Particle Model (beside Yade's CPM figures).
//  b) scaling: dense random 2D and 3D assemblies from 1e3 to 1e6 particles; the cost per particle-step must
//     stay flat (O(N)).
//  c) effects: the cost of each optional effect (gravity, local damping, contact dashpots, energy tracing)
//     as a ratio to the same run without it.
//
// Only the stepping loop is timed (std::chrono::steady_clock); each timing is repeated (default 3) on a fresh
// world and the best is kept. Ratios are always taken within one run: the machine is shared and noisy.
//
//   throughput [--quick] [--only shared|bonded|cpm|scaling|effects] [--specimen-dir DIR] [--reps N]
#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <memory>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "benchmarks/dense_assembly.hpp"
#include "benchmarks/run_timing.hpp"
#include "contact_models/cpm.hpp"
#include "contact_models/linear.hpp"
#include "contact_models/parallel_bond.hpp"
#include "engine/errors.hpp"
#include "engine/parallel.hpp"
#include "engine/world.hpp"
#include "io/sphere_list.hpp"
#include "preprocess/spatial_order.hpp"

#ifndef MESOCRACK_SOURCE_DIR
#define MESOCRACK_SOURCE_DIR "."
#endif

namespace {

using namespace mc::bench;

using namespace mc;

struct Options {
  bool quick = false;
  bool shared = true, scaling = true, effects = true;
  bool unbonded = true;              // the shared specimen also without bonds (--only bonded: with bonds only)
  bool parallel = true, cpm = true;  // its parallel-bonded and CPM runs (--only bonded / cpm: that one alone)
  std::string specimen_dir = MESOCRACK_SPECIMEN_DIR;
  int reps = 3;
  bool reps_given = false;
};

const int kThreads[] = {1, 2};

// ---------------------------------------------------------------------------------------------------------
// Worlds

struct Material {
  double modulus = 30e9;  // contact modulus E_c [Pa]
  double density = 2600;  // [kg/m³]
  double kn_ks = 1.0;
  double friction = 0.5;
  double damping = 0.0;  // ζ of the contact dashpots
  bool bonded = false;  // parallel bonds (E̅_c = E_c, k̄_n/k̄_s = k_n/k_s, λ̄ = 1, unbreakable here) beside the contacts
  bool cpm = false;  // instead, CPM contacts (k_N = E_c), cohesive where d ≤ 1.05 (R_i + R_j)
};

// The CPM of the shared run: k_N = E_c, k_T/k_N = 0.2, the document's inelastic parameters, but ε_0 = 1e-3 so that
// no contact damages in the timed window (the README: no bond breaks there), as in the parallel-bond run; cohesive
// contacts on the README's bond pairs, R_I = 1.05.
CpmParams shared_cpm_params(double modulus) {
  CpmParams p;
  p.modulus = modulus;
  p.crack_onset_strain = 1e-3;
  p.relative_ductility = 30;
  p.cohesion = 3.5e6;
  p.tan_friction = 0.8;
  p.interaction_radius = 1.05;
  return p;
}

template <int D>
World<D> make_world(const std::vector<Vec<D>>& x, const std::vector<double>& r, const Material& mat) {
  World<D> w;
  LinearParams lp;
  lp.modulus = mat.modulus;
  lp.kn_ks_ratio = mat.kn_ks;
  lp.friction = mat.friction;
  lp.damping_ratio = mat.damping;
  if (mat.cpm) {
    w.sets.push_back(std::make_unique<ContactSet<Cpm, D>>(shared_cpm_params(mat.modulus)));
  } else if (mat.bonded) {
    ParallelBondParams bp;
    bp.contact = lp;
    bp.modulus = mat.modulus;
    bp.kn_ks_ratio = mat.kn_ks;
    bp.tensile_mean = bp.shear_mean = 1e12;  // no bond breaks in the timed window (README)
    w.sets.push_back(std::make_unique<ContactSet<ParallelBond, D>>(bp));
  } else {
    w.sets.push_back(std::make_unique<ContactSet<Linear, D>>(lp));
  }
  w.model_of = {{0}};
  const int n = static_cast<int>(x.size());
  auto& p = w.particles;
  for (auto* v : {&p.x, &p.v, &p.f}) v->reserve(n);
  p.w.reserve(n), p.m.reserve(n), p.q.reserve(n), p.radius.reserve(n), p.mass.reserve(n), p.inertia.reserve(n);
  p.phase.reserve(n), p.fix.reserve(n);
  Vec<D> lo = Vec<D>::Constant(kInf), hi = Vec<D>::Constant(-kInf);
  for (int i = 0; i < n; ++i) {
    p.add(x[i], r[i], mat.density, 0);
    lo = lo.cwiseMin(x[i]);
    hi = hi.cwiseMax(x[i]);
  }
  const Vec<D> margin = Vec<D>::Constant((hi - lo).maxCoeff() + 1.0);
  w.domain_lo = lo - margin;
  w.domain_hi = hi + margin;
  return w;
}

// ---------------------------------------------------------------------------------------------------------
// a) The shared specimen

struct Peer {
  const char* name;
  double pss[4];  // n10k 1 core, n10k 2 cores, n50k 1 core, n50k 2 cores (particle-steps/s)
};
// benchmarks/specimens/README.md, "What the peers did on it".
const Peer kPeers[] = {
    {"ESyS-Particle, RotBond (6-DOF bond)", {1.17e6, 1.40e6, 8.3e5, 1.15e6}},
    {"Yade, CohFrict (6-DOF bond)", {6.0e5, 1.02e6, 4.8e5, 8.1e5}},
    {"Yade, CPM", {6.4e5, 1.24e6, 5.3e5, 9.4e5}},
    {"LAMMPS, central harmonic bonds + granular pair (no moments)", {9.3e6, 1.9e7, 6.6e6, 1.14e7}},
};

struct SharedRun {
  std::string name;
  int n = 0;
  double radius = 0, height = 0;
  double dt_readme = 0;
  std::string refusal;   // the engine's message if it refused dt_readme
  Timing t[2];           // 1 and 2 threads
  double strain = kNaN;  // z strain of the moved layer after the run (2 threads, last repetition)
  long rss_before_kib = -1, hwm_kib = -1;
  bool hwm_reset = false;
  double read_seconds = 0;
};

const int kSharedWarmup = 10;

// One repetition on a fresh world. Throws InputError if the engine refuses the fixed step.
Timing shared_once(const SphereList<3>& s, const Material& mat, double dt_fixed, double height, int steps,
                   double* strain) {
  World<3> w = make_world<3>(s.x, s.radius, mat);
  const FixMask all = static_cast<FixMask>((1u << (3 + Dim<3>::rot)) - 1);  // every translation and rotation
  w.timestep.fixed = dt_fixed;
  w.init();
  // README: bonds on every pair with centre distance ≤ 1.05 (r_i + r_j), i.e. gap ≤ 0.1 r for equal radii.
  // CPM: cohesive contacts within R_I = 1.05, the same pairs.
  if (mat.bonded || mat.cpm) w.install_bonds(0.1, 1);
  // Loading (README): tag 1 held, tag 2 moved down at constant velocity so that the strain along z is 1e-4
  // after 2010 steps. The velocity follows from the step actually used.
  const double v = 1e-4 * height / (2010.0 * w.dt);
  std::vector<int> top;
  for (int i = 0; i < s.size(); ++i) {
    if (s.tag[i] == 1) w.particles.fix[i] = all;
    if (s.tag[i] == 2) {
      w.particles.v[i] = Vec<3>(0, 0, -v);
      w.particles.fix[i] = all;
      top.push_back(i);
    }
  }
  Timing t = time_steps(w, kSharedWarmup, steps);
  double dz = 0;
  for (int i : top) dz += s.x[i][2] - w.particles.x[i][2];
  if (strain && !top.empty()) *strain = dz / static_cast<double>(top.size()) / height;
  return t;
}

SharedRun run_shared(const std::string& path, const std::string& name, const Material& mat, int steps,
                     const Options& opt) {
  SharedRun run;
  run.name = name;
  const auto r0 = Clock::now();
  SphereList<3> s = read_sphere_list<3>(path);
  {
    // Numbered along a Morton curve, as `mesocrack run` loads a sphere list (engine/build_world.cpp).
    const std::vector<int> order = morton_order<3>(s.x);
    const SphereList<3> f = s;
    for (std::size_t k = 0; k < order.size(); ++k)
      s.x[k] = f.x[order[k]], s.radius[k] = f.radius[order[k]], s.tag[k] = f.tag[order[k]], s.id[k] = f.id[order[k]];
  }
  run.read_seconds = std::chrono::duration<double>(Clock::now() - r0).count();
  run.n = s.size();
  double zlo = kInf, zhi = -kInf;
  for (int i = 0; i < s.size(); ++i) {
    run.radius = std::max(run.radius, s.radius[i]);
    zlo = std::min(zlo, s.x[i][2] - s.radius[i]);
    zhi = std::max(zhi, s.x[i][2] + s.radius[i]);
  }
  run.height = zhi - zlo;
  run.dt_readme = 0.3 * run.radius * std::sqrt(mat.density / mat.modulus);  // README: dt = 0.3 r sqrt(ρ/E)
  run.rss_before_kib = status_kib("VmRSS");
  run.hwm_reset = reset_peak_rss();
  for (int ti = 0; ti < 2; ++ti) {
    omp_set_num_threads(kThreads[ti]);
    for (int rep = 0; rep < opt.reps; ++rep) {
      progress("  shared %s, %d thread(s), repetition %d/%d ...", name.c_str(), kThreads[ti], rep + 1, opt.reps);
      double strain = kNaN;
      Timing t;
      try {
        t = shared_once(s, mat, run.refusal.empty() ? run.dt_readme : 0.0, run.height, steps, &strain);
      } catch (const InputError& e) {
        // The engine's critical estimate refuses the README step: say so and use the engine's own step.
        run.refusal = e.what();
        progress(" README step refused, engine's own step used ...");
        t = shared_once(s, mat, 0.0, run.height, steps, &strain);
      }
      progress(" %.2f s\n", t.seconds);
      run.t[ti].keep_best(t);
      run.strain = strain;
    }
  }
  run.hwm_kib = status_kib("VmHWM");
  return run;
}

void section_shared(const Options& opt, bool bonded, bool cpm = false) {
  Material mat;  // E_c = 30 GPa, ρ = 2600, kn/ks = 1, μ = 0.5, no dashpots
  mat.bonded = bonded && !cpm;
  mat.cpm = cpm;
  const char* model = cpm      ? "CPM (cohesive within R_I = 1.05)"
                      : bonded ? "parallel bonds + linear contacts"
                               : "unbonded linear contacts";
  const int steps = opt.quick ? 200 : 2000;
  std::vector<SharedRun> runs;
  const std::vector<std::string> names =
      opt.quick ? std::vector<std::string>{"n10k"} : std::vector<std::string>{"n10k", "n50k"};
  for (const auto& name : names) {
    const std::string path = opt.specimen_dir + "/" + name + ".spheres";
    progress("shared specimen %s\n", path.c_str());
    runs.push_back(run_shared(path, name, mat, steps, opt));
  }

  std::printf("## a) The shared specimen (benchmarks/specimens): %s\n\n", model);
  if (cpm)
    std::printf(
        "Model: **Concrete Particle Model** (`ContactSet<Cpm,3>`, Šmilauer; the peers' line to compare is "
        "Yade, CPM): cohesive contacts on every pair with d <= 1.05 (R_i + R_j) (R_I = 1.05, the README's bond "
        "pairs), k_N = E_c below, k_T/k_N = 0.2, c_T0 = 3.5 MPa, tan φ = 0.8, ε_f/ε_0 = 30, ε_0 = 1e-3 (no "
        "damage in the window), compressive hardening and the logarithmic surface on; no linear contacts: the "
        "keys below other than the modulus and density do not apply. Bond-steps/s = cohesive contacts x "
        "steps/s.\n\n");
  else if (bonded)
    std::printf(
        "Model: **parallel bonds** (`ContactSet<ParallelBond,3>`, 6-DOF beams, Tang 3.37-3.41) on every pair "
        "with d <= 1.05 (R_i + R_j), bond modulus = contact modulus, k̄_n/k̄_s = k_n/k_s, λ̄ = 1, in parallel "
        "with the linear contacts below. Bond-steps/s = bonds x steps/s.\n\n");
  std::printf(
      "Contacts: linear contacts (`ContactSet<Linear,3>`), contact modulus E_c = %.3g Pa "
      "(ball k_n = 4 R E_c, pair k_n = 2 R E_c in series), k_n/k_s = %.3g, friction μ = %.3g, no dashpots, "
      "density %.4g kg/m³; no gravity, no local damping, no energy tracing. %s Tag 1 fixed (all 6 DOFs), "
      "tag 2 moved down at constant velocity (all 6 DOFs fixed, prescribed v_z) for a z strain of 1e-4 "
      "after 2010 steps; %d warm-up steps, then %d timed steps%s; best of %d fresh runs.\n\n",
      mat.modulus, mat.kn_ks, mat.friction, mat.density,
      bonded ? "The peers ran bonded specimens too: the ratios compare bond loop with bond loop."
             : "The peers ran *bonded* specimens: the ratios below compare our unbonded contact loop with "
               "their bond loops (section a, bonded, compares like with like).",
      kSharedWarmup, steps, opt.quick ? " (--quick: 200 instead of 2000)" : "", opt.reps);

  for (const auto& r : runs) {
    std::printf("- %s: %d spheres, r = %.4g m, height %.4g m, read in %.3f s; README dt = 0.3 r sqrt(ρ/E) = %.4g s",
                r.name.c_str(), r.n, r.radius, r.height, r.read_seconds, r.dt_readme);
    if (r.refusal.empty())
      std::printf(", accepted (engine's critical estimate %.4g s).", r.t[0].dt_critical);
    else
      std::printf(
          ", **refused by the engine**: \"%s\". Engine's own step used instead: dt = %.4g s (0.8 × "
          "critical %.4g s).",
          r.refusal.c_str(), r.t[0].dt, r.t[0].dt_critical);
    std::printf(" z strain of the moved layer after %d steps: %.3g.\n", kSharedWarmup + steps, r.strain);
  }
  std::printf("\n");

  std::printf(
      "| specimen | threads | particles | candidate pairs / particle | touching pairs / particle | "
      "coordination | rebuilds in window | particle-steps/s | contact-steps/s | ns / particle-step | CPU/wall | "
      "2-thread speedup |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const auto& r : runs)
    for (int ti = 0; ti < 2; ++ti) {
      const Timing& t = r.t[ti];
      std::printf("| %s | %d | %d | %s | %s | %s | %lld | %s | %s | %s | %s | %s |\n", r.name.c_str(), kThreads[ti],
                  t.n, fix(t.candidates / t.n, 2).c_str(), fix(t.contacts / t.n, 2).c_str(),
                  fix(2.0 * t.contacts / t.n, 2).c_str(), static_cast<long long>(t.rebuilds),
                  sci(t.particle_steps()).c_str(), sci(t.contact_steps()).c_str(),
                  fix(t.ns_per_particle_step(), 1).c_str(), t.share(kThreads[ti]).c_str(),
                  ti == 1 ? fix(r.t[0].seconds / r.t[1].seconds, 2).c_str() : "");
    }
  std::printf(
      "\n(candidate pairs = pairs in the neighbour lists, within R_i + R_j + skin, skin = 0.1 R_min; for this "
      "specimen they are exactly the README's bond pairs, d ≤ 1.05 (R_i + R_j). Touching pairs: overlap > 0; "
      "contact-steps/s counts those. Coordination = 2 × touching pairs / N. CPU/wall = process CPU time / "
      "wall time in the timed loop, ≈ the thread count on a quiet machine; \"contended\": below 80 %% of the "
      "cores asked for, other processes took them and the figure measures the machine more than the engine.)"
      "\n\n");

  // Our figures beside the peers', in the README's columns.
  auto ours = [&](int col) -> double {
    const int spec = col / 2, ti = col % 2;
    return spec < static_cast<int>(runs.size()) ? runs[spec].t[ti].particle_steps() : kNaN;
  };
  std::printf("Particle-steps per second, stepping loop only (peers: README table):\n\n");
  std::printf("| engine, model | n10k, 1 core | n10k, 2 cores | n50k, 1 core | n50k, 2 cores |\n");
  std::printf("|---|---|---|---|---|\n");
  for (const auto& p : kPeers)
    std::printf("| %s | %s | %s | %s | %s |\n", p.name, sci(p.pss[0], 3).c_str(), sci(p.pss[1], 3).c_str(),
                sci(p.pss[2], 3).c_str(), sci(p.pss[3], 3).c_str());
  std::printf("| **mesocrack, %s (this run)** | **%s** | **%s** | **%s** | **%s** |\n\n", model, sci(ours(0)).c_str(),
              sci(ours(1)).c_str(), sci(ours(2)).c_str(), sci(ours(3)).c_str());
  std::printf("Ratio ours / peer (> 1: mesocrack faster; %s):\n\n", cpm      ? "the CPM line is like with like"
                                                                    : bonded ? "both sides bonded"
                                                                             : "ours without bonds here");
  if (bonded)
    for (const auto& r : runs)
      for (int ti = 0; ti < 2; ++ti)
        std::printf("- %s, %d thread(s): bond-steps/s = %s\n", r.name.c_str(), kThreads[ti],
                    sci(r.t[ti].candidates * r.t[ti].particle_steps() / r.t[ti].n).c_str());
  if (bonded) std::printf("\n");
  std::printf("| ours / peer | n10k, 1 core | n10k, 2 cores | n50k, 1 core | n50k, 2 cores |\n");
  std::printf("|---|---|---|---|---|\n");
  for (const auto& p : kPeers)
    std::printf("| %s | %s | %s | %s | %s |\n", p.name, fix(ours(0) / p.pss[0], 2).c_str(),
                fix(ours(1) / p.pss[1], 2).c_str(), fix(ours(2) / p.pss[2], 2).c_str(),
                fix(ours(3) / p.pss[3], 2).c_str());
  std::printf("\n");

  std::printf("Memory (peers, README: ESyS 44 MiB, Yade ~340 MiB with Python, for n10k):\n\n");
  std::printf(
      "| specimen | VmRSS before the worlds | peak resident (VmHWM) | engine containers (estimate) | "
      "bytes / particle: particles | contacts (pairs + histories) | slots | gather lists | total |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  for (const auto& r : runs) {
    const Footprint& fp = r.t[1].fp;
    const double n = r.n;
    std::printf("| %s | %.1f MiB | %.1f MiB%s | %.1f MiB | %.0f | %.0f | %.0f | %.0f | %.0f |\n", r.name.c_str(),
                r.rss_before_kib / 1024.0, r.hwm_kib / 1024.0, r.hwm_reset ? "" : " (peak of the whole process)",
                fp.total() / 1048576.0, fp.particles / n, fp.contacts / n, fp.slots / n, fp.gather / n, fp.total() / n);
  }
  std::printf(
      "\n(VmHWM is reset before each specimen, so it is the peak while that specimen's worlds existed, "
      "including the process itself and the particle list read from the file.)\n\n");
}

// ---------------------------------------------------------------------------------------------------------
// b) Scaling

struct ScalingRow {
  int dim = 0, target = 0;
  double held = 0;  // fraction of particles held (near the cube's faces)
  Timing t[2];
};

template <int D>
ScalingRow scaling_row(int target, bool quick, const Options& opt) {
  const Cell<D>& cell = cell_for_dim<D>(quick);
  const Assembly<D> a = tile(cell, kR0, target, false);
  const int n = static_cast<int>(a.x.size());
  const int steps = std::max(50, static_cast<int>((quick ? 2e6 : 2e7) / n));
  ScalingRow row;
  row.dim = D;
  row.target = target;
  row.held = static_cast<double>(std::count(a.edge.begin(), a.edge.end(), 1)) / n;
  Material mat;
  const FixMask all = static_cast<FixMask>((1u << (D + Dim<D>::rot)) - 1);
  for (int ti = 0; ti < 2; ++ti) {
    omp_set_num_threads(kThreads[ti]);
    for (int rep = 0; rep < opt.reps; ++rep) {
      progress("  %dD N = %d, %d steps, %d thread(s), repetition %d/%d ...", D, n, steps, kThreads[ti], rep + 1,
               opt.reps);
      World<D> w = make_world<D>(a.x, a.r, mat);
      // The particles near the faces may have lost periodic partners: held in place, they keep the rest of the
      // assembly in its (periodic) equilibrium, in place of walls.
      for (int i = 0; i < n; ++i)
        if (a.edge[i]) w.particles.fix[i] = all;
      w.init();
      const Timing t = time_steps(w, 10, steps);
      progress(" %.2f s\n", t.seconds);
      row.t[ti].keep_best(t);
    }
  }
  return row;
}

void section_scaling(const Options& opt) {
  std::vector<int> sizes = opt.quick ? std::vector<int>{1000, 10000} : std::vector<int>{1000, 10000, 100000, 1000000};
  std::vector<ScalingRow> rows;
  progress("scaling\n");
  for (int n : sizes) rows.push_back(scaling_row<2>(n, opt.quick, opt));
  for (int n : sizes) rows.push_back(scaling_row<3>(n, opt.quick, opt));

  const Cell<2>& c2 = cell_for_dim<2>(opt.quick);
  const Cell<3>& c3 = cell_for_dim<3>(opt.quick);
  std::printf("## b) Scaling with the number of particles\n\n");
  std::printf(
      "Dense random assemblies, radii uniform in [0.8, 1.2]·r0 (r0 = %.3g m): a periodic cell of %zu (2D) / "
      "%zu (3D) particles brought just past jamming (overlap-energy minimisation at φ = %.4f / %.4f; cell "
      "coordination %.2f / %.2f, mean overlap %.2f %% / %.2f %% of r0, max %.1f %% / %.1f %%), tiled and "
      "clipped to a square / cube, numbered along a Morton curve. The particles within R + 1.2 r0 of a face (they may "
      "have lost periodic partners) are held (all DOFs fixed) in place of walls, so the rest stays in "
      "equilibrium, dense; "
      "no walls, no gravity, no damping. Unbonded linear contacts as in a); the engine's own step (0.8 × "
      "critical). Steps = max(50, %s/N) after 10 warm-up steps; best of %d fresh runs. Coordination = 2 × "
      "touching pairs / N. CPU/wall = process CPU time / wall time in the loop (≈ thread count on a quiet "
      "machine; \"contended\": below 80 %% of the cores asked for). The engine runs loops of fewer than %d "
      "items on one thread, so the 2-thread runs of the smallest sizes are partly serial.\n\n",
      kR0, c2.x.size(), c3.x.size(), c2.phi, c3.phi, c2.z, c3.z, 100 * c2.mean_overlap, 100 * c3.mean_overlap,
      100 * c2.max_overlap, 100 * c3.max_overlap, opt.quick ? "2e6" : "2e7", opt.reps, kParallelMin);
  std::printf(
      "| dim | N | held | steps | candidate pairs / particle | coordination | rebuilds | bytes / particle | "
      "1 thread: particle-steps/s | ns / particle-step | contact-steps/s | CPU/wall | "
      "2 threads: particle-steps/s | ns / particle-step | contact-steps/s | CPU/wall | speedup |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const auto& r : rows) {
    const Timing &a = r.t[0], &b = r.t[1];
    std::printf("| %dD | %d | %.1f %% | %d | %s | %s | %lld | %.0f | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n",
                r.dim, a.n, 100 * r.held, a.steps, fix(a.candidates / a.n, 2).c_str(),
                fix(2.0 * a.contacts / a.n, 2).c_str(), static_cast<long long>(a.rebuilds),
                static_cast<double>(a.fp.total()) / a.n, sci(a.particle_steps()).c_str(),
                fix(a.ns_per_particle_step(), 1).c_str(), sci(a.contact_steps()).c_str(), a.share(1).c_str(),
                sci(b.particle_steps()).c_str(), fix(b.ns_per_particle_step(), 1).c_str(),
                sci(b.contact_steps()).c_str(), b.share(2).c_str(), fix(a.seconds / b.seconds, 2).c_str());
  }
  std::printf("\nCost per particle-step relative to the smallest size of the same dimension (flat = O(N)):\n\n");
  std::printf("| dim | N | 1 thread | 2 threads |\n|---|---|---|---|\n");
  for (const auto& r : rows) {
    const ScalingRow* base = nullptr;
    for (const auto& q : rows)
      if (q.dim == r.dim) {
        base = &q;
        break;
      }
    std::printf("| %dD | %d | %s | %s |\n", r.dim, r.t[0].n,
                fix(r.t[0].ns_per_particle_step() / base->t[0].ns_per_particle_step(), 2).c_str(),
                fix(r.t[1].ns_per_particle_step() / base->t[1].ns_per_particle_step(), 2).c_str());
  }
  std::printf("\n");
}

// ---------------------------------------------------------------------------------------------------------
// c) Effects

struct Effect {
  const char* name;
  bool gravity = false, local_damping = false, dashpots = false, energy = false;
};

void section_effects(const Options& opt) {
  const int target = opt.quick ? 10000 : 100000;
  const Cell<3>& cell = cell_for_dim<3>(opt.quick);
  const Assembly<3> a = tile(cell, kR0, target, false);
  const int n = static_cast<int>(a.x.size());
  const int steps = std::max(50, static_cast<int>((opt.quick ? 1e6 : 1e7) / n));
  const FixMask all = static_cast<FixMask>((1u << 6) - 1);
  // The walls touch the outermost particles by 0.5 % of r0.
  Vec<3> lo = Vec<3>::Constant(kInf), hi = Vec<3>::Constant(-kInf);
  for (int i = 0; i < n; ++i) {
    lo = lo.cwiseMin(a.x[i] - Vec<3>::Constant(a.r[i]));
    hi = hi.cwiseMax(a.x[i] + Vec<3>::Constant(a.r[i]));
  }
  lo.array() += kTargetOverlap * kR0;
  hi.array() -= kTargetOverlap * kR0;
  const std::vector<Effect> effects = {
      {"nothing declared (reference)"},
      {"gravity (0, 0, −9.81) m/s²", true},
      {"local damping α = 0.7", false, true},
      {"contact dashpots ζ = 0.1", false, false, true},
      {"energy tracing", false, false, false, true},
      {"nothing declared, again (noise floor)"},
      {"all four", true, true, true, true},
  };
  progress("effects: %d particles in six walls, %d steps\n", n, steps);
  // seconds[threads][effect]: the repetitions are interleaved, so slow phases of the machine hit every effect.
  std::vector<std::vector<Timing>> best(2, std::vector<Timing>(effects.size()));
  for (int ti = 0; ti < 2; ++ti) {
    omp_set_num_threads(kThreads[ti]);
    for (int rep = 0; rep < opt.reps; ++rep)
      for (std::size_t e = 0; e < effects.size(); ++e) {
        const Effect& ef = effects[e];
        progress("  %d thread(s), repetition %d/%d, %s ...", kThreads[ti], rep + 1, opt.reps, ef.name);
        Material mat;
        if (ef.dashpots) mat.damping = 0.1;
        World<3> w = make_world<3>(a.x, a.r, mat);
        for (int i = 0; i < n; ++i)
          if (a.edge[i]) w.particles.fix[i] = all;  // as in b)
        WallMaterial wm;
        wm.kn = 4 * kR0 * mat.modulus;  // as stiff as a ball of radius r0
        wm.ks = wm.kn / mat.kn_ks;
        wm.friction = mat.friction;
        for (int k = 0; k < 3; ++k)
          for (int side = 0; side < 2; ++side) {
            Vec<3> pt = 0.5 * (lo + hi), nrm = Vec<3>::Zero();
            pt[k] = side ? hi[k] : lo[k];
            nrm[k] = side ? -1.0 : 1.0;
            Wall<3> wl = Wall<3>::plane(pt, nrm);
            wl.name = std::string(side ? "+" : "-") + "xyz"[k];
            wl.material = wm;
            w.walls.push_back(wl);
          }
        if (ef.gravity) w.gravity = Vec<3>(0, 0, -9.81);
        if (ef.local_damping) w.local_damping = 0.7;
        w.trace_energy = ef.energy;
        w.init();
        if (ef.energy) {
          w.update_energy();
          w.energy.initial = w.energy.kinetic + w.energy.strain;
        }
        const Timing t = time_steps(w, 10, steps);
        progress(" %.2f s\n", t.seconds);
        best[ti][e].keep_best(t);
      }
  }
  std::printf("## c) Cost of the optional effects\n\n");
  std::printf(
      "3D assembly of %d particles as in b) (cube of side %.4g m, the %.1f %% near the faces held), inside six "
      "fixed planar walls touching the outermost particles; unbonded linear contacts; %d steps after 10 "
      "warm-up; each effect on a fresh world, repetitions interleaved, best of %d. Ratio = step time with the "
      "effect / step time with nothing declared; the second \"nothing declared\" row is the noise floor.\n\n",
      n, a.side, 100.0 * static_cast<double>(std::count(a.edge.begin(), a.edge.end(), 1)) / n, steps, opt.reps);
  std::printf(
      "| declared | 1 thread: ns / particle-step | ratio | CPU/wall | 2 threads: ns / particle-step | ratio | "
      "CPU/wall |\n|---|---|---|---|---|---|---|\n");
  for (std::size_t e = 0; e < effects.size(); ++e)
    std::printf("| %s | %s | %s | %s | %s | %s | %s |\n", effects[e].name,
                fix(best[0][e].ns_per_particle_step(), 1).c_str(),
                fix(best[0][e].seconds / best[0][0].seconds, 3).c_str(), best[0][e].share(1).c_str(),
                fix(best[1][e].ns_per_particle_step(), 1).c_str(),
                fix(best[1][e].seconds / best[1][0].seconds, 3).c_str(), best[1][e].share(2).c_str());
  std::printf(
      "\n(reference run: coordination %.2f, candidate pairs / particle %.2f, ball–wall pairs %.0f, "
      "rebuilds in the window %lld.)\n\n",
      2.0 * best[1][0].contacts / n, best[1][0].candidates / n, best[1][0].wall_candidates,
      static_cast<long long>(best[1][0].rebuilds));
}

// ---------------------------------------------------------------------------------------------------------

[[noreturn]] void usage(const std::string& why) {
  std::fprintf(
      stderr,
      "%s\nusage: throughput [--quick] [--only shared|bonded|cpm|scaling|effects] [--specimen-dir DIR] [--reps N]\n",
      why.c_str());
  std::exit(2);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage("option " + a + " needs a value");
      return argv[++i];
    };
    if (a == "--quick") {
      o.quick = true;
    } else if (a == "--only") {
      const std::string v = value();
      if (v != "shared" && v != "bonded" && v != "cpm" && v != "scaling" && v != "effects")
        usage("--only '" + v + "': allowed shared, bonded, cpm, scaling, effects");
      o.shared = v == "shared" || v == "bonded" || v == "cpm", o.scaling = v == "scaling", o.effects = v == "effects";
      o.unbonded = v == "shared", o.parallel = v != "cpm", o.cpm = v != "bonded";
    } else if (a == "--specimen-dir") {
      o.specimen_dir = value();
    } else if (a == "--reps") {
      const std::string v = value();
      char* end = nullptr;
      const long r = std::strtol(v.c_str(), &end, 10);
      if (*end || r < 1 || r > 100) usage("--reps '" + v + "': allowed an integer from 1 to 100");
      o.reps = static_cast<int>(r);
      o.reps_given = true;
    } else if (a == "--help" || a == "-h") {
      usage("Throughput of the stepping loop, as markdown tables.");
    } else {
      usage("unknown option '" + a + "'");
    }
  }
  if (o.quick && !o.reps_given) o.reps = 1;
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  // On a shared machine, threads that spin at the end of each parallel region (libgomp's default) lose whole time
  // slices whenever another process holds a core, and 2-thread runs become several times slower than 1-thread
  // runs. Unless the caller chose a policy, run with passive waiting: libgomp reads it at start-up, so re-execute.
  bool policy_set_here = false;
  if (!std::getenv("OMP_WAIT_POLICY")) {
    setenv("OMP_WAIT_POLICY", "passive", 1);
    setenv("MESOCRACK_BENCH_POLICY_SET", "1", 1);
    execv("/proc/self/exe", argv);  // returns only on failure: go on with the default policy
    unsetenv("OMP_WAIT_POLICY");
  }
  policy_set_here = std::getenv("MESOCRACK_BENCH_POLICY_SET") != nullptr;
  const char* policy = std::getenv("OMP_WAIT_POLICY");
  const Options opt = parse(argc, argv);
  const auto t0 = Clock::now();
  std::printf("# mesocrack throughput%s\n\n", opt.quick ? " (--quick: small sizes)" : "");
  std::printf(
      "%d hardware threads visible (omp_get_num_procs); timings with omp_set_num_threads(1) and (2). "
      "OpenMP wait policy: %s%s.\n\n",
      omp_get_num_procs(), policy ? policy : "libgomp default (spin, then sleep)",
      policy_set_here ? " (set by this benchmark; run with OMP_WAIT_POLICY=active to measure spinning threads)" : "");
  std::printf(
      "Load average (1 / 5 / 15 min) at the start: %s. The machine may be shared: the CPU/wall columns and "
      "the load after each section tell how quiet it was.\n\n",
      loadavg().c_str());
  auto section = [](auto&& fn) {
    fn();
    std::printf("(load average after this section: %s)\n\n", loadavg().c_str());
    std::fflush(stdout);
  };
  try {
    if (opt.shared && opt.unbonded) section([&] { section_shared(opt, false); });
    if (opt.shared && opt.parallel) section([&] { section_shared(opt, true); });
    if (opt.shared && opt.cpm) section([&] { section_shared(opt, true, true); });
    if (opt.scaling) section([&] { section_scaling(opt); });
    if (opt.effects) section([&] { section_effects(opt); });
  } catch (const std::exception& e) {
    std::fprintf(stderr, "throughput: %s\n", e.what());
    return 1;
  }
  std::printf("Total run time %.0f s.\n", std::chrono::duration<double>(Clock::now() - t0).count());
  return 0;
}
