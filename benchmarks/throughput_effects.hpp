// Section c) of the throughput benchmark (benchmarks/throughput.cpp): the cost of each optional effect (gravity,
// local damping, contact dashpots, energy tracing) as a ratio to the same run without it.
#pragma once
#include <omp.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "benchmarks/dense_assembly.hpp"
#include "benchmarks/run_timing.hpp"
#include "benchmarks/throughput_world.hpp"

namespace mc::bench {

struct Effect {
  const char* name;
  bool gravity = false, local_damping = false, dashpots = false, energy = false;
};

// Six fixed planar walls, one per face of the box [lo, hi], as stiff as a ball of radius r0.
inline void add_box_walls(World<3>& w, const Vec<3>& lo, const Vec<3>& hi, const Material& mat) {
  WallMaterial wm;
  wm.kn = 4 * kR0 * mat.modulus;
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
}

// One repetition of one effect on a fresh world: the assembly held at its faces as in b), in the walls [lo, hi].
inline Timing effect_once(const Assembly<3>& a, const Effect& ef, const Vec<3>& lo, const Vec<3>& hi, int steps) {
  Material mat;
  if (ef.dashpots) mat.damping = 0.1;
  World<3> w = make_world<3>(a.x, a.r, mat);
  for (std::size_t i = 0; i < a.x.size(); ++i)
    if (a.edge[i]) w.particles.fix[i] = fix_all(3);
  add_box_walls(w, lo, hi, mat);
  if (ef.gravity) w.gravity = Vec<3>(0, 0, -9.81);
  if (ef.local_damping) w.local_damping = 0.7;
  w.trace_energy = ef.energy;
  w.init();
  if (ef.energy) {
    w.update_energy();
    w.energy.initial = w.energy.kinetic + w.energy.strain;
  }
  return time_steps(w, 10, steps);
}

// best[threads][effect], each effect's ratio taken to the reference (the first effect) of the same thread count.
inline void print_effects(const std::vector<Effect>& effects, const std::vector<std::vector<Timing>>& best,
                          const Assembly<3>& a, int steps, int reps) {
  const int n = static_cast<int>(a.x.size());
  std::printf("## c) Cost of the optional effects\n\n");
  std::printf(
      "3D assembly of %d particles as in b) (cube of side %.4g m, the %.1f %% near the faces held), inside six "
      "fixed planar walls touching the outermost particles; unbonded linear contacts; %d steps after 10 "
      "warm-up; each effect on a fresh world, repetitions interleaved, best of %d. Ratio = step time with the "
      "effect / step time with nothing declared; the second \"nothing declared\" row is the noise floor.\n\n",
      n, a.side, 100.0 * static_cast<double>(std::count(a.edge.begin(), a.edge.end(), 1)) / n, steps, reps);
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

inline void section_effects(const Options& opt) {
  const int target = opt.quick ? 10000 : 100000;
  const Cell<3>& cell = cell_for_dim<3>(opt.quick);
  const Assembly<3> a = tile(cell, kR0, target, false);
  const int n = static_cast<int>(a.x.size());
  const int steps = std::max(50, static_cast<int>((opt.quick ? 1e6 : 1e7) / n));
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
  // best[threads][effect]: the repetitions are interleaved, so slow phases of the machine hit every effect.
  std::vector<std::vector<Timing>> best(2, std::vector<Timing>(effects.size()));
  for (int ti = 0; ti < 2; ++ti) {
    omp_set_num_threads(kThreads[ti]);
    for (int rep = 0; rep < opt.reps; ++rep)
      for (std::size_t e = 0; e < effects.size(); ++e) {
        progress("  %d thread(s), repetition %d/%d, %s ...", kThreads[ti], rep + 1, opt.reps, effects[e].name);
        const Timing t = effect_once(a, effects[e], lo, hi, steps);
        progress(" %.2f s\n", t.seconds);
        best[ti][e].keep_best(t);
      }
  }
  print_effects(effects, best, a, steps, opt.reps);
}

}  // namespace mc::bench
