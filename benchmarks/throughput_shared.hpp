// Section a) of the throughput benchmark (benchmarks/throughput.cpp): the shared specimen of
// benchmarks/specimens/README.md, loaded as that README says, and our figures on it (the peers on the same machine:
// make peers-bench).
#pragma once
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "benchmarks/dense_assembly.hpp"
#include "benchmarks/run_timing.hpp"
#include "benchmarks/throughput_world.hpp"
#include "engine/errors.hpp"
#include "io/sphere_list.hpp"
#include "preprocess/spatial_order.hpp"

namespace mc::bench {

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

inline constexpr int kSharedWarmup = 10;

// The shared specimen as the README loads it, on a fresh world: bonds (or CPM's cohesive contacts) installed, tag 1
// held, tag 2 moved down (its indices in *top). Throws InputError if the engine refuses the fixed step.
inline World<3> shared_world(const SphereList<3>& s, const Material& mat, double dt_fixed, double height,
                             std::vector<int>* top) {
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
  for (int i = 0; i < s.size(); ++i) {
    if (s.tag[i] == 1) w.particles.fix[i] = all;
    if (s.tag[i] == 2) {
      w.particles.v[i] = Vec<3>(0, 0, -v);
      w.particles.fix[i] = all;
      top->push_back(i);
    }
  }
  return w;
}

// One repetition on a fresh world. Throws InputError if the engine refuses the fixed step.
inline Timing shared_once(const SphereList<3>& s, const Material& mat, double dt_fixed, double height, int steps,
                          double* strain) {
  std::vector<int> top;
  World<3> w = shared_world(s, mat, dt_fixed, height, &top);
  Timing t = time_steps(w, kSharedWarmup, steps);
  double dz = 0;
  for (int i : top) dz += s.x[i][2] - w.particles.x[i][2];
  if (strain && !top.empty()) *strain = dz / static_cast<double>(top.size()) / height;
  return t;
}

// The shared specimen's largest radius and its height (from the lowest sphere's bottom to the highest one's top).
struct SharedSize {
  double radius = 0, height = 0;
  double dt_readme(const Material& mat) const {  // README: dt = 0.3 r sqrt(ρ/E)
    return 0.3 * radius * std::sqrt(mat.density / mat.modulus);
  }
};

inline SharedSize shared_size(const SphereList<3>& s) {
  SharedSize size;
  double zlo = kInf, zhi = -kInf;
  for (int i = 0; i < s.size(); ++i) {
    size.radius = std::max(size.radius, s.radius[i]);
    zlo = std::min(zlo, s.x[i][2] - s.radius[i]);
    zhi = std::max(zhi, s.x[i][2] + s.radius[i]);
  }
  size.height = zhi - zlo;
  return size;
}

// Numbered along a Morton curve, as `mesocrack run` loads a sphere list (engine/build_world.cpp).
inline SphereList<3> read_in_morton_order(const std::string& path) {
  SphereList<3> s = read_sphere_list<3>(path);
  const std::vector<int> order = morton_order<3>(s.x);
  const SphereList<3> f = s;
  for (std::size_t k = 0; k < order.size(); ++k)
    s.x[k] = f.x[order[k]], s.radius[k] = f.radius[order[k]], s.tag[k] = f.tag[order[k]], s.id[k] = f.id[order[k]];
  return s;
}

inline SharedRun run_shared(const std::string& path, const std::string& name, const Material& mat, int steps,
                            const Options& opt) {
  SharedRun run;
  run.name = name;
  const auto r0 = Clock::now();
  const SphereList<3> s = read_in_morton_order(path);
  run.read_seconds = std::chrono::duration<double>(Clock::now() - r0).count();
  run.n = s.size();
  const SharedSize size = shared_size(s);
  run.radius = size.radius;
  run.height = size.height;
  run.dt_readme = size.dt_readme(mat);
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

inline const char* shared_model(bool bonded, bool cpm) {
  return cpm      ? "CPM (cohesive within R_I = 1.05)"
         : bonded ? "parallel bonds + linear contacts"
                  : "unbonded linear contacts";
}

// The heading, the model and the loading: enough to rerun the case in another engine.
inline void print_shared_setup(const Options& opt, const Material& mat, bool bonded, bool cpm, int steps) {
  std::printf("## a) The shared specimen (benchmarks/specimens): %s\n\n", shared_model(bonded, cpm));
  if (cpm)
    std::printf(
        "Model: **Concrete Particle Model** (`ContactSet<Cpm,3>`, Šmilauer; make peers-bench sets it against "
        "Yade's CPM): cohesive contacts on every pair with d <= 1.05 (R_i + R_j) (R_I = 1.05, the README's bond "
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
      bonded ? "The peers' runs of this specimen (make peers-bench) are bonded too: bond loop against bond loop."
             : "make peers-bench sets this unbonded loop against LIGGGHTS's Hertz contacts, which have no bonds.",
      kSharedWarmup, steps, opt.quick ? " (--quick: 200 instead of 2000)" : "", opt.reps);
}

// Per specimen: its size, whether the engine took the README's step, the strain reached; then the timings.
inline void print_shared_runs(const std::vector<SharedRun>& runs, int steps) {
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
}

// Our figures in the columns of benchmarks/specimens/README.md. No ratio to a peer: one counts only when both ran in
// the same session on the same machine, which make peers-bench does.
inline void print_shared_rates(const std::vector<SharedRun>& runs, bool bonded, bool cpm) {
  auto ours = [&](int col) -> double {
    const int spec = col / 2, ti = col % 2;
    return spec < static_cast<int>(runs.size()) ? runs[spec].t[ti].particle_steps() : kNaN;
  };
  std::printf(
      "Particle-steps per second, stepping loop only (against the peers on this machine: make peers-bench):\n\n");
  std::printf("| engine, model | n10k, 1 core | n10k, 2 cores | n50k, 1 core | n50k, 2 cores |\n");
  std::printf("|---|---|---|---|---|\n");
  std::printf("| mesocrack, %s | %s | %s | %s | %s |\n\n", shared_model(bonded, cpm), sci(ours(0)).c_str(),
              sci(ours(1)).c_str(), sci(ours(2)).c_str(), sci(ours(3)).c_str());
  if (!bonded) return;
  for (const auto& r : runs)
    for (int ti = 0; ti < 2; ++ti)
      std::printf("- %s, %d thread(s): bond-steps/s = %s\n", r.name.c_str(), kThreads[ti],
                  sci(r.t[ti].candidates * r.t[ti].particle_steps() / r.t[ti].n).c_str());
  std::printf("\n");
}

inline void print_shared_memory(const std::vector<SharedRun>& runs) {
  std::printf("Memory:\n\n");
  std::printf(
      "| specimen | VmRSS before the worlds | peak resident (VmHWM) | engine containers (estimate) | "
      "bytes / particle: particles | contacts (pairs + histories) | slots | gather lists | "
      "total |\n");
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

// One run of the shared specimen, as one line the peers' runs also print (benchmarks/peers/peers_bench.py).
inline void one_shared(const Options& opt) {
  Material mat;
  mat.bonded = opt.one_model == "parallel";
  mat.cpm = opt.one_model == "cpm";
  const SphereList<3> s = read_in_morton_order(opt.specimen_dir + "/" + opt.one_specimen + ".spheres");
  const SharedSize size = shared_size(s);
  omp_set_num_threads(opt.one_threads);
  const int steps = 2000;
  double strain = kNaN;
  Timing t;
  try {
    t = shared_once(s, mat, size.dt_readme(mat), size.height, steps, &strain);
  } catch (const InputError&) {
    // As in section_shared: the engine's critical estimate refuses the README step; its own step, same step count.
    t = shared_once(s, mat, 0.0, size.height, steps, &strain);
  }
  std::printf(
      "RESULT engine=mesocrack model=%s particles=%d threads=%d steps=%d dt=%.4g wall_s=%.3f "
      "particle_steps_per_s=%.5g contacts=%.0f candidates=%.0f\n",
      opt.one_model.c_str(), s.size(), opt.one_threads, steps, t.dt, t.seconds, s.size() * steps / t.seconds,
      t.contacts, t.candidates);
}

inline void section_shared(const Options& opt, bool bonded, bool cpm = false) {
  Material mat;  // E_c = 30 GPa, ρ = 2600, kn/ks = 1, μ = 0.5, no dashpots
  mat.bonded = bonded && !cpm;
  mat.cpm = cpm;
  const int steps = opt.quick ? 200 : 2000;
  std::vector<SharedRun> runs;
  const std::vector<std::string> names =
      opt.quick ? std::vector<std::string>{"n10k"} : std::vector<std::string>{"n10k", "n50k"};
  for (const auto& name : names) {
    const std::string path = opt.specimen_dir + "/" + name + ".spheres";
    progress("shared specimen %s\n", path.c_str());
    runs.push_back(run_shared(path, name, mat, steps, opt));
  }
  print_shared_setup(opt, mat, bonded, cpm, steps);
  print_shared_runs(runs, steps);
  print_shared_rates(runs, bonded, cpm);
  print_shared_memory(runs);
}

}  // namespace mc::bench
