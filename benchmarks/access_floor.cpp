// What the memory alone costs the parallel-bonded block's step. The arrays a step of `throughput`'s bonded block
// reads and writes, at the engine's sizes and in its order, are walked with the arithmetic taken out: every value
// read is added into a sum and every value written gets that sum times a zero the compiler cannot see. What this
// costs per particle-step is what the memory alone asks of the step for this access pattern on this machine (not a
// bound: a walk asking for more ahead might run faster still). Set beside the engine's own step on the same block,
// timed in turns, it says how much of the memory's extra time beyond the caches the engine hides behind its
// arithmetic (README, Throughput, "What the memory alone costs").
//   build/benchmarks/access_floor [--max N] [--reps N]
// The walk, as the engine's step (ContactSet::compute, World::move_particles, World::critical_timestep):
// - force pass: the pairs sorted by A in blocks of kGroup particles; a block zeroes its group's sums, then each pair
//   reads A's and B's position, velocity, spin, radius and stiffness factor, its 16 B of properties, reads and
//   writes its 88 B of history, adds to A's sums, and to B's when B is of the block's group, else writes its slot
//   (force, moment on B, live byte); the B of the pair 16 ahead is asked for early
//   (Particles::prefetch_contact_fields), as 8-wide lanes do, and the history of the same pair, which the engine
//   does not;
// - law of motion: per particle its sums, its far slots through its gather list, its fixity, velocity, spin, mass,
//   inertia, position, position at the last rebuild and radius read, and its force, velocity, spin and position
//   written;
// - every 10th step the timestep estimate: per pair its properties, A's and B's position, radius and stiffness
//   factor, into two sums per particle (zeroed by its block) or its slot; per particle its sums, far slots, mass and
//   inertia.
#include <omp.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <vector>

#include "benchmarks/bonded_block.hpp"
#include "benchmarks/options.hpp"
#include "benchmarks/run_timing.hpp"
#include "benchmarks/throughput_world.hpp"
#include "engine/pair_blocks.hpp"
#include "engine/parallel.hpp"

using namespace mc;
using namespace mc::bench;

namespace {

// Zero at run time: the values stay as they were, and the compiler must still load and store each one.
volatile double g_zero = 0.0;
// Where the passes' reductions go, so that the compiler keeps them.
volatile double g_sink = 0.0;

// The step's arrays, sized and linked as the engine's are for the same pairs: the particles' own arrays, the parallel
// bond's history and properties, the blocks of the force pass (PairBlocks) and the far slots with their gather lists.
class MemoryWalk {
 public:
  using History = ParallelBond::History<3>;
  using Properties = ParallelBond::Properties<3>;

  MemoryWalk(const Particles<3>& p, const std::vector<Pair>& pairs)
      : p_(p), pairs_(pairs), x0_(p.x), history_(pairs.size()), properties_(pairs.size(), Properties{1.0, 1e6f, 1e6f}) {
    const int n = p.size();
    m_.assign(n, Vec<3>::Zero());
    std::vector<int> groups;
    for (int i = 0; i < n; i += kGroup) groups.push_back(i);
    groups.push_back(n);
    blocks_.build(pairs, groups);
    // Each particle's far slots as B, in slot order (World::relink).
    const std::vector<std::size_t> far = blocks_.far_pairs(pairs);
    gather_start_.assign(n + 1, 0);
    for (std::size_t c : far) ++gather_start_[pairs[c][1] + 1];
    for (int i = 0; i < n; ++i) gather_start_[i + 1] += gather_start_[i];
    gather_.resize(far.size());
    std::vector<int> fill(gather_start_.begin(), gather_start_.end() - 1);
    for (std::size_t k = 0; k < far.size(); ++k) gather_[fill[pairs[far[k]][1]]++] = static_cast<int>(k);
    sf_.assign(far.size(), Vec<3>::Zero());
    smb_.assign(far.size(), Vec<3>::Zero());
    live_.assign(far.size(), 1);
    estimate_sums_.resize(2 * static_cast<std::size_t>(n));
  }

  // One step, each part's wall time added to `seconds` (force pass, law of motion, timestep estimate).
  void step(bool estimate, std::array<double, 3>& seconds) {
    const auto t0 = Clock::now();
    force_pass();
    const auto t1 = Clock::now();
    law_of_motion();
    const auto t2 = Clock::now();
    if (estimate) timestep_pass();
    const auto t3 = Clock::now();
    seconds[0] += std::chrono::duration<double>(t1 - t0).count();
    seconds[1] += std::chrono::duration<double>(t2 - t1).count();
    seconds[2] += std::chrono::duration<double>(t3 - t2).count();
  }
  std::size_t far_slots() const { return blocks_.far_count(); }

 private:
  void force_pass() {
    const double z = g_zero;
    const std::size_t np = pairs_.size();
    for (int k = 0; k < blocks_.count(); ++k) {
      const int near_end = blocks_.near_end[k];
      for (int i = blocks_.group_first(k); i < near_end; ++i) p_.f[i].setZero(), m_[i].setZero();
      std::size_t slot = blocks_.far[k];
      for (std::size_t c = blocks_.first[k]; c < blocks_.first[k + 1]; ++c) {
        if (c + 16 < np) {
          p_.prefetch_contact_fields(pairs_[c + 16][1]);
          // A walk without arithmetic issues its loads faster than the hardware's prefetchers keep up with on the
          // history: at 10⁶ its force pass took 87–91 ns per particle-step without this request, 74–75 with it.
          // The engine's lanes asking for the same gained nothing measurable.
          const char* ahead = reinterpret_cast<const char*>(&history_[c + 16]);
          __builtin_prefetch(ahead), __builtin_prefetch(ahead + 64);
        }
        const auto [i, j] = pairs_[c];
        const Properties& q = properties_[c];
        History& h = history_[c];
        // Summed as a tree, so that the walk waits on its loads and not on a chain of adds.
        const double s =
            ((p_.radius[i] + p_.radius[j]) + (p_.stiffness[i] + p_.stiffness[j])) +
            ((q.stiffness + (q.tensile + q.shear)) + (h.bond_fn + h.bond_mn)) +
            ((h.fs + h.bond_fs + h.bond_ms) + (p_.x[j] - p_.x[i]) + (p_.v[j] - p_.v[i]) + (p_.w[j] + p_.w[i])).sum();
        const Vec<3> r = Vec<3>::Constant(z * s);
        h.fs += r, h.bond_fs += r, h.bond_ms += r, h.bond_fn += z * s, h.bond_mn += z * s;
        p_.f[i] -= r, m_[i] += r;
        if (j < near_end) {
          p_.f[j] += r, m_[j] += r;
        } else {
          sf_[slot] = r, smb_[slot] = r, live_[slot] = 1;
          ++slot;
        }
      }
    }
  }

  void law_of_motion() {
    const double z = g_zero;
    double sink = 0;
    for (int i = 0; i < p_.size(); ++i) {
      Vec<3> f = p_.f[i], m = m_[i];
      for (int k = gather_start_[i]; k < gather_start_[i + 1]; ++k) {
        const int slot = gather_[k];
        if (!live_[slot]) continue;
        f += sf_[slot], m += smb_[slot];
      }
      p_.f[i] = f;
      const double s = f.sum() + m.sum() + p_.mass[i] + p_.inertia[i] + p_.radius[i] + p_.fix[i];
      p_.v[i] += Vec<3>::Constant(z * s);
      p_.w[i] += Vec<3>::Constant(z * s);
      p_.x[i] += z * p_.v[i];
      sink += (p_.x[i] - x0_[i]).squaredNorm() + p_.w[i].sum();
    }
    g_sink = g_sink + sink;
  }

  void timestep_pass() {
    const int n = p_.size();
    std::vector<double>& sums = estimate_sums_;
    for (int k = 0; k < blocks_.count(); ++k) {
      for (int i = blocks_.group_first(k); i < blocks_.near_end[k]; ++i) sums[2 * i] = sums[2 * i + 1] = 0;
      std::size_t slot = blocks_.far[k];
      for (std::size_t c = blocks_.first[k]; c < blocks_.first[k + 1]; ++c) {
        const auto [i, j] = pairs_[c];
        const double kc = properties_[c].stiffness + p_.radius[i] + p_.radius[j] + p_.stiffness[i] + p_.stiffness[j] +
                          (p_.x[j] - p_.x[i]).sum();
        sums[2 * i] += kc, sums[2 * i + 1] += kc;
        if (j < blocks_.near_end[k]) {
          sums[2 * j] += kc, sums[2 * j + 1] += kc;
        } else {
          sf_[slot][0] = kc, smb_[slot][0] = kc, live_[slot] = 1;
          ++slot;
        }
      }
    }
    double tmin = 1e300;
    for (int i = 0; i < n; ++i) {
      double kt = sums[2 * i], kr = sums[2 * i + 1];
      for (int k = gather_start_[i]; k < gather_start_[i + 1]; ++k) kt += sf_[gather_[k]][0], kr += smb_[gather_[k]][0];
      tmin = std::min(tmin, p_.mass[i] / (kt + 1) + p_.inertia[i] / (kr + 1));
    }
    g_sink = g_sink + tmin;
  }

  Particles<3> p_;                         // a copy: the walk's sums and moves leave the engine's world as it was
  const std::vector<Pair> pairs_;          // a copy: a rebuild of the engine's lists would not reach the walk's blocks
  std::vector<Vec<3>> x0_, m_, sf_, smb_;  // positions at the last rebuild, moment sums, far slots
  std::vector<History> history_;
  std::vector<Properties> properties_;
  PairBlocks blocks_;
  std::vector<int> gather_start_, gather_;
  std::vector<std::uint8_t> live_;
  // The estimate's two sums per particle, kept between passes as the engine keeps its slots: a vector made in each
  // pass would add the first touch of fresh pages to the walk.
  std::vector<double> estimate_sums_;
};

// ns per particle-step of the walk's parts, and their sum last; the estimate runs every 10th step, as the engine's.
std::array<double, 4> walk_ns(MemoryWalk& mw, int n, int steps) {
  std::array<double, 3> seconds{};
  for (int s = 0; s < 5; ++s) mw.step(s % 10 == 0, seconds);
  seconds = {};
  for (int s = 0; s < steps; ++s) mw.step(s % 10 == 0, seconds);
  const double per = 1e9 / (static_cast<double>(n) * steps);
  return {seconds[0] * per, seconds[1] * per, seconds[2] * per, (seconds[0] + seconds[1] + seconds[2]) * per};
}

}  // namespace

int main(int argc, char** argv) {
  int max_n = 10000000, reps = 3;
  CLI::App app{"access_floor: the bonded block's step against a walk of its memory accesses alone (one thread)"};
  app.add_option("--max", max_n, "the largest block, particles (blocks of 10^4, 10^5, ... up to it)")
      ->check(CLI::Range(10000, 20000000));
  app.add_option("--reps", reps, "timed windows of the engine and of the walk, in turns; the best of each kept")
      ->check(CLI::Range(1, 100));
  if (const auto code = read_options(app, argc, argv, "access_floor")) return *code;
  omp_set_num_threads(1);
  std::printf(
      "| N | far slots / particle | engine, ns / particle-step | walk alone | walk: force pass / law of motion / "
      "estimate | walk / engine | engine − engine at 10⁴ | walk − walk at 10⁴ |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  double engine0 = 0, walk0 = 0;
  for (int target = 10000; target <= max_n; target *= 10) {
    World<3> w = bonded_block(target);
    const int n = w.particles.size();
    const int steps = std::max(20, static_cast<int>(2e7 / n));
    MemoryWalk mw(w.particles, w.sets[0]->pairs());
    double engine = kInf;
    std::array<double, 4> walk{kInf, kInf, kInf, kInf};
    for (int r = 0; r < reps; ++r) {  // in turns, the best of each kept
      engine = std::min(engine, time_steps(w, r == 0 ? 5 : 0, steps).ns_per_particle_step());
      const std::array<double, 4> t = walk_ns(mw, n, steps);
      if (t[3] < walk[3]) walk = t;
    }
    if (target == 10000) engine0 = engine, walk0 = walk[3];
    std::printf("| %d | %.2f | %.1f | %.1f | %.1f / %.1f / %.1f | %.2f | %+.1f | %+.1f |\n", n,
                static_cast<double>(mw.far_slots()) / n, engine, walk[3], walk[0], walk[1], walk[2], walk[3] / engine,
                engine - engine0, walk[3] - walk0);
    std::fflush(stdout);
  }
}
