#include "rigid_cell/grafted_distribution.hpp"

#include <cmath>
#include <functional>
#include <sstream>

#include "engine/errors.hpp"

namespace mc::rigid_cell {

namespace {

const double kSqrt2 = std::sqrt(2.0), kSqrt2Pi = std::sqrt(2 * M_PI);

double upper_normal(double z) { return 0.5 * std::erfc(z / kSqrt2); }  // 1 − Φ(z), accurate where it is tiny
double normal_density(double z) { return std::exp(-0.5 * z * z) / kSqrt2Pi; }

// Acklam's rational approximation of Φ⁻¹ (relative error below 1.2e-9), for p ≤ 1/2.
double acklam_lower(double p) {
  static constexpr double a[] = {-3.969683028665376e+01, 2.209460984245205e+02,  -2.759285104469687e+02,
                                 1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
  static constexpr double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                                 6.680131188771972e+01, -1.328068155288572e+01};
  static constexpr double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                                 -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
  static constexpr double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                                 3.754408661907416e+00};
  if (p < 0.02425) {
    const double q = std::sqrt(-2 * std::log(p));
    return (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
           ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  }
  const double q = p - 0.5, r = q * q;
  return (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
         (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1);
}

// The root of an increasing f in (lo, hi), f(lo) < 0 < f(hi), by bisection down to adjacent doubles: a few hundred
// evaluations of closed forms, the same bits everywhere.
double bisect(const std::function<double(double)>& f, double lo, double hi) {
  for (;;) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) return mid;
    (f(mid) < 0 ? lo : hi) = mid;
  }
}

// The lower incomplete gamma function γ(a, x) = ∫₀ˣ t^(a−1) e^(−t) dt by its series
// x^a e^(−x) Σ xⁿ / (a (a+1) … (a+n)), which converges fast for the x ≤ 0.11 of a tail grafted at P_gr ≤ 0.1.
double lower_gamma(double a, double x) {
  double term = 1 / a, sum = term;
  for (int n = 1; term > 1e-17 * sum; ++n) sum += term *= x / (a + n);
  return std::pow(x, a) * std::exp(-x) * sum;
}

// The grafted distribution whose Gaussian core has mean 1 and standard deviation cv (before it is scaled to mean
// 1): where the graft lies, and the distribution's mean and standard deviation.
struct Unscaled {
  double z_gr, graft, scale, rf, mean, deviation;
};

Unscaled unscaled(double cv, const WeibullTail& t) {
  const double m = t.modulus, q = -std::log1p(-t.probability);  // q = (x_gr/s₁)^m
  // The densities meet at x_gr: the Weibull's (m/x_gr) q (1 − P_gr) is r_f φ(z)/δ_G with
  // r_f = (1 − P_gr)/(1 − Φ(z)), z = (x_gr − μ_G)/δ_G; so m q cv = (1 + cv z) φ(z)/(1 − Φ(z)), whose right side
  // rises from 0 at x_gr = 0 (z = −1/cv) without bound.
  const double z =
      bisect([&](double z) { return (1 + cv * z) * normal_density(z) / upper_normal(z) - m * q * cv; }, -1 / cv, 25.0);
  Unscaled u{z, 1 + cv * z, 0, 0, 0, 0};
  u.scale = u.graft / std::pow(q, 1 / m);
  u.rf = (1 - t.probability) / upper_normal(z);
  // Moments: of the tail, s₁ᵏ γ(1 + k/m, q); of the core above z, for X = 1 + cv Z,
  // r_f [(1 − Φ) + cv φ] and r_f [(1 + cv²)(1 − Φ) + (2 cv + cv² z) φ].
  const double Q = upper_normal(z), phi = normal_density(z);
  const double m1 = u.scale * lower_gamma(1 + 1 / m, q) + u.rf * (Q + cv * phi);
  const double m2 =
      u.scale * u.scale * lower_gamma(1 + 2 / m, q) + u.rf * ((1 + cv * cv) * Q + (2 * cv + cv * cv * z) * phi);
  u.mean = m1;
  u.deviation = std::sqrt(m2 - m1 * m1);
  return u;
}

double relative_deviation(double cv, const WeibullTail& t) {
  const Unscaled u = unscaled(cv, t);
  return u.deviation / u.mean;
}

}  // namespace

double normal_cdf(double z) { return 0.5 * std::erfc(-z / kSqrt2); }

double normal_quantile(double p) {
  if (p > 0.5) return -normal_quantile(1 - p);
  const double x = acklam_lower(p);
  const double u = (normal_cdf(x) - p) * kSqrt2Pi * std::exp(0.5 * x * x);
  return x - u / (1 + 0.5 * x * u);  // one Halley step: to round-off
}

// The core's coefficient of variation δ_G/μ_G is solved for first: the grafted shape depends on it alone, and
// the distribution's own coefficient of variation rises with it (from what the tail alone gives at δ_G → 0).
// Then everything is scaled to mean 1. For the thesis's deviation 0.25 with m = 24, P_gr = 10⁻³: μ_G = 0.9963,
// δ_G = 0.2548, x_gr = 0.356 (z_gr = −2.51), r_f = 1.0051.
GraftedWeibullGauss::GraftedWeibullGauss(double deviation, const WeibullTail& tail) : tail_(tail) {
  constexpr double kLeast = 1e-6, kMost = 2;  // the core's cv searched
  const double lowest = relative_deviation(kLeast, tail), highest = relative_deviation(kMost, tail);
  if (!(deviation > lowest && deviation < highest)) {
    std::ostringstream m;
    m << "a Gaussian distribution with a Weibull tail of modulus " << tail.modulus << " grafted at probability "
      << tail.probability << " and mean 1 has a standard deviation between " << lowest << " and " << highest << ", not "
      << deviation << " (Bazant & Pang 2007)";
    throw InputError(m.str());
  }
  const double cv = bisect([&](double cv) { return relative_deviation(cv, tail) - deviation; }, kLeast, kMost);
  const Unscaled u = unscaled(cv, tail);
  mu_ = 1 / u.mean;
  delta_ = cv * mu_;
  graft_ = u.graft * mu_;
  scale_ = u.scale * mu_;
  rf_ = u.rf;
}

double GraftedWeibullGauss::cdf(double x) const {
  if (x <= 0) return 0;
  if (x <= graft_) return -std::expm1(-std::pow(x / scale_, tail_.modulus));
  return 1 - rf_ * upper_normal((x - mu_) / delta_);
}

double GraftedWeibullGauss::of_normal(double g) const {
  const double p = normal_cdf(g);
  if (p <= tail_.probability) return scale_ * std::pow(-std::log1p(-p), 1 / tail_.modulus);
  // Above the graft 1 − F(x) = r_f (1 − Φ(z)): solved through the upper tail, which keeps its digits for large g.
  return mu_ - delta_ * normal_quantile(upper_normal(g) / rf_);
}

}  // namespace mc::rigid_cell
