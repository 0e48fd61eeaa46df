// Timing the parts of a rigid-cell step alone, for the family's benchmarks.
#pragma once
#include <algorithm>
#include <chrono>

namespace mc::bench {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The best of `repeats` timings of f (a noisy machine makes single timings long, never short).
template <typename F>
double best_of(int repeats, F&& f) {
  double best = 1e300;
  for (int i = 0; i < repeats; ++i) {
    const auto t0 = Clock::now();
    f();
    best = std::min(best, seconds_since(t0));
  }
  return best;
}

}  // namespace mc::bench
