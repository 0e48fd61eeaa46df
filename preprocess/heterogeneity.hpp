// Heterogeneity of the micro-parameters (Tang 2013 §8.1.2): a particle or bond parameter of a phase drawn, per
// particle or bond, from a Weibull distribution (8.4) or from a normal truncated to positive values. Reproducible:
// the same seed gives the same values in the same order on every platform.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/random_stream.hpp"

namespace mc {

// Tang (8.4): f(x; λ, k) = (k/λ) (x/λ)^(k−1) exp(−(x/λ)^k), x ≥ 0; scale λ > 0 (near the mean), shape k > 0 (the
// homogeneity index: the larger, the narrower).
struct Weibull {
  double scale = 1;  // λ
  double shape = 1;  // k
};
double mean(const Weibull& w);      // λ Γ(1 + 1/k)
double variance(const Weibull& w);  // λ² [Γ(1 + 2/k) − Γ²(1 + 1/k)]
// Inverse transform: x = λ (−ln(1 − u))^(1/k), u uniform in [0, 1).
double sample(const Weibull& w, RandomStream& rng);

// A normal N(mean, std²) with the values ≤ 0 left out (redrawn). `mean` and `std` are those of the normal before
// truncation; a parameter must be positive, so at least 1 % of it must lie above 0 (mean > −2.326 std).
struct TruncatedNormal {
  double mean = 1;
  double std = 0;
};
// μ + σ φ(α) / (1 − Φ(α)) with α = −μ/σ: the mean of what is drawn.
double mean(const TruncatedNormal& t);
// Normal deviates by the Box–Muller transform, redrawn while ≤ 0. std = 0 gives `mean` itself.
double sample(const TruncatedNormal& t, RandomStream& rng);

// How a parameter of a phase varies: fixed (a), Weibull (λ = a, k = b) or truncated normal (mean a, std b).
struct ParameterDistribution {
  enum Kind { fixed, weibull, truncated_normal } kind = fixed;
  double a = 0, b = 0;
};

// Throws InputError for parameters that define no positive distribution (λ, k ≤ 0; std < 0; mean too far below
// zero; a fixed value that is not finite).
void check_distribution(const ParameterDistribution& d);

// n values, the i-th for the i-th particle or bond, from the stream `seed`.
std::vector<double> draw_values(const ParameterDistribution& d, std::size_t n, std::uint64_t seed);

}  // namespace mc
