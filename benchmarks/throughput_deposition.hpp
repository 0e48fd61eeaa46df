// Section d) of the throughput benchmark (benchmarks/throughput.cpp): a deposition flow, where a fixed Verlet
// skin rebuilds the neighbour lists every few steps, run with the skin fixed and adaptive (World::rebuild_interval).
#pragma once
#include <omp.h>

#include <cstdio>
#include <vector>

#include "benchmarks/dense_assembly.hpp"
#include "benchmarks/run_timing.hpp"
#include "benchmarks/throughput_effects.hpp"
#include "benchmarks/throughput_world.hpp"
#include "engine/random_stream.hpp"

namespace mc::bench {

struct DepositionCase {
  const char* name;
  int rebuild_interval;
};

// A loose cloud (lattice spacing 2.6 r0, radii 0.8–1.2 r0) poured into a box: every particle starts at 5 m/s
// downwards with a random sideways velocity of up to 3 m/s, under gravity; unbonded linear contacts with
// friction, grains of 1 GPa (a granular material rather than concrete: the step is then long enough for a fixed
// skin to need a rebuild every ten steps or so).
inline Timing deposition_once(int per_side, int rebuild_interval, int steps) {
  Material mat;
  mat.modulus = 1e9;
  std::vector<Vec<3>> x;
  std::vector<double> r;
  RandomStream rng(11);
  const double a = 2.6 * kR0;
  for (int k = 0; k < 2 * per_side; ++k)
    for (int j = 0; j < per_side; ++j)
      for (int i = 0; i < per_side; ++i)
        x.push_back(Vec<3>((i + 0.5) * a, (j + 0.5) * a, (k + 0.5) * a)), r.push_back(kR0 * rng.uniform(0.8, 1.2));
  World<3> w = make_world<3>(x, r, mat);
  for (int i = 0; i < w.particles.size(); ++i) w.particles.v[i] = Vec<3>(rng.uniform(-3, 3), rng.uniform(-3, 3), -5.0);
  add_box_walls(w, Vec<3>::Zero(), Vec<3>(per_side * a, per_side * a, 2 * per_side * a), mat);
  w.gravity = Vec<3>(0, 0, -9.81);
  w.rebuild_interval = rebuild_interval;
  w.init();
  return time_steps(w, 10, steps);
}

inline void section_deposition(const Options& opt) {
  const int per_side = opt.quick ? 12 : 22, steps = opt.quick ? 500 : 3000;
  const std::vector<DepositionCase> cases = {{"fixed skin 0.1 R_min", 0},
                                             {"adaptive, rebuild_interval 30 (the scene default)", 30},
                                             {"adaptive, rebuild_interval 60", 60}};
  std::vector<std::vector<Timing>> best(2, std::vector<Timing>(cases.size()));
  progress("deposition: %d particles, %d steps\n", 2 * per_side * per_side * per_side, steps);
  for (int ti = 0; ti < 2; ++ti) {
    omp_set_num_threads(kThreads[ti]);
    for (int rep = 0; rep < opt.reps; ++rep)
      for (std::size_t c = 0; c < cases.size(); ++c) {  // interleaved repetitions
        progress("  %d thread(s), repetition %d/%d, %s ...", kThreads[ti], rep + 1, opt.reps, cases[c].name);
        const Timing t = deposition_once(per_side, cases[c].rebuild_interval, steps);
        progress(" %.2f s\n", t.seconds);
        best[ti][c].keep_best(t);
      }
  }
  std::printf("## d) Deposition: a fixed and an adaptive Verlet skin\n\n");
  std::printf(
      "%d particles (radii 0.8–1.2 r0, r0 = %.3g m) on a loose lattice of spacing 2.6 r0 in a box of six walls, "
      "poured at 5 m/s downwards with random sideways velocities up to 3 m/s, under gravity; unbonded linear "
      "contacts as in a) but with a contact modulus of 1 GPa; %d steps after 10 warm-up; best of %d, repetitions "
      "interleaved.\n\n",
      best[0][0].n, kR0, steps, opt.reps);
  std::printf(
      "| skin | rebuilds in the window | steps per rebuild | candidate pairs / particle | dt [s] | 1 thread: ns / "
      "particle-step | 2 threads: ns / particle-step | time against the fixed skin (1 thread) |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (std::size_t c = 0; c < cases.size(); ++c) {
    const Timing &a = best[0][c], &b = best[1][c];
    std::printf("| %s | %lld | %s | %s | %.4g | %s | %s | %s |\n", cases[c].name, static_cast<long long>(a.rebuilds),
                fix(a.rebuilds > 0 ? double(a.steps) / double(a.rebuilds) : kInf, 1).c_str(),
                fix(a.candidates / a.n, 2).c_str(), a.dt, fix(a.ns_per_particle_step(), 1).c_str(),
                fix(b.ns_per_particle_step(), 1).c_str(), fix(a.seconds / best[0][0].seconds, 2).c_str());
  }
  std::printf("\n");
}

}  // namespace mc::bench
