// A sum of doubles that does not depend on the order of its terms: each term is added exactly into a long
// fixed-point accumulator (every double is an integer multiple of 2^−1074), and the total is rounded once. Sums
// over particles or contacts then give the same bits however they are split between threads or processes
// (World::split), where a running sum in floating point would depend on the split.
#pragma once
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

namespace mc {

class ExactSum {
 public:
  // Limb k holds bits [32k, 32k + 32) of the total in units of 2^−1074; a double's 53-bit significand shifted to
  // its exponent spans at most three limbs. The largest double reaches bit 2098, limb 65, and the top limb takes
  // the carries and the sign.
  static constexpr int kLimbs = 67;

  void add(double x) {
    const auto bits = std::bit_cast<std::uint64_t>(x);
    if ((bits << 1) == 0) return;  // ±0: most contacts dissipate nothing in most steps
    const int exponent = static_cast<int>((bits >> 52) & 0x7ff);
    if (exponent == 0x7ff) {  // infinities and NaN: summed apart (their sum does not depend on the order either)
      special_ += x;
      return;
    }
    std::uint64_t m = bits & ((std::uint64_t(1) << 52) - 1);
    if (exponent > 0) m |= std::uint64_t(1) << 52;
    const int shift = exponent > 0 ? exponent - 1 : 0;  // x = m · 2^(shift − 1074)
    const unsigned __int128 wide = static_cast<unsigned __int128>(m) << (shift & 31);
    const int k = shift >> 5;
    const auto lo = static_cast<std::int64_t>(wide & 0xffffffffu),
               mid = static_cast<std::int64_t>((wide >> 32) & 0xffffffffu), hi = static_cast<std::int64_t>(wide >> 64);
    // Negated without a branch (the signs of the terms come in no pattern): (v ^ s) − s is −v when s = −1.
    const std::int64_t sign = -static_cast<std::int64_t>(bits >> 63);
    limb_[k] += (lo ^ sign) - sign;
    limb_[k + 1] += (mid ^ sign) - sign;
    limb_[k + 2] += (hi ^ sign) - sign;
    // Each limb takes under 2^32 per term: carried before 2^30 terms can overflow its 63 bits.
    if (++terms_ == (std::int64_t(1) << 30)) carry();
  }

  ExactSum& operator+=(const ExactSum& o) {
    carry();
    ExactSum other = o;
    other.carry();
    for (int k = 0; k < kLimbs; ++k) limb_[k] += other.limb_[k];
    special_ += o.special_;
    terms_ = 1;
    return *this;
  }

  // The total rounded to the nearest double.
  double value() const {
    ExactSum s = *this;
    s.carry();
    const bool negative = s.limb_[kLimbs - 1] < 0;
    if (negative) {
      for (auto& l : s.limb_) l = -l;
      s.carry();
    }
    int top = kLimbs - 1;
    while (top >= 0 && s.limb_[top] == 0) --top;
    if (top < 0) return special_ + 0.0;
    // The top three limbs hold at least 65 significant bits; a lower non-zero limb sets the lowest bit (sticky),
    // which lies well below the rounding position, so one conversion rounds the exact total correctly.
    const int base = top >= 2 ? top - 2 : 0;
    unsigned __int128 u = 0;
    for (int k = top; k >= base; --k) u = (u << 32) | static_cast<std::uint32_t>(s.limb_[k]);
    for (int k = 0; k < base; ++k)
      if (s.limb_[k] != 0) u |= 1;
    const double magnitude = std::ldexp(static_cast<double>(u), 32 * base - 1074);
    return (negative ? -magnitude : magnitude) + special_;
  }

  // The limbs and the non-finite part, to be summed across processes (integers add exactly in any order).
  std::array<std::int64_t, kLimbs>& limbs() {
    carry();
    return limb_;
  }
  double& special() { return special_; }

 private:
  // Brings every limb but the top into [0, 2^32), carrying upwards.
  void carry() {
    for (int k = 0; k + 1 < kLimbs; ++k) {
      const std::int64_t c = limb_[k] >> 32;  // floor division (C++20: arithmetic shift)
      limb_[k] -= c * (std::int64_t(1) << 32);
      limb_[k + 1] += c;
    }
    terms_ = 0;
  }

  std::array<std::int64_t, kLimbs> limb_{};
  double special_ = 0;
  std::int64_t terms_ = 0;
};

}  // namespace mc
