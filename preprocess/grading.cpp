#include "preprocess/grading.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "engine/errors.hpp"

namespace mc {

namespace {

void check_sieves(const char* what, const std::vector<double>& sieves) {
  std::ostringstream m;
  if (sieves.size() < 2) {
    m << what << ": need at least two sieve sizes, got " << sieves.size();
    throw InputError(m.str());
  }
  for (std::size_t i = 0; i < sieves.size(); ++i)
    if (!(sieves[i] > 0) || !std::isfinite(sieves[i]) || (i > 0 && !(sieves[i] > sieves[i - 1]))) {
      m << what << ": sieve sizes must be positive, finite and increasing; sieve " << i + 1 << " is " << sieves[i];
      throw InputError(m.str());
    }
}

// A size in [lo, hi) with number density ∝ d^beta.
double power_law(double lo, double hi, double beta, double u) {
  if (std::abs(beta + 1) < 1e-12) return lo * std::pow(hi / lo, u);
  const double b1 = beta + 1, a = std::pow(lo, b1), b = std::pow(hi, b1);
  return std::pow(a + u * (b - a), 1 / b1);
}

}  // namespace

void check_grading(const Grading& g) {
  std::ostringstream m;
  if (g.ranges.empty()) throw InputError("grading: no size range");
  double sum = 0;
  for (std::size_t i = 0; i < g.ranges.size(); ++i) {
    const SizeRange& r = g.ranges[i];
    if (!(r.lo > 0 && r.hi > r.lo && std::isfinite(r.hi))) {
      m << "grading: size range " << i + 1 << " [" << r.lo << ", " << r.hi << ") must have 0 < lo < hi";
      throw InputError(m.str());
    }
    if (!(r.share >= 0 && std::isfinite(r.share))) {
      m << "grading: size range " << i + 1 << " has share " << r.share << ": must be non-negative";
      throw InputError(m.str());
    }
    sum += r.share;
    for (std::size_t j = 0; j < i; ++j)
      if (r.lo < g.ranges[j].hi && g.ranges[j].lo < r.hi) {
        m << "grading: size ranges " << j + 1 << " and " << i + 1 << " overlap";
        throw InputError(m.str());
      }
  }
  if (std::abs(sum - 1) > 1e-9) {
    m << "grading: the shares sum to " << sum << ", not 1";
    throw InputError(m.str());
  }
}

Grading tang_table_4_1(double mm) {
  return Grading{{{4 * mm, 8 * mm, 0.2}, {8 * mm, 16 * mm, 0.2}, {16 * mm, 32 * mm, 0.3}, {32 * mm, 64 * mm, 0.3}}};
}

double fuller_passing(double d, double d_max, double n) { return std::pow(d / d_max, n); }

Grading fuller_grading(const std::vector<double>& sieves, double n) {
  check_sieves("Fuller grading", sieves);
  if (!(n > 0) || !std::isfinite(n))
    throw InputError("Fuller grading: exponent n = " + std::to_string(n) + " must be positive");
  const double dmax = sieves.back(), total = 1 - fuller_passing(sieves.front(), dmax, n);
  Grading g;
  for (std::size_t i = 0; i + 1 < sieves.size(); ++i)
    g.ranges.push_back({sieves[i], sieves[i + 1],
                        (fuller_passing(sieves[i + 1], dmax, n) - fuller_passing(sieves[i], dmax, n)) / total});
  return g;
}

double walraven_passing(double r, double pk) {
  const double r2 = r * r, r4 = r2 * r2, r6 = r4 * r2, r8 = r4 * r4, r10 = r8 * r2;
  return pk * (1.455 * std::sqrt(r) - 0.5 * r2 + 0.036 * r4 + 0.006 * r6 + 0.002 * r8 + 0.001 * r10);
}

SectionGrading walraven_section(const std::vector<double>& sieves, double pk) {
  check_sieves("Walraven section grading", sieves);
  if (!(pk > 0 && pk < 1))
    throw InputError("Walraven section grading: volume fraction P_k = " + std::to_string(pk) + " must be in (0, 1)");
  const double dmax = sieves.back();
  SectionGrading s;
  for (std::size_t i = 0; i + 1 < sieves.size(); ++i) {
    const double a = walraven_passing(sieves[i] / dmax, pk), b = walraven_passing(sieves[i + 1] / dmax, pk);
    s.grading.ranges.push_back({sieves[i], sieves[i + 1], b - a});
    s.fraction += b - a;
  }
  for (auto& r : s.grading.ranges) r.share /= s.fraction;
  return s;
}

std::vector<SizedAggregate> fill_grading(const Grading& g, double target, int dim,
                                         const std::function<double(double)>& make, RandomStream& rng, SizeDraw draw,
                                         double fuller_n) {
  check_grading(g);
  if (!(target >= 0) || !std::isfinite(target))
    throw InputError("aggregate sizes: the target content must be non-negative");
  if (dim != 2 && dim != 3) throw InputError("aggregate sizes: dimension must be 2 or 3");
  std::vector<int> order(g.ranges.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return g.ranges[a].lo > g.ranges[b].lo; });
  std::vector<SizedAggregate> out;
  int made = 0;
  double carry = 0;  // content a coarser range could not take
  for (int k : order) {
    const SizeRange& r = g.ranges[k];
    const double want = r.share * target + carry;
    carry = 0;
    const std::size_t first = out.size();
    double have = 0;
    while (true) {
      const double u = rng.uniform();
      const double d =
          draw == SizeDraw::uniform ? r.lo + u * (r.hi - r.lo) : power_law(r.lo, r.hi, fuller_n - 1 - dim, u);
      const double c = make(d);
      if (!(c > 0) || !std::isfinite(c))
        throw InputError("aggregate sizes: an aggregate of size " + std::to_string(d) + " has no content");
      SizedAggregate a{made++, k, d, 1.0, c};
      if (have + c <= want) {
        out.push_back(a);
        have += c;
        continue;
      }
      const double rest = want - have;
      const double s = std::pow(rest / c, 1.0 / dim);
      if (s * d >= r.lo) {  // shrink the last one
        a.scale = s;
        a.size = s * d;
        a.content = rest;
        out.push_back(a);
        break;
      }
      // Grow the smallest of the range (the most room below hi), or carry the rest.
      SizedAggregate* small = nullptr;
      for (std::size_t i = first; i < out.size(); ++i)
        if (!small || out[i].size < small->size) small = &out[i];
      if (small) {
        const double grow = std::pow((small->content + rest) / small->content, 1.0 / dim);
        if (small->size * grow < r.hi) {
          small->scale *= grow;
          small->size *= grow;
          small->content += rest;
          break;
        }
        // Or all of the range's aggregates, by a common factor.
        double largest = 0;
        for (std::size_t i = first; i < out.size(); ++i) largest = std::max(largest, out[i].size);
        const double all = std::pow((have + rest) / have, 1.0 / dim);
        if (largest * all < r.hi) {
          for (std::size_t i = first; i < out.size(); ++i) {
            out[i].scale *= all;
            out[i].size *= all;
            out[i].content *= std::pow(all, dim);
          }
          break;
        }
      }
      carry = rest;
      break;
    }
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const SizedAggregate& a, const SizedAggregate& b) { return a.size > b.size; });
  return out;
}

std::vector<SizedAggregate> aggregate_sizes(const Grading& g, double fraction, double domain, int dim,
                                            double shape_factor, std::uint64_t seed, SizeDraw draw, double fuller_n) {
  if (!(fraction > 0 && fraction < 1))
    throw InputError("aggregate sizes: fraction " + std::to_string(fraction) + " must be in (0, 1)");
  if (!(domain > 0) || !(shape_factor > 0))
    throw InputError("aggregate sizes: domain content and shape factor must be positive");
  RandomStream rng(seed);
  return fill_grading(
      g, fraction * domain, dim, [&](double d) { return shape_factor * std::pow(d, dim); }, rng, draw, fuller_n);
}

}  // namespace mc
