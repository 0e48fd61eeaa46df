// Fibres as segments in a specimen (rigid_cell/fibre_placement.hpp, Květoň §5.4): their number from the volume
// fraction, their directions (isotropic, aligned, von Mises–Fisher), and the wall effect of Květoň's rule (a fibre
// partly outside is drawn again) against the cut-at-the-surface rule, on the 60 × 20 × 10 mm prism of §6.3 with
// 2 % of PVA fibres, d_f 40 µm, l_f 8 mm.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>

#include "rigid_cell/fibre_placement.hpp"
#include "tests/common/relative.hpp"

using namespace mc;
using namespace mc::rigid_cell;

namespace {

constexpr double kLx = 60e-3, kLy = 20e-3, kT = 10e-3, kL = 8e-3;

FibrePlacement pva(FibreBoundary boundary = FibreBoundary::Redraw) {
  FibrePlacement p;
  p.volume_fraction = 0.02, p.length = kL, p.diameter = 40e-6, p.boundary = boundary;
  return p;
}

SpecimenShape<3> prism() { return SpecimenShape<3>::box(Vec<3>(kLx, kLy, kT)); }

Vec<3> unit(const Fibre& f) { return (f.b - f.a).normalized(); }

// Mean and standard error of |u_k| over fibres (those whose centre passes `keep`).
template <class Keep>
std::pair<double, double> mean_abs(const std::vector<Fibre>& fibres, int k, Keep keep) {
  double s = 0, s2 = 0;
  int n = 0;
  for (const Fibre& f : fibres) {
    if (!keep(0.5 * (f.a + f.b))) continue;
    const double c = std::abs(unit(f)[k]);
    s += c, s2 += c * c, ++n;
  }
  const double m = s / n;
  return {m, std::sqrt((s2 / n - m * m) / n)};
}

// Květoň's rule in a box: a direction u is kept with the probability that a uniform centre lies at least (l/2)|u_i|
// from every wall, ∝ Π (L_i − l |u_i|). The mean of |u_z| under that weight, by the midpoint rule on (cos θ, φ) with
// 1000 × 1000 cells (|u_i| has kinks on the grid lines only: error far below the 1e-3 of the sampling).
double redrawn_mean_abs_uz() {
  const int n = 1000;
  double num = 0, den = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double w = -1.0 + (i + 0.5) * 2.0 / n, phi = (j + 0.5) * 2 * M_PI / n, s = std::sqrt(1 - w * w);
      const double ux = s * std::cos(phi), uy = s * std::sin(phi);
      const double weight = (kLx - kL * std::abs(ux)) * (kLy - kL * std::abs(uy)) * (kT - kL * std::abs(w));
      num += std::abs(w) * weight, den += weight;
    }
  return num / den;
}

}  // namespace

TEST_CASE("fibres_number_what_the_volume_fraction_asks_and_lie_inside_the_specimen") {
  const SpecimenShape<3> shape = prism();
  RandomStream rng(3);
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<Fibre> fibres = place_fibres(shape, pva(), rng);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // N = V_f V/(π d²/4 l) = 0.02 · 12 cm³/(1.2566e-9 m² · 8 mm) = 23 873.
  CHECK(fibres.size() == 23873);
  CHECK(fibre_count(pva(), shape.volume()) == 23873);
  MESSAGE(fibres.size(), " fibres placed in ", seconds, " s");
  // Each wholly inside (its ends within round-off of the box), each of length l_f.
  int outside = 0;
  double worst_length = 0;
  for (const Fibre& f : fibres) {
    for (const Vec<3>& e : {f.a, f.b})
      outside += (e.array() < -1e-15).any() || (e.array() > Vec<3>(kLx, kLy, kT).array() + 1e-15).any();
    worst_length = std::max(worst_length, std::abs((f.b - f.a).norm() / kL - 1));
  }
  CHECK(outside == 0);
  CHECK(worst_length < 1e-12);
  // The same seed, the same fibres to the last bit.
  RandomStream again(3);
  const std::vector<Fibre> twice = place_fibres(shape, pva(), again);
  bool same = twice.size() == fibres.size();
  for (std::size_t i = 0; same && i < fibres.size(); ++i) same = twice[i].a == fibres[i].a && twice[i].b == fibres[i].b;
  CHECK(same);
}

TEST_CASE("isotropic_fibres_lie_along_the_surfaces_under_the_redraw_rule_and_not_when_cut") {
  const SpecimenShape<3> shape = prism();
  RandomStream rng(5);
  const std::vector<Fibre> redrawn = place_fibres(shape, pva(), rng);
  const std::vector<Fibre> cut = place_fibres(shape, pva(FibreBoundary::Cut), rng);
  const auto all = [](const Vec<3>&) { return true; };
  // Cut at the surface: isotropic everywhere, E|u_k| = 1/2; within 4 standard errors (about 0.008).
  for (int k = 0; k < 3; ++k) {
    const auto [m, se] = mean_abs(cut, k, all);
    CAPTURE(k);
    CHECK(std::abs(m - 0.5) < 4 * se);
  }
  // Redrawn: the directions weighted by the room a fibre of that direction has, Π (L_i − l |u_i|): across the
  // 10 mm thickness the 8 mm fibres lie flat, E|u_z| = 0.407 instead of 1/2 (0.389 from the thickness alone; the
  // side walls, which turn fibres away from x and y, give back some).
  const double expected = redrawn_mean_abs_uz();
  const auto [m, se] = mean_abs(redrawn, 2, all);
  MESSAGE("redrawn: E|u_z| = ", m, " ± ", se, ", the room-weighted mean ", expected, "; cut: 1/2");
  CHECK(expected == test::relative(0.407, 0.002));
  CHECK(std::abs(m - expected) < 4 * se);
  // Cutting shortens the fibres near the surfaces: the volume fraction falls below 2 %.
  double length = 0;
  for (const Fibre& f : cut) length += (f.b - f.a).norm();
  const double fraction = length * 0.25 * M_PI * 40e-6 * 40e-6 / shape.volume();
  MESSAGE("cut: volume fraction ", fraction);
  CHECK(fraction < 0.02 * 0.95);
  CHECK(fraction > 0.02 * 0.5);
}

TEST_CASE("preferential_fibres_spread_about_their_axis_as_von_mises_fisher_says") {
  // Density ∝ exp(κ cos θ) about the axis: E cos θ = coth κ − 1/κ, var cos θ = 1 − 2 E cos θ/κ − (E cos θ)².
  FibrePlacement p = pva();
  p.orientation = FibreOrientation::Preferential;
  p.direction = Vec<3>(1, 1, 0).normalized();
  RandomStream rng(9);
  for (const double kappa : {0.5, 5.0, 50.0}) {
    p.concentration = kappa;
    const int n = 100000;
    double s = 0, worst_norm = 0;
    for (int i = 0; i < n; ++i) {
      const Vec<3> u = draw_direction(p, rng);
      worst_norm = std::max(worst_norm, std::abs(u.norm() - 1));
      s += u.dot(p.direction);
    }
    CHECK(worst_norm < 1e-12);
    const double mean = 1.0 / std::tanh(kappa) - 1.0 / kappa, se = std::sqrt((1 - 2 * mean / kappa - mean * mean) / n);
    CAPTURE(kappa);
    CHECK(std::abs(s / n - mean) < 4 * se);
  }
  p.orientation = FibreOrientation::Aligned;
  CHECK(draw_direction(p, rng) == p.direction);
}
