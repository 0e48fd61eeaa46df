// Random numbers that depend on the seed alone: splitmix64 (a Weyl sequence through a 64-bit mixing function).
// Integer arithmetic only, so a seed gives the same numbers on every platform, compiler and standard library
// (std::uniform_real_distribution does not). The engine draws bond strengths per pair with it; the
// preprocessor's RandomStream and the tests use the same generator.
#pragma once
#include <array>
#include <cmath>
#include <cstdint>

#include "engine/keys.hpp"  // Scatter

namespace mc {

// One step of splitmix64: advances `state` and returns the next 64 random bits.
inline std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// Random numbers for one pair, from the seed and the pair alone: a bond's strengths do not depend on the order
// in which bonds are installed, nor on the thread count.
struct PairRandom {
  std::uint64_t state;
  PairRandom(std::uint64_t seed, const std::array<int, 2>& p)
      : state(seed ^ (static_cast<std::uint64_t>(p[0]) * 0x9e3779b97f4a7c15ull) ^
              (static_cast<std::uint64_t>(p[1]) * 0xc2b2ae3d27d4eb4full)) {}
  double uniform() {  // in (0, 1): both logarithms below stay finite
    return (static_cast<double>(splitmix64(state) >> 11) + 0.5) * 0x1.0p-53;
  }
  // Normal(mean, std) truncated to positive values by redrawing (Box–Muller).
  double operator()(double mean, double std) {
    if (std == 0) return mean;
    for (;;) {
      const double x = mean + std * std::sqrt(-2.0 * std::log(uniform())) * std::cos(2.0 * M_PI * uniform());
      if (x > 0) return x;
    }
  }
  // With a Weibull shape k > 0: Weibull(scale λ = a, shape k), Tang (8.4), by inverse transform; else
  // Normal(a, b) truncated to positive values.
  double operator()(double a, double b, double weibull_shape) {
    if (weibull_shape > 0) return a * std::pow(-std::log(uniform()), 1.0 / weibull_shape);
    return (*this)(a, b);
  }
  double operator()(const Scatter& s) { return (*this)(s.mean, s.std, s.weibull_shape); }
};

}  // namespace mc
