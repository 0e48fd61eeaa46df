// Section b) of the throughput benchmark (benchmarks/throughput.cpp): dense random 2D and 3D assemblies from 1e3
// to 1e6 particles; the cost per particle-step must stay flat (O(N)).
#pragma once
#include <omp.h>

#include <algorithm>
#include <cstdio>
#include <vector>

#include "benchmarks/dense_assembly.hpp"
#include "benchmarks/run_timing.hpp"
#include "benchmarks/throughput_world.hpp"
#include "engine/parallel.hpp"

namespace mc::bench {

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

// The heading and how the assemblies were made, from the jammed cells actually used.
inline void print_scaling_setup(const Options& opt) {
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
}

inline void print_scaling_table(const std::vector<ScalingRow>& rows) {
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
}

inline void print_scaling_relative(const std::vector<ScalingRow>& rows) {
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

inline void section_scaling(const Options& opt) {
  std::vector<int> sizes = opt.quick ? std::vector<int>{1000, 10000} : std::vector<int>{1000, 10000, 100000, 1000000};
  std::vector<ScalingRow> rows;
  progress("scaling\n");
  for (int n : sizes) rows.push_back(scaling_row<2>(n, opt.quick, opt));
  for (int n : sizes) rows.push_back(scaling_row<3>(n, opt.quick, opt));
  print_scaling_setup(opt);
  print_scaling_table(rows);
  print_scaling_relative(rows);
}

}  // namespace mc::bench
