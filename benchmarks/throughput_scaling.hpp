// Section b) of the throughput benchmark (benchmarks/throughput.cpp): dense random 2D and 3D assemblies from 1e3
// to 1e6 particles, and a parallel-bonded 3D block from 1e4 to 1e7; the cost per particle-step and the memory per
// particle must stay flat (O(N)). The bonded rows also give the bytes a step streams and the fraction of the
// machine's triad bandwidth the loop reaches.
#pragma once
#include <omp.h>

#include <algorithm>
#include <cstdio>
#include <vector>

#include "benchmarks/bonded_block.hpp"
#include "benchmarks/dense_assembly.hpp"
#include "benchmarks/run_timing.hpp"
#include "benchmarks/stream_triad.hpp"
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

struct BondedRow {
  Timing t[2];
  double bonds = 0;       // intact bonds per particle
  double peak_bytes = 0;  // growth of the peak resident set while the worlds existed, per particle
};

// The 3D assembly of the unbonded rows as the bonded block (bonded_block.hpp). One fresh world per thread count.
inline BondedRow bonded_row(int target, bool quick, int reps) {
  const Assembly<3> a = tile(cell_for_dim<3>(quick), kR0, target, false);
  const int n = static_cast<int>(a.x.size());
  const int steps = std::max(20, static_cast<int>((quick ? 2e6 : 2e7) / n));
  BondedRow row;
  const long rss0 = status_kib("VmRSS");
  reset_peak_rss();
  for (int ti = 0; ti < 2; ++ti) {
    omp_set_num_threads(kThreads[ti]);
    progress("  bonded 3D N = %d, %d steps, %d thread(s) ...", n, steps, kThreads[ti]);
    std::size_t bonds = 0;
    World<3> w = bonded_block(a, &bonds);
    row.bonds = static_cast<double>(bonds) / n;
    // The best of `reps` windows of the same world (the block neither breaks nor flows): a slow stretch of a shared
    // machine falls on one window, and generating a block of 10^7 costs more than timing it.
    for (int rep = 0; rep < reps; ++rep) row.t[ti].keep_best(time_steps(w, rep == 0 ? 5 : 0, steps));
    progress(" %.2f s\n", row.t[ti].seconds);
  }
  row.peak_bytes = 1024.0 * static_cast<double>(status_kib("VmHWM") - rss0) / n;
  return row;
}

inline void print_bonded_scaling(const std::vector<BondedRow>& rows, const double triad[2], int reps) {
  std::printf(
      "\n### Parallel-bonded 3D block\n\nThe 3D assemblies above, every pair with a gap <= 0.1 R_min bonded by "
      "parallel bonds beside the linear contacts (the shared specimen's model, unbreakable here), the particles "
      "near the faces held; steps = max(20, 2e7/N) after 5 warm-up steps, the best of %d windows of the same "
      "world per thread count. Memory: the engine's containers (particles, contacts, slots, gather lists) and "
      "the growth of the process's peak resident set while the block's worlds existed (it includes the "
      "transient lists of the neighbour search and bonding). Streamed: the bytes a step would move through "
      "memory without caches (benchmarks/run_timing.hpp, streamed_bytes_per_step). Triad bandwidth of this "
      "machine, measured in this run (STREAM's a = b + s c over 3 x 128 MiB): %.1f GB/s on 1 thread, %.1f GB/s "
      "on 2.\n\n",
      reps, triad[0] / 1e9, triad[1] / 1e9);
  std::printf(
      "| N | bonds / particle | containers, B / particle | peak resident growth, B / particle | "
      "1 thread: ns / particle-step | 2 threads: ns / particle-step | speedup | streamed B / particle-step | "
      "GB/s, 1 thread | of triad | GB/s, 2 threads | of triad |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const auto& r : rows) {
    const Timing &a = r.t[0], &b = r.t[1];
    std::printf("| %d | %s | %.0f | %.0f | %s | %s | %s | %.0f | %s | %s %% | %s | %s %% |\n", a.n,
                fix(r.bonds, 2).c_str(), static_cast<double>(a.fp.total()) / a.n, r.peak_bytes,
                fix(a.ns_per_particle_step(), 1).c_str(), fix(b.ns_per_particle_step(), 1).c_str(),
                fix(a.seconds / b.seconds, 2).c_str(), a.streamed, fix(a.bytes_per_second() / 1e9, 1).c_str(),
                fix(100 * a.bytes_per_second() / triad[0], 0).c_str(), fix(b.bytes_per_second() / 1e9, 1).c_str(),
                fix(100 * b.bytes_per_second() / triad[1], 0).c_str());
  }
  // Against the size before as well: where the blocks outgrow the caches the time steps up once, and O(N) means
  // flat from there on.
  std::printf("\nRelative to the smallest block (flat within 20 %%: O(N)), and to the block before it:\n\n");
  std::printf(
      "| N | ns / particle-step, 1 thread | 2 threads | containers per particle | against the block before, 1 thread | "
      "2 threads |\n|---|---|---|---|---|---|\n");
  // Row k against row `base`: time per particle-step on thread count ti, and containers per particle.
  auto time_ratio = [&](std::size_t k, std::size_t base, int ti) {
    return fix(rows[k].t[ti].ns_per_particle_step() / rows[base].t[ti].ns_per_particle_step(), 2);
  };
  auto memory = [&](std::size_t k) { return static_cast<double>(rows[k].t[0].fp.total()) / rows[k].t[0].n; };
  for (std::size_t k = 0; k < rows.size(); ++k)
    std::printf("| %d | %s | %s | %s | %s | %s |\n", rows[k].t[0].n, time_ratio(k, 0, 0).c_str(),
                time_ratio(k, 0, 1).c_str(), fix(memory(k) / memory(0), 2).c_str(),
                k == 0 ? "" : time_ratio(k, k - 1, 0).c_str(), k == 0 ? "" : time_ratio(k, k - 1, 1).c_str());
  std::printf("\n");
}

inline void section_scaling(const Options& opt) {
  std::vector<int> sizes = opt.quick ? std::vector<int>{1000, 10000} : std::vector<int>{1000, 10000, 100000, 1000000};
  if (opt.unbonded_scaling) {
    std::vector<ScalingRow> rows;
    progress("scaling\n");
    for (int n : sizes) rows.push_back(scaling_row<2>(n, opt.quick, opt));
    for (int n : sizes) rows.push_back(scaling_row<3>(n, opt.quick, opt));
    print_scaling_setup(opt);
    print_scaling_table(rows);
    print_scaling_relative(rows);
  }
  const std::vector<int> bonded_sizes =
      opt.quick ? std::vector<int>{10000, 100000} : std::vector<int>{10000, 100000, 1000000, opt.max_bonded};
  std::vector<BondedRow> bonded;
  for (int n : bonded_sizes) bonded.push_back(bonded_row(n, opt.quick, opt.reps));
  const double triad[2] = {triad_bytes_per_second(1), triad_bytes_per_second(2)};
  print_bonded_scaling(bonded, triad, opt.reps);
}

}  // namespace mc::bench
