// doctest's Approx(x).epsilon(e) allows e (1 + max(|a|, |x|)): for a quantity far below 1 in SI units (a contact
// duration of 124 µs, a slip of 61 µm) that is an absolute tolerance of e, which says nothing. relative(x, e)
// allows e max(|a|, |x|), whatever the magnitude (and 0 == 0: doctest's test is strict, so the scale is the least
// positive double rather than zero).
#pragma once
#include <doctest/doctest.h>

#include <limits>

namespace mc::test {
inline doctest::Approx relative(double x, double e) {
  return doctest::Approx(x).epsilon(e).scale(std::numeric_limits<double>::min());
}
}  // namespace mc::test
