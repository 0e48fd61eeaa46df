// A small seeded random stream for the preprocessor: splitmix64 (a Weyl sequence through a 64-bit mixing
// function). Integer arithmetic only, so a seed gives the same numbers on every platform, compiler and standard
// library (std::uniform_real_distribution does not). Tang (4.3) uses a Lehmer generator; any good stream will do.
#pragma once
#include <cstdint>

namespace mc {

class RandomStream {
 public:
  explicit RandomStream(std::uint64_t seed) : s_(seed) {}

  std::uint64_t next() {
    std::uint64_t z = (s_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
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
