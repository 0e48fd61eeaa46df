// Květoň ch. 8: the ingredients of the rigid cells' implicit dynamics. The cell mass matrix (8.6)-(8.8) against the
// kinetic energy of a rigid motion integrated over the cell, and Newmark's scheme (8.2)-(8.5) against its closed-form
// behaviour on an undamped oscillator (period elongation and amplitude decay of the chosen β, γ).
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "engine/errors.hpp"
#include "rigid_cell/mass_properties.hpp"
#include "rigid_cell/newmark.hpp"
#include "tests/common/relative.hpp"
#include "tests/rigid_cell/box_cell.hpp"

using namespace mc;
using namespace mc::rigid_cell;

namespace {

// ∫ ρ/2 |u̇ + θ̇ × r|² dV over the box [lo, hi] (r about `node`) by 2-point Gauss rules per axis: the integrand is
// quadratic in r, which they integrate exactly.
double box_kinetic_energy(const Vec<3>& lo, const Vec<3>& hi, const Vec<3>& node, double density, const Vec<3>& v,
                          const Vec<3>& w) {
  const double g = 1 / std::sqrt(3.0);
  double e = 0;
  for (double sx : {-g, g})
    for (double sy : {-g, g})
      for (double sz : {-g, g}) {
        const Vec<3> s(sx, sy, sz);
        const Vec<3> x = 0.5 * (lo + hi) + 0.5 * (hi - lo).cwiseProduct(s);
        e += (v + w.cross(x - node)).squaredNorm();
      }
  return 0.5 * density * e * (hi - lo).prod() / 8;  // eight points, equal weights
}

}  // namespace

TEST_CASE("cell_mass_matrix_gives_the_kinetic_energy_of_every_rigid_motion_about_an_off_centre_node") {
  const Vec<3> lo(0, 0, 0), hi(0.03, 0.02, 0.01), node(0.012, 0.005, 0.004);
  const double density = 2400;
  const Eigen::Matrix<double, 6, 6> M = mc::test::box_cell(lo, hi, node).mass_matrix(density);
  CHECK((M - M.transpose()).norm() == 0);
  // Six motions, each a translation and a turn: ½ q̇ᵀ M q̇ against the integral. The coupling S_m (8.7) matters:
  // without it a translation along x with a turn about z misses 2 m Δ_y v_x ω_z.
  const std::vector<std::pair<Vec<3>, Vec<3>>> motions = {
      {Vec<3>(1, 0, 0), Vec<3>(0, 0, 0)},        {Vec<3>(0, 0, 0), Vec<3>(0, 0, 3)},
      {Vec<3>(1, 0, 0), Vec<3>(0, 0, 50)},       {Vec<3>(0, 2, -1), Vec<3>(40, 0, 0)},
      {Vec<3>(0.3, -1, 2), Vec<3>(-20, 70, 10)}, {Vec<3>(0, 0, 1), Vec<3>(0, -90, 0)}};
  for (const auto& [v, w] : motions) {
    Eigen::Matrix<double, 6, 1> q;
    q << v, w;
    const double expected = box_kinetic_energy(lo, hi, node, density, v, w);
    // Both sides are exact: only round-off separates them.
    CHECK(0.5 * q.dot(M * q) == mc::test::relative(expected, 1e-12));
  }
}

TEST_CASE("cell_mass_matrix_2d_gives_the_kinetic_energy_of_a_rigid_motion") {
  // A 2D square cell (unit thickness) of side h about an off-centre node: the triangle fan of its four edges.
  const double h = 0.01, density = 2000;
  const Vec<2> node(0.003, 0.0065);
  const std::array<Vec<2>, 4> corner{Vec<2>(0, 0), Vec<2>(h, 0), Vec<2>(h, h), Vec<2>(0, h)};
  MassProperties<2> m;
  for (int i = 0; i < 4; ++i) m += pyramid<2>(std::array<Vec<2>, 2>{corner[i] - node, corner[(i + 1) % 4] - node});
  const Eigen::Matrix3d M = m.mass_matrix(density);
  // u̇ = (vx, vy), θ̇ = ω: ∫ρ/2 |(vx − ω r_y, vy + ω r_x)|² dA, with r about the node; the square's centroid sits at
  // c = (h/2, h/2) − node, its polar moment about it m h²/6.
  const double vx = 0.4, vy = -1.3, w = 25, mass = density * h * h;
  const Vec<2> c = Vec<2>(h / 2, h / 2) - node;
  const double expected = 0.5 * mass * (vx * vx + vy * vy) + mass * w * (-vx * c.y() + vy * c.x()) +
                          0.5 * w * w * (mass * h * h / 6 + mass * c.squaredNorm());
  const Eigen::Vector3d q(vx, vy, w);
  CHECK(0.5 * q.dot(M * q) == mc::test::relative(expected, 1e-12));
}

TEST_CASE("newmark_oscillator_has_the_closed_form_period_elongation_and_amplitude_decay") {
  // x'' + ω² x = 0 stepped by (8.4) with K = ω², M = 1, then (8.2)-(8.3); Květoň's β 0.3, γ 0.55 and the
  // trapezoidal rule (¼, ½), at 20 and 8 steps per period.
  const double omega = 2 * std::numbers::pi * 50;  // 50 Hz
  for (const auto [beta, gamma] : {std::pair{0.3, 0.55}, std::pair{0.25, 0.5}})
    for (const double steps_per_period : {20.0, 8.0}) {
      CAPTURE(beta);
      CAPTURE(gamma);
      CAPTURE(steps_per_period);
      const NewmarkScheme s(beta, gamma, 2 * std::numbers::pi / omega / steps_per_period);
      const NewmarkOscillator closed(s, omega);
      double x = 1e-3, v = 0.2, a = -omega * omega * x;
      const double x0 = x, x1 = (x0 + s.dt * v - (0.5 - beta) * omega * omega * s.dt * s.dt * x0) /
                                (1 + beta * omega * omega * s.dt * s.dt);
      // x_n = ρⁿ (x₀ cos nΩ̄ + c₂ sin nΩ̄), c₂ from x₁.
      const double c2 = (x1 / closed.rho - x0 * std::cos(closed.omega_bar)) / std::sin(closed.omega_bar);
      std::vector<double> path{x};
      for (int n = 1; n <= 400; ++n) {
        const double x_next = (s.inertial_history(x, v, a)) / (omega * omega + s.a0());  // (8.4), M = 1
        const double a_next = s.acceleration(x_next, x, v, a);
        v = s.velocity(v, a, a_next);
        a = a_next, x = x_next;
        path.push_back(x);
        const double expected =
            std::pow(closed.rho, n) * (x0 * std::cos(n * closed.omega_bar) + c2 * std::sin(n * closed.omega_bar));
        // The recurrence is exact; round-off grows slowly over 400 steps: 1e-9 of the amplitude.
        REQUIRE(std::abs(x - expected) < 1e-9 * std::hypot(x0, c2));
      }
      // The scheme's figures: trapezoidal keeps the amplitude (ρ = 1) and lengthens the period by
      // Ω/(2 atan(Ω/2)); γ > ½ damps.
      const double W = omega * s.dt;
      if (gamma == 0.5) {
        CHECK(closed.decay_per_period() == mc::test::relative(1.0, 1e-12));
        CHECK(closed.period_ratio(s, omega) == mc::test::relative(W / (2 * std::atan(W / 2)), 1e-12));
      } else {
        CHECK(closed.decay_per_period() < 1);
      }
      CHECK(closed.period_ratio(s, omega) > 1);
    }
}

TEST_CASE("newmark_refuses_parameters_outside_its_unconditional_stability") {
  CHECK_THROWS_AS(NewmarkScheme(0.2, 0.5, 1e-5), InputError);   // 2β < γ
  CHECK_THROWS_AS(NewmarkScheme(0.3, 0.45, 1e-5), InputError);  // γ < ½
  CHECK_THROWS_AS(NewmarkScheme(0.3, 0.55, 0), InputError);
  CHECK_NOTHROW(NewmarkScheme(NewmarkScheme::kBeta, NewmarkScheme::kGamma, 1e-5));
}
