// The one-sided pull-out law of a fibre (rigid_cell/fibre_pullout.hpp; Květoň (5.1)–(5.10), after Naaman et al.
// 1991) against its closed forms, on the fibre of Květoň's §6.1: E_f 30 GPa, d_f 40 µm, G_d 5 N/m, τ_0 2 MPa,
// f_tf 1000 MPa, l_f 10 mm with 35 % on the short side (L_e 3.5 mm).
#include <doctest/doctest.h>

#include <cmath>

#include "rigid_cell/fibre_pullout.hpp"
#include "tests/common/relative.hpp"

using namespace mc::rigid_cell;

namespace {

FibreMaterial kveton_fibre(double debonding_energy = 5.0, double slip_hardening = 0.0) {
  FibreMaterial f;
  f.modulus = 30e9;
  f.diameter = 40e-6;
  f.tensile_strength = 1000e6;
  f.friction_stress = 2e6;
  f.debonding_energy = debonding_energy;
  f.slip_hardening = slip_hardening;
  return f;
}

constexpr double kShort = 3.5e-3;  // the short side of the 10 mm fibre [m]

// ∫ P dv over [a, b] by Simpson's rule on n (even) intervals: (5.1) is smooth within each branch.
template <class F>
double simpson(F p, double a, double b, int n) {
  const double h = (b - a) / n;
  double s = p(a) + p(b);
  for (int i = 1; i < n; ++i) s += (i % 2 ? 4.0 : 2.0) * p(a + i * h);
  return s * h / 3.0;
}

}  // namespace

TEST_CASE("fibre_debonding_starts_at_the_bond_energy_force_and_meets_friction_at_full_debonding_without_it") {
  const FibreMaterial f = kveton_fibre();
  const double d = f.diameter;
  // P(0) = √(π² E_f d_f³ G_d/2) (Květoň §6.2): 0.2177 N for the §6.1 fibre.
  CHECK(debonding_force(f, 0.0) == test::relative(std::sqrt(0.5 * M_PI * M_PI * f.modulus * d * d * d * 5.0), 1e-14));
  CHECK(debonding_force(f, 0.0) == test::relative(0.2177, 1e-3));
  // Without bond energy the debonding branch reaches P_0 = π L_e d_f τ_0 exactly at v_d (2τ_0 L_e²/(E_f d_f)):
  // (5.1) is continuous there, which fixes the D_f of the thesis's (5.2) as d_f. Round-off only: 1e-12.
  for (const double le : {1e-3, kShort, 6.5e-3}) {
    const FibreMaterial g0 = kveton_fibre(0.0);
    const double vd = full_debonding_slip(g0, le);
    CHECK(vd == test::relative(2 * g0.friction_stress * le * le / (g0.modulus * d), 1e-14));
    CHECK(debonding_force(g0, vd) == test::relative(friction_force(g0, le), 1e-12));
    CHECK(friction_force(g0, le) == test::relative(M_PI * le * d * g0.friction_stress, 1e-14));
  }
  // With G_d > 0 the force drops at v_d from the debonding branch to P_0 (Květoň §6.1: "instant drop").
  const double vd = full_debonding_slip(f, kShort);
  CHECK(vd == test::relative(61.0e-6, 2e-3));  // 40.8 µm of friction, 20.2 µm of bond energy
  CHECK(debonding_force(f, vd) == test::relative(1.097, 1e-3));
  CHECK(pullout_force(f, kShort, vd * (1 + 1e-12)) == test::relative(friction_force(f, kShort), 1e-9));
  CHECK(friction_force(f, kShort) == test::relative(0.8796, 1e-3));
}

TEST_CASE("fibre_slides_out_over_its_embedment_with_slip_hardening_or_softening") {
  for (const double beta : {-0.01, 0.0, 0.01}) {
    const FibreMaterial f = kveton_fibre(5.0, beta);
    const double vd = full_debonding_slip(f, kShort), p0 = friction_force(f, kShort);
    CAPTURE(beta);
    // (5.1) half-way out: P_0 (1/2)(1 + β_f L_e/(2 d_f)): 0.5625 P_0 softening, 0.5 P_0, 0.9375 P_0 hardening.
    CHECK(pullout_force(f, kShort, vd + 0.5 * kShort) ==
          test::relative(p0 * 0.5 * (1 + beta * kShort / (2 * f.diameter)), 1e-12));
    // Out: nothing left.
    CHECK(pullout_force(f, kShort, vd + kShort) == 0.0);
    CHECK(pullout_force(f, kShort, vd + 2 * kShort) == 0.0);
  }
  // Softening wears the friction away at s = d_f/|β_f| = 4 mm, before a 6.5 mm embedment is out; it stays gone.
  const FibreMaterial soft = kveton_fibre(5.0, -0.01);
  const double vd = full_debonding_slip(soft, 6.5e-3);
  CHECK(pullout_force(soft, 6.5e-3, vd + 3.99e-3) > 0.0);
  CHECK(pullout_force(soft, 6.5e-3, vd + 4.01e-3) == 0.0);
  CHECK(pullout_force(soft, 6.5e-3, vd + 6e-3) == 0.0);
}

TEST_CASE("fibre_debonded_length_solves_the_embedment_quadratic_and_inverts_full_debonding") {
  for (const double g : {0.0, 1e-9, 5.0, 50.0}) {
    const FibreMaterial f = kveton_fibre(g);
    const double a = 2 * f.friction_stress / (f.modulus * f.diameter), b = std::sqrt(8 * g / (f.modulus * f.diameter));
    CAPTURE(g);
    // (5.5) is the root of (5.4) with v for v_d: a L² + b L − v = 0, to round-off relative to v.
    for (const double v : {1e-9, 1e-6, 2e-5, 6e-5}) {
      const double ld = debonded_length(f, v);
      CHECK(std::abs(a * ld * ld + b * ld - v) < 1e-12 * v);
    }
    // Debonded whole at v_d(L_e): the debonded length is L_e.
    for (const double le : {1e-3, kShort, 6.5e-3})
      CHECK(debonded_length(f, full_debonding_slip(f, le)) == test::relative(le, 1e-12));
  }
}

TEST_CASE("fibre_pullout_work_is_the_integral_of_its_force") {
  // The closed form of ∫P dv against Simpson's rule on each branch (smooth within it): 2000 intervals take the
  // quadrature error below 1e-10 of the work (measured: below 1e-15).
  for (const double beta : {-0.01, 0.0, 0.01})
    for (const double g : {0.0, 5.0}) {
      const FibreMaterial f = kveton_fibre(g, beta);
      const double vd = full_debonding_slip(f, kShort);
      // v = v_d t²: without bond energy P grows as √v, whose infinite slope at 0 Simpson's rule would resolve
      // only to 2e-8; in t the integrand 2 v_d t P(v_d t²) is smooth.
      const double debonding =
          simpson([&](double t) { return 2 * vd * t * debonding_force(f, vd * t * t); }, 0.0, 1.0, 2000);
      const double sliding = simpson([&](double v) { return sliding_force(f, kShort, v); }, vd, vd + kShort, 2000);
      CAPTURE(beta);
      CAPTURE(g);
      const double work = pullout_work(f, kShort);
      MESSAGE("beta ", beta, ", G_d ", g, ": work ", work, " J, quadrature/closed form - 1 = ",
              (debonding + sliding) / work - 1);
      CHECK(std::abs((debonding + sliding) / work - 1) < 1e-10);
    }
}

TEST_CASE("fibre_too_long_breaks_and_an_inclined_one_breaks_sooner_and_snubs") {
  const FibreMaterial f = kveton_fibre();
  const double strength_force = f.tensile_strength * M_PI * f.diameter * f.diameter / 4;  // 1.2566 N
  // Květoň §6.1: the 10 mm fibre pulls out of its 3.5 mm side (largest force 1.097 N, at v_d), the 20 mm one
  // (7 mm) breaks: its friction alone, 1.759 N, is above the fibre's strength.
  CHECK(debonding_force(f, full_debonding_slip(f, kShort)) < strength_force);
  CHECK(friction_force(f, 2 * kShort) > strength_force);
  // (5.10) with k_rup 0.33 (§6.4): inclined 0.5 rad, its strength falls to 84.8 %, below what the short side
  // carries at full debonding: the inclined short fibre breaks too.
  FibreMaterial micro = f;
  micro.rupture_coefficient = 0.33, micro.snubbing_coefficient = 0.1, micro.spalling_coefficient = 500;
  CHECK(inclined_strength(micro, 0.0) == f.tensile_strength);
  CHECK(inclined_strength(micro, 0.5) == test::relative(f.tensile_strength * std::exp(-0.165), 1e-14));
  CHECK(inclined_strength(micro, 0.5) * M_PI * f.diameter * f.diameter / 4 <
        debonding_force(f, full_debonding_slip(f, kShort)));
  // (5.9): snubbing raises the force by exp(k_sn φ'_f), 5.1 % at 0.5 rad; none along the straining direction.
  CHECK(snubbing_factor(micro, 0.0) == 1.0);
  CHECK(snubbing_factor(micro, 0.5) == test::relative(std::exp(0.05), 1e-14));
  // (5.8): no spalling along the normal; at θ = 60° and P_N = 1 N, with the matrix's f_t = 3 MPa:
  // sin 30°/(500 · 3 MPa · 40 µm · cos² 30°) = 11.1 µm.
  CHECK(spalling_length(micro, 1.0, 0.0, 3e6) == 0.0);
  CHECK(spalling_length(micro, 1.0, M_PI / 3, 3e6) == test::relative(0.5 / (500 * 3e6 * 40e-6 * 0.75), 1e-14));
  CHECK(spalling_length(f, 1.0, M_PI / 3, 3e6) == 0.0);  // k_sp = 0: spalling off
}
