// Heterogeneous micro-parameters (Tang 2013 §8.1.2): the Weibull sampler (8.4) must have the closed-form mean and
// variance, the truncated normal must stay positive with the closed-form truncated mean, and both must be
// reproducible by seed.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/errors.hpp"
#include "preprocess/heterogeneity.hpp"
#include "tests/common/relative.hpp"

using namespace mc;

namespace {

struct Moments {
  double mean = 0, variance = 0, fourth = 0;  // fourth central moment, for the variance's standard error
};

Moments moments(const std::vector<double>& x) {
  Moments m;
  for (double v : x) m.mean += v;
  m.mean /= static_cast<double>(x.size());
  for (double v : x) {
    const double d2 = (v - m.mean) * (v - m.mean);
    m.variance += d2;
    m.fourth += d2 * d2;
  }
  m.variance /= static_cast<double>(x.size() - 1);
  m.fourth /= static_cast<double>(x.size());
  return m;
}

}  // namespace

// 200 000 draws each; within 4 standard errors: of the mean √(σ²/n), of the variance √((μ₄ − σ⁴)/n).
TEST_CASE("weibull_samples_match_closed_form_mean_and_variance") {
  const std::size_t n = 200000;
  for (const Weibull w : {Weibull{2.0, 1.5}, Weibull{5e6, 3.0}, Weibull{1.0, 10.0}}) {
    const auto x = draw_values({ParameterDistribution::weibull, w.scale, w.shape}, n, 77);
    const Moments m = moments(x);
    const double se_mean = std::sqrt(variance(w) / n);
    const double se_var = std::sqrt((m.fourth - variance(w) * variance(w)) / n);
    CHECK(std::abs(m.mean - mean(w)) < 4 * se_mean);
    CHECK(std::abs(m.variance - variance(w)) < 4 * se_var);
    CHECK(*std::min_element(x.begin(), x.end()) >= 0);
  }
  // Closed forms at k = 1 (exponential: mean λ, variance λ²) and k = 2 (Rayleigh: mean λ√π/2).
  CHECK(mean(Weibull{3, 1}) == mc::test::relative(3, 1e-5));
  CHECK(variance(Weibull{3, 1}) == mc::test::relative(9, 1e-5));
  CHECK(mean(Weibull{2, 2}) == mc::test::relative(std::sqrt(M_PI), 1e-5));
}

// Mean μ + σφ(α)/(1 − Φ(α)), α = −μ/σ, within 4 standard errors of 200 000 draws.
TEST_CASE("truncated_normal_samples_stay_positive_with_the_truncated_mean") {
  const std::size_t n = 200000;
  // Mildly truncated: μ = 1, σ = 0.5 (α = −2, 2.3 % cut off): mean 1 + 0.5·φ(2)/Φ(2) = 1.027623.
  const TruncatedNormal t{1.0, 0.5};
  CHECK(mean(t) == mc::test::relative(1.0 + 0.5 * 0.0539910 / 0.9772499, 1e-6));
  const auto x = draw_values({ParameterDistribution::truncated_normal, t.mean, t.std}, n, 5);
  CHECK(*std::min_element(x.begin(), x.end()) > 0);
  const Moments m = moments(x);
  CHECK(std::abs(m.mean - mean(t)) < 4 * std::sqrt(m.variance / n));
  CHECK(m.variance < 0.25);  // truncation narrows it
  // Untruncated in practice (μ = 10σ): the plain normal's moments.
  const auto y = draw_values({ParameterDistribution::truncated_normal, 10.0, 1.0}, n, 6);
  const Moments my = moments(y);
  CHECK(std::abs(my.mean - 10.0) < 4 * std::sqrt(1.0 / n));
  CHECK(std::abs(my.variance - 1.0) < 4 * std::sqrt(2.0 / n));
}

TEST_CASE("parameter_draws_are_reproducible_and_refuse_distributions_without_positive_values") {
  const ParameterDistribution w{ParameterDistribution::weibull, 3e6, 4.0};
  CHECK(draw_values(w, 1000, 42) == draw_values(w, 1000, 42));
  CHECK(draw_values(w, 1000, 42) != draw_values(w, 1000, 43));
  CHECK(draw_values({ParameterDistribution::fixed, 7.0, 0}, 3, 1) == std::vector<double>{7.0, 7.0, 7.0});
  CHECK(draw_values({ParameterDistribution::truncated_normal, 2.0, 0.0}, 2, 1) == std::vector<double>{2.0, 2.0});
  CHECK_THROWS_AS(draw_values({ParameterDistribution::weibull, 1.0, 0.0}, 1, 1), InputError);
  CHECK_THROWS_AS(draw_values({ParameterDistribution::weibull, -1.0, 2.0}, 1, 1), InputError);
  CHECK_THROWS_AS(draw_values({ParameterDistribution::truncated_normal, -3.0, 1.0}, 1, 1), InputError);
  CHECK_THROWS_AS(draw_values({ParameterDistribution::truncated_normal, 1.0, -1.0}, 1, 1), InputError);
}
