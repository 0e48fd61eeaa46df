#include "preprocess/heterogeneity.hpp"

#include <cmath>
#include <sstream>

#include "engine/errors.hpp"

namespace mc {

namespace {

double normal_cdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }
double normal_pdf(double x) { return std::exp(-0.5 * x * x) / std::sqrt(2 * M_PI); }

// The lowest mean / std allowed: Φ(−2.326) = 1 %, so at most 100 draws per value on average.
constexpr double kLowestMeanOverStd = -2.326;

}  // namespace

double mean(const Weibull& w) { return w.scale * std::tgamma(1 + 1 / w.shape); }

double variance(const Weibull& w) {
  const double g1 = std::tgamma(1 + 1 / w.shape), g2 = std::tgamma(1 + 2 / w.shape);
  return w.scale * w.scale * (g2 - g1 * g1);
}

double sample(const Weibull& w, RandomStream& rng) {
  return w.scale * std::pow(-std::log1p(-rng.uniform()), 1 / w.shape);
}

double mean(const TruncatedNormal& t) {
  if (t.std == 0) return t.mean;
  const double alpha = -t.mean / t.std;
  return t.mean + t.std * normal_pdf(alpha) / (1 - normal_cdf(alpha));
}

double sample(const TruncatedNormal& t, RandomStream& rng) {
  if (t.std == 0) return t.mean;
  while (true) {
    // Box–Muller: two uniforms give a standard normal deviate (the second of the pair is not kept, so each
    // value depends on a fixed number of draws from the stream).
    const double u1 = 1 - rng.uniform(), u2 = rng.uniform();  // u1 in (0, 1]
    const double z = std::sqrt(-2 * std::log(u1)) * std::cos(2 * M_PI * u2);
    const double x = t.mean + t.std * z;
    if (x > 0) return x;
  }
}

void check_distribution(const ParameterDistribution& d) {
  std::ostringstream m;
  switch (d.kind) {
    case ParameterDistribution::fixed:
      if (!std::isfinite(d.a)) {
        m << "fixed parameter value " << d.a << " must be finite";
        throw InputError(m.str());
      }
      return;
    case ParameterDistribution::weibull:
      if (!(d.a > 0 && std::isfinite(d.a) && d.b > 0 && std::isfinite(d.b))) {
        m << "Weibull distribution (8.4): scale = " << d.a << " and shape = " << d.b << " must both be positive";
        throw InputError(m.str());
      }
      return;
    case ParameterDistribution::truncated_normal:
      if (!(d.b >= 0 && std::isfinite(d.b) && std::isfinite(d.a))) {
        m << "truncated normal distribution: std = " << d.b << " must be non-negative and mean finite";
        throw InputError(m.str());
      }
      if (d.b == 0 ? !(d.a > 0) : !(d.a / d.b > kLowestMeanOverStd)) {
        m << "truncated normal distribution: mean = " << d.a << ", std = " << d.b
          << " leaves less than 1 % of the values positive (needs mean > " << kLowestMeanOverStd
          << " std); a positive parameter so skewed is better drawn from a Weibull distribution";
        throw InputError(m.str());
      }
      return;
  }
  throw InputError("unknown parameter distribution");
}

std::vector<double> draw_values(const ParameterDistribution& d, std::size_t n, std::uint64_t seed) {
  check_distribution(d);
  RandomStream rng(seed);
  std::vector<double> out(n);
  for (auto& x : out) {
    switch (d.kind) {
      case ParameterDistribution::fixed: x = d.a; break;
      case ParameterDistribution::weibull: x = sample(Weibull{d.a, d.b}, rng); break;
      case ParameterDistribution::truncated_normal: x = sample(TruncatedNormal{d.a, d.b}, rng); break;
    }
  }
  return out;
}

}  // namespace mc
