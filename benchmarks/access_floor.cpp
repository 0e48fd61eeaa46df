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
//   (force, moment on B, live byte); the B of the pair 2 × 8 ahead is asked for early, as the lanes do, and the
//   history of the pair 16 ahead, which the engine does not;
// - law of motion: per particle its sums, its far slots through its gather list, its fixity, velocity, spin, mass,
//   inertia, position, position at the last rebuild and radius read, and its force, velocity, spin and position
//   written;
// - every 10th step the timestep estimate: per pair its properties, A's and B's position, radius and stiffness
//   factor, into two transient sums per particle or its slot; per particle its sums, far slots, mass and inertia.
#include <omp.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "benchmarks/bonded_block.hpp"
#include "benchmarks/run_timing.hpp"
#include "benchmarks/throughput_world.hpp"
#include "engine/parallel.hpp"

using namespace mc;
using namespace mc::bench;

namespace {

// Zero at run time: the values stay as they were, and the compiler must still load and store each one.
volatile double g_zero = 0.0;
// Where the passes' reductions go, so that the compiler keeps them.
volatile double g_sink = 0.0;

struct Properties {
  double stiffness;
  float tensile, shear;
};

// The step's arrays, sized and linked as the engine's are for the same pairs.
class MemoryWalk {
 public:
  MemoryWalk(const Particles<3>& p, const std::vector<Pair>& pairs) : pairs_(pairs) {
    n_ = p.size();
    x_ = p.x, v_ = p.v, w_ = p.w, x0_ = p.x;
    f_.assign(n_, Vec<3>::Zero());
    m_.assign(n_, Vec<3>::Zero());
    radius_ = p.radius, mass_ = p.mass, inertia_ = p.inertia, stiffness_ = p.stiffness, fix_ = p.fix;
    history_.assign(pairs.size(), {});
    properties_.assign(pairs.size(), {1.0, 1e6f, 1e6f});
    // As the engine: a pair is far when B is beyond A's group; the far pairs take slots in pair order, and each
    // particle gathers those whose B it is.
    std::vector<int> per_b(n_ + 1, 0);
    block_begin_.assign(n_ / kGroup + 2, pairs.size());
    block_far_.assign(block_begin_.size(), 0);
    for (std::size_t c = pairs.size(); c-- > 0;) block_begin_[pairs[c][0] / kGroup] = c;
    for (std::size_t g = block_begin_.size() - 1; g-- > 0;)
      block_begin_[g] = std::min(block_begin_[g], block_begin_[g + 1]);
    for (std::size_t g = 0; g + 1 < block_begin_.size(); ++g) {
      block_far_[g] = slots_;
      for (std::size_t c = block_begin_[g]; c < block_begin_[g + 1]; ++c)
        if (far(g, pairs[c][1])) ++slots_, ++per_b[pairs[c][1] + 1];
    }
    for (int i = 0; i < n_; ++i) per_b[i + 1] += per_b[i];
    gather_start_ = per_b;
    gather_.assign(slots_, 0);
    for (std::size_t g = 0, slot = 0; g + 1 < block_begin_.size(); ++g)
      for (std::size_t c = block_begin_[g]; c < block_begin_[g + 1]; ++c)
        if (far(g, pairs[c][1])) gather_[per_b[pairs[c][1]]++] = static_cast<int>(slot++);
    sf_.assign(slots_, Vec<3>::Zero());
    smb_.assign(slots_, Vec<3>::Zero());
    live_.assign(slots_, 1);
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
  std::size_t far_slots() const { return slots_; }

 private:
  void prefetch_history(std::size_t c) const {
    const char* h = reinterpret_cast<const char*>(&history_[c]);
    __builtin_prefetch(h), __builtin_prefetch(h + 64);
  }
  static bool far(std::size_t group, int b) { return static_cast<std::size_t>(b) / kGroup != group; }

  void force_pass() {
    const double z = g_zero;
    const std::size_t np = pairs_.size();
    for (std::size_t g = 0; g + 1 < block_begin_.size(); ++g) {
      const int first = static_cast<int>(g) * kGroup, last = std::min(n_, first + kGroup);
      for (int i = first; i < last; ++i) f_[i].setZero(), m_[i].setZero();
      std::size_t slot = block_far_[g];
      for (std::size_t c = block_begin_[g]; c < block_begin_[g + 1]; ++c) {
        if (c + 16 < np) {
          const int ahead = pairs_[c + 16][1];
          __builtin_prefetch(&x_[ahead]), __builtin_prefetch(&v_[ahead]), __builtin_prefetch(&w_[ahead]);
          __builtin_prefetch(&radius_[ahead]), __builtin_prefetch(&stiffness_[ahead]);
        }
        // A walk without arithmetic issues its loads faster than the hardware's prefetchers keep up with on the
        // history: at 10⁶ its force pass took 87–91 ns per particle-step without this request, 74–75 with it. The
        // engine's lanes asking for the same gained nothing measurable.
        if (c + 16 < np) prefetch_history(c + 16);
        const auto [i, j] = pairs_[c];
        const Properties& q = properties_[c];
        // Summed as a tree, so that the walk waits on its loads and not on a chain of adds.
        auto& h = history_[c];
        const double hs = ((h[0] + h[1]) + (h[2] + h[3])) + ((h[4] + h[5]) + (h[6] + h[7])) + ((h[8] + h[9]) + h[10]);
        const double s = ((radius_[i] + radius_[j]) + (stiffness_[i] + stiffness_[j])) +
                         ((q.stiffness + (q.tensile + q.shear)) + hs) +
                         ((x_[j] - x_[i]) + (v_[j] - v_[i]) + (w_[j] + w_[i])).sum();
        for (double& hk : h) hk += z * s;
        const Vec<3> r = Vec<3>::Constant(z * s);
        f_[i] -= r, m_[i] += r;
        if (!far(g, j)) {
          f_[j] += r, m_[j] += r;
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
    for (int i = 0; i < n_; ++i) {
      Vec<3> f = f_[i], m = m_[i];
      for (int k = gather_start_[i]; k < gather_start_[i + 1]; ++k) {
        const int slot = gather_[k];
        if (!live_[slot]) continue;
        f += sf_[slot], m += smb_[slot];
      }
      f_[i] = f;
      const double s = f.sum() + m.sum() + mass_[i] + inertia_[i] + radius_[i] + fix_[i];
      v_[i] += Vec<3>::Constant(z * s);
      w_[i] += Vec<3>::Constant(z * s);
      x_[i] += z * v_[i];
      sink += (x_[i] - x0_[i]).squaredNorm() + w_[i].sum();
    }
    g_sink = g_sink + sink;
  }

  void timestep_pass() {
    std::vector<double> sums(2 * static_cast<std::size_t>(n_), 0.0);
    for (std::size_t g = 0, slot = 0; g + 1 < block_begin_.size(); ++g)
      for (std::size_t c = block_begin_[g]; c < block_begin_[g + 1]; ++c) {
        const auto [i, j] = pairs_[c];
        const double k =
            properties_[c].stiffness + radius_[i] + radius_[j] + stiffness_[i] + stiffness_[j] + (x_[j] - x_[i]).sum();
        sums[2 * i] += k, sums[2 * i + 1] += k;
        if (!far(g, j)) {
          sums[2 * j] += k, sums[2 * j + 1] += k;
        } else {
          sf_[slot][0] = k, smb_[slot][0] = k, live_[slot] = 1;
          ++slot;
        }
      }
    double tmin = 1e300;
    for (int i = 0; i < n_; ++i) {
      double kt = sums[2 * i], kr = sums[2 * i + 1];
      for (int k = gather_start_[i]; k < gather_start_[i + 1]; ++k) kt += sf_[gather_[k]][0], kr += smb_[gather_[k]][0];
      tmin = std::min(tmin, mass_[i] / (kt + 1) + inertia_[i] / (kr + 1));
    }
    g_sink = g_sink + tmin;
  }

  int n_ = 0;
  const std::vector<Pair>& pairs_;
  std::vector<Vec<3>> x_, v_, w_, x0_, f_, m_, sf_, smb_;
  std::vector<double> radius_, mass_, inertia_, stiffness_;
  std::vector<FixMask> fix_;
  std::vector<std::array<double, 11>> history_;
  std::vector<Properties> properties_;
  std::vector<int> gather_start_, gather_;
  std::vector<std::uint8_t> live_;
  std::vector<std::size_t> block_begin_, block_far_;  // per group: its first pair, its first far slot
  std::size_t slots_ = 0;
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

// The value of `--max` or `--reps`; any other argument, or a value out of range, stops the run with a message.
struct Arguments {
  int max_n = 10000000, reps = 3;
};

Arguments read_arguments(int argc, char** argv) {
  Arguments a;
  for (int k = 1; k < argc; k += 2) {
    const std::string name = argv[k];
    int* target = name == "--max" ? &a.max_n : name == "--reps" ? &a.reps : nullptr;
    const long lo = name == "--max" ? 10000 : 1, hi = name == "--max" ? 20000000 : 100;
    char* rest = nullptr;
    const long v = k + 1 < argc ? std::strtol(argv[k + 1], &rest, 10) : 0;
    if (!target || k + 1 >= argc || *rest != '\0' || v < lo || v > hi) {
      std::fprintf(stderr,
                   "access_floor: %s %s: allowed are --max N (10000 to 20000000 particles) and --reps N (1 to 100)\n",
                   argv[k], k + 1 < argc ? argv[k + 1] : "(no value)");
      std::exit(2);
    }
    *target = static_cast<int>(v);
  }
  return a;
}

}  // namespace

int main(int argc, char** argv) {
  const Arguments args = read_arguments(argc, argv);
  const int max_n = args.max_n, reps = args.reps;
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
