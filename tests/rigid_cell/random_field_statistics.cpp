// The random field of Květoň §3.4 (3.21): its marginal (mean 1, the declared deviation, the Weibull left tail of
// Bažant & Pang 2007), its squared-exponential autocorrelation, the eigenvalues of its Karhunen–Loève expansion,
// and the same field for a seed whatever the thread count.
#include <doctest/doctest.h>
#include <omp.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <vector>

#include "engine/errors.hpp"
#include "engine/random_stream.hpp"
#include "rigid_cell/random_field.hpp"
#include "tests/common/relative.hpp"

using namespace mc;
using namespace mc::rigid_cell;

namespace {

// A square of 30 l_c whose field keeps `variance_kept` of its variance, realisation `seed`.
constexpr double kLc = 0.01, kSide = 30 * kLc;
RandomField<2> square_field(double variance_kept, std::uint64_t seed) {
  RandomFieldParams p;
  p.correlation_length = kLc;
  p.deviation = 0.25;
  p.grid_spacing = kLc / 3;
  p.variance_kept = variance_kept;
  p.seed = seed;
  return RandomField<2>(Vec<2>::Zero(), Vec<2>::Constant(kSide), p);
}

// 10 × 10 anchors 3 l_c apart: their fields correlate by e⁻⁹ = 1.2e-4 at most, independent samples for all
// purposes here.
std::vector<Vec<2>> anchors() {
  std::vector<Vec<2>> a;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) a.emplace_back((1.5 + 3 * i) * kLc, (1.5 + 3 * j) * kLc);
  return a;
}

double mean(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0) / v.size(); }

double deviation(const std::vector<double>& v) {
  const double m = mean(v);
  double s = 0;
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / (v.size() - 1));
}

double pearson(const std::vector<double>& a, const std::vector<double>& b) {
  const double ma = mean(a), mb = mean(b);
  double ab = 0, aa = 0, bb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ab += (a[i] - ma) * (b[i] - mb);
    aa += (a[i] - ma) * (a[i] - ma);
    bb += (b[i] - mb) * (b[i] - mb);
  }
  return ab / std::sqrt(aa * bb);
}

}  // namespace

TEST_CASE("random field: h over 40 000 independent points has mean 1 and the declared deviation (Kveton 3.21)") {
  std::vector<double> h;
  for (std::uint64_t seed = 1; seed <= 400; ++seed) {
    const RandomField<2> field = square_field(0.99, seed);
    for (const Vec<2>& x : anchors()) h.push_back(field.h(x));
  }
  // Standard errors over N = 40 000: of the mean σ/√N = 0.00125, of the deviation about σ/√(2N) = 0.00088 (a
  // near-Gaussian's); both within four of them.
  const double n = static_cast<double>(h.size());
  CHECK(std::abs(mean(h) - 1) < 4 * 0.25 / std::sqrt(n));
  CHECK(std::abs(deviation(h) - 0.25) < 4 * 0.25 / std::sqrt(2 * n));
  MESSAGE("h: mean " << mean(h) << ", deviation " << deviation(h) << " over " << h.size() << " points");
}

TEST_CASE("random field: the Gaussian field correlates at lags l_c/2, l_c, 2 l_c as exp(-|dx|^2/l_c^2)") {
  // Each anchor paired with a point at each lag in a random direction: 40 000 pairs per lag. The sample
  // correlation's standard error is (1 − ρ²)/√N: 0.0020, 0.0043, 0.0050; the check allows four. 99.9 % of the
  // variance kept, so that the truncation's own bias (+0.0003 at l_c) stays far below that.
  const std::vector<double> lags{0.5 * kLc, kLc, 2 * kLc};
  std::vector<std::vector<double>> a(lags.size()), b(lags.size());
  RandomStream directions(17);
  for (std::uint64_t seed = 1; seed <= 400; ++seed) {
    const RandomField<2> field = square_field(0.999, seed);
    for (const Vec<2>& x : anchors()) {
      const double gx = field.gaussian(x);
      for (std::size_t l = 0; l < lags.size(); ++l) {
        const double angle = directions.uniform(0, 2 * M_PI);
        a[l].push_back(gx);
        b[l].push_back(field.gaussian(x + lags[l] * Vec<2>(std::cos(angle), std::sin(angle))));
      }
    }
  }
  for (std::size_t l = 0; l < lags.size(); ++l) {
    const double rho = std::exp(-std::pow(lags[l] / kLc, 2)), r = pearson(a[l], b[l]);
    CAPTURE(lags[l]);
    CHECK(std::abs(r - rho) < 4 * (1 - rho * rho) / std::sqrt(static_cast<double>(a[l].size())));
    MESSAGE("lag " << lags[l] / kLc << " l_c: correlation " << r << ", exp(-lag^2/l_c^2) = " << rho);
  }
}

TEST_CASE("random field: a long axis's correlation eigenvalues fill the kernel's spectral density (Szego)") {
  // 300 nodes h = l_c/3 apart. The correlation matrix is Toeplitz; as it grows its eigenvalues spread as its
  // symbol f(θ) = Σ_k exp(−k²h²/l_c²) e^{ikθ} (Szegő): the largest tends to f(0) = √π l_c/h (to e^{−π²l_c²/h²}),
  // and the share above f(0)/2 to the share of θ where f > f(0)/2, 2 (h/l_c) √ln2 / π: 53.0 of 300.
  const double lc = 0.02, h = lc / 3;
  RandomFieldParams p;
  p.correlation_length = lc, p.deviation = 0.25, p.grid_spacing = h;
  const RandomField<2> field(Vec<2>::Zero(), Vec<2>(299 * h, 2 * h), p);
  const Eigen::VectorXd& lambda = field.eigenvalues(0);
  REQUIRE(lambda.size() == 300);
  const double f0 = std::sqrt(M_PI) * lc / h;
  CHECK(lambda[0] == mc::test::relative(f0, 5e-4));  // measured: 2.4e-4 below (finite-size)
  const auto above = std::count_if(lambda.begin(), lambda.end(), [&](double l) { return l > f0 / 2; });
  CHECK(std::abs(above - 300 * 2 * (h / lc) * std::sqrt(std::log(2.0)) / M_PI) <= 1);
  CHECK(lambda.sum() == mc::test::relative(300, 1e-12));  // the trace: the variance of 300 nodes
  CHECK(field.variance_fraction() >= 0.99);
}

TEST_CASE("random field: the grid's correlation eigenvalues are products of its axes' (Vorechovsky 2008)") {
  const double lc = 0.02;
  RandomFieldParams p;
  p.correlation_length = lc, p.deviation = 0.25, p.grid_spacing = lc / 3, p.variance_kept = 0.9999;
  const RandomField<2> field(Vec<2>::Zero(), Vec<2>(0.05, 0.03), p);
  const Eigen::VectorXd &x = field.nodes(0), &y = field.nodes(1);
  REQUIRE(x.size() * y.size() == 54);  // 9 × 6 nodes
  // The whole grid's correlation matrix, decomposed as it stands.
  std::vector<Vec<2>> grid;
  for (double xi : x)
    for (double yj : y) grid.emplace_back(xi, yj);
  Eigen::MatrixXd C(54, 54);
  for (int i = 0; i < 54; ++i)
    for (int j = 0; j < 54; ++j) C(i, j) = std::exp(-(grid[i] - grid[j]).squaredNorm() / (lc * lc));
  Eigen::VectorXd whole = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(C).eigenvalues();
  std::vector<double> products;
  for (double a : field.eigenvalues(0))
    for (double b : field.eigenvalues(1)) products.push_back(a * b);
  std::sort(products.begin(), products.end());
  for (int k = 0; k < 54; ++k) CHECK(std::abs(whole[k] - products[k]) < 1e-12 * whole[53]);
  CHECK(field.variance_fraction() >= 0.9999);
  CHECK(field.variance_fraction() <= 1 + 1e-12);
}

TEST_CASE("random field: a seed gives the same field bits on one thread or two, another seed another field") {
  // An axis of 301 nodes: large enough for Eigen's products to share out work between threads.
  RandomFieldParams p;
  p.correlation_length = 0.01, p.deviation = 0.25, p.grid_spacing = 0.01 / 3, p.seed = 5;
  const Vec<2> lo = Vec<2>::Zero(), hi(1.0, 0.05);
  std::vector<Vec<2>> points;
  RandomStream where(3);
  for (int i = 0; i < 1000; ++i) points.emplace_back(where.uniform(0, 1.0), where.uniform(0, 0.05));
  const auto values = [&](int threads, std::uint64_t seed) {
    omp_set_num_threads(threads);
    p.seed = seed;
    const RandomField<2> field(lo, hi, p);
    std::vector<double> h;
    for (const Vec<2>& x : points) h.push_back(field.h(x));
    return h;
  };
  const int before = omp_get_max_threads();
  const std::vector<double> one = values(1, 5), two = values(2, 5), other = values(1, 6);
  omp_set_num_threads(before);
  CHECK(std::memcmp(one.data(), two.data(), one.size() * sizeof(double)) == 0);
  int differ = 0;
  for (std::size_t i = 0; i < one.size(); ++i) differ += one[i] != other[i];
  CHECK(differ == 1000);
}

TEST_CASE("grafted distribution: Weibull of modulus m below P_gr, density continuous there, mean 1, deviation 0.25") {
  const WeibullTail tail{24, 1e-3};
  const GraftedWeibullGauss F(0.25, tail);
  // On Weibull paper, ln(−ln(1 − F)) against ln x, the tail is a line of slope m up to the graft.
  const auto weibull_paper = [&](double p) {
    const double x = F.of_normal(normal_quantile(p));
    CHECK(F.cdf(x) == mc::test::relative(p, 1e-10));  // of_normal inverts cdf
    return std::array<double, 2>{std::log(x), std::log(-std::log1p(-p))};
  };
  const auto a = weibull_paper(1e-8), b = weibull_paper(1e-5), c = weibull_paper(tail.probability);
  CHECK((b[1] - a[1]) / (b[0] - a[0]) == mc::test::relative(24, 1e-9));
  CHECK((c[1] - b[1]) / (c[0] - b[0]) == mc::test::relative(24, 1e-9));
  CHECK(std::exp(c[0]) == mc::test::relative(F.graft(), 1e-12));
  // The density on either side of the graft (Bažant & Pang's continuity), by differences of the cdf.
  const double x = F.graft(), e = 1e-7;
  const double left = (F.cdf(x) - F.cdf(x - e)) / e, right = (F.cdf(x + e) - F.cdf(x)) / e;
  CHECK(left == mc::test::relative(right, 1e-4));
  // Mean and deviation: ∫ F⁻¹(Φ(g)) φ(g) dg by Simpson's rule over |g| ≤ 10 (the rest weighs 1e-23).
  const int n = 200000;
  const double step = 20.0 / n;
  double m1 = 0, m2 = 0;
  for (int i = 0; i <= n; ++i) {
    const double g = -10 + i * step, w = (i == 0 || i == n ? 1 : i % 2 ? 4 : 2) * step / 3;
    const double v = F.of_normal(g), phi = std::exp(-0.5 * g * g) / std::sqrt(2 * M_PI);
    m1 += w * v * phi;
    m2 += w * v * v * phi;
  }
  CHECK(m1 == mc::test::relative(1, 1e-8));
  CHECK(std::sqrt(m2 - m1 * m1) == mc::test::relative(0.25, 1e-7));
}

TEST_CASE("grafted distribution: a deviation its tail cannot give is refused with the range it can") {
  // A tail of modulus 24 grafted at 10 % holds the deviation below about 0.22 however wide the core.
  try {
    const GraftedWeibullGauss F(0.25, WeibullTail{24, 0.1});
    FAIL("accepted");
  } catch (const InputError& e) {
    const std::string what = e.what();
    CHECK_MESSAGE(what.find("between") != std::string::npos, what);
    CHECK_MESSAGE(what.find("0.25") != std::string::npos, what);
  }
}
