// A seeded random stream on splitmix64 (engine/random.hpp): the same numbers on every platform. The preprocessor
// (Tang (4.3) uses a Lehmer generator; any good stream will do) and the rigid cells' node placement draw from it.
#pragma once
#include <cstdint>

#include "engine/random.hpp"

namespace mc {

class RandomStream {
 public:
  explicit RandomStream(std::uint64_t seed) : s_(seed) {}

  std::uint64_t next() { return splitmix64(s_); }
  // Uniform in [0, 1), 53 random bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  // Uniform in [a, b): Tang (4.4), X' = a + (b − a) X.
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
  // Uniform integer in [0, n), n > 0 (multiply-shift: bias below n / 2⁶⁴).
  std::uint64_t below(std::uint64_t n) {
    return static_cast<std::uint64_t>((static_cast<unsigned __int128>(next()) * n) >> 64);
  }
  // A new stream, independent for all practical purposes, e.g. one per aggregate or per phase.
  RandomStream split() { return RandomStream(next() ^ 0x6a09e667f3bcc909ull); }

 private:
  std::uint64_t s_;
};

}  // namespace mc
