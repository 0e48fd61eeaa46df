// Sums that must not depend on how their terms are split (engine/exact_sum.hpp): between threads, blocks or the
// processes of a split specimen. Each is the exact sum of its terms rounded once to the nearest double, so any
// order and any grouping give the same bits, and the value is the correctly rounded one.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "engine/exact_sum.hpp"
#include "engine/random_stream.hpp"

using mc::ExactSum;

namespace {

double exact(const std::vector<double>& terms) {
  ExactSum s;
  for (double x : terms) s.add(x);
  return s.value();
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

// Terms whose exact sums are known: cancellation that a running sum loses entirely, ties, subnormals, and ten
// times 0.1 (exactly 1.000000000000000055511…, which rounds to 1).
TEST_CASE("exact_sum_gives_the_correctly_rounded_total_of_its_terms") {
  CHECK(exact({1e100, 1.0, -1e100}) == 1.0);
  CHECK(exact({1e308, 1e308, -1e308}) == 1e308);  // the intermediate 2e308 overflows a double, not the sum
  CHECK(exact(std::vector<double>(10, 0.1)) == 1.0);
  CHECK(exact({1.0, std::ldexp(1.0, -53)}) == 1.0);  // a tie rounds to even
  CHECK(exact({1.0, std::ldexp(1.0, -53), std::ldexp(1.0, -1074)}) == std::nextafter(1.0, 2.0));  // above the tie
  const double tiny = std::numeric_limits<double>::denorm_min();
  CHECK(exact({tiny, tiny, tiny}) == 3 * tiny);
  CHECK(exact({-2.5, 0.5}) == -2.0);
  CHECK(same_bits(exact({}), 0.0));
  CHECK(std::isinf(exact({1.0, std::numeric_limits<double>::infinity()})));
  CHECK(std::isnan(exact({std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()})));
}

// 20 000 terms over 600 decades, both signs: summed in shuffled orders, and in parts merged in other groupings,
// the total has the same bits every time (a running sum in double differs between orders here).
TEST_CASE("exact_sum_does_not_depend_on_the_order_or_the_grouping_of_its_terms") {
  mc::RandomStream rng(3);
  std::vector<double> terms;
  for (int k = 0; k < 20000; ++k) {
    const double magnitude = std::pow(10.0, -300 + 600 * rng.uniform());
    terms.push_back(rng.uniform() < 0.5 ? -magnitude : magnitude);
  }
  const double reference = exact(terms);
  bool naive_differs = false;
  double naive_reference = 0;
  for (double x : terms) naive_reference += x;
  for (int round = 0; round < 5; ++round) {
    for (std::size_t k = terms.size() - 1; k > 0; --k)
      std::swap(terms[k], terms[static_cast<std::size_t>(rng.uniform() * static_cast<double>(k + 1)) % (k + 1)]);
    CHECK(same_bits(exact(terms), reference));
    double naive = 0;
    for (double x : terms) naive += x;
    naive_differs |= !same_bits(naive, naive_reference);
    // Split into 1 + round parts, summed apart and merged.
    const std::size_t parts = 1 + round;
    std::vector<ExactSum> part(parts);
    for (std::size_t k = 0; k < terms.size(); ++k) part[k % parts].add(terms[k]);
    ExactSum merged;
    for (std::size_t q = parts; q-- > 0;) merged += part[q];
    CHECK(same_bits(merged.value(), reference));
  }
  CHECK(naive_differs);  // the case is one where order matters to a running sum
}
