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
  CHECK(debonding_force(f, 0.0) == mc::test::relative(std::sqrt(0.5 * M_PI * M_PI * f.modulus * d * d * d * 5.0), 1e-14));
  CHECK(debonding_force(f, 0.0) == mc::test::relative(0.2177, 1e-3));
  // Without bond energy the debonding branch reaches P_0 = π L_e d_f τ_0 exactly at v_d (2τ_0 L_e²/(E_f d_f)):
  // (5.1) is continuous there, which fixes the D_f of the thesis's (5.2) as d_f. Round-off only: 1e-12.
  for (const double le : {1e-3, kShort, 6.5e-3}) {
    const FibreMaterial g0 = kveton_fibre(0.0);
    const double vd = full_debonding_slip(g0, le);
    CHECK(vd == mc::test::relative(2 * g0.friction_stress * le * le / (g0.modulus * d), 1e-14));
    CHECK(debonding_force(g0, vd) == mc::test::relative(friction_force(g0, le), 1e-12));
    CHECK(friction_force(g0, le) == mc::test::relative(M_PI * le * d * g0.friction_stress, 1e-14));
  }
  // With G_d > 0 the force drops at v_d from the debonding branch to P_0 (Květoň §6.1: "instant drop").
  const double vd = full_debonding_slip(f, kShort);
  CHECK(vd == mc::test::relative(61.0e-6, 2e-3));  // 40.8 µm of friction, 20.2 µm of bond energy
  CHECK(debonding_force(f, vd) == mc::test::relative(1.097, 1e-3));
  CHECK(pullout_force(f, kShort, vd * (1 + 1e-12)) == mc::test::relative(friction_force(f, kShort), 1e-9));
  CHECK(friction_force(f, kShort) == mc::test::relative(0.8796, 1e-3));
}

TEST_CASE("fibre_slides_out_over_its_embedment_with_slip_hardening_or_softening") {
  for (const double beta : {-0.01, 0.0, 0.01}) {
    const FibreMaterial f = kveton_fibre(5.0, beta);
    const double vd = full_debonding_slip(f, kShort), p0 = friction_force(f, kShort);
    CAPTURE(beta);
    // (5.1) half-way out: P_0 (1/2)(1 + β_f L_e/(2 d_f)): 0.5625 P_0 softening, 0.5 P_0, 0.9375 P_0 hardening.
    CHECK(pullout_force(f, kShort, vd + 0.5 * kShort) ==
          mc::test::relative(p0 * 0.5 * (1 + beta * kShort / (2 * f.diameter)), 1e-12));
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
      CHECK(debonded_length(f, full_debonding_slip(f, le)) == mc::test::relative(le, 1e-12));
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
  CHECK(inclined_strength(micro, 0.5) == mc::test::relative(f.tensile_strength * std::exp(-0.165), 1e-14));
  CHECK(inclined_strength(micro, 0.5) * M_PI * f.diameter * f.diameter / 4 <
        debonding_force(f, full_debonding_slip(f, kShort)));
  // (5.9): snubbing raises the force by exp(k_sn φ'_f), 5.1 % at 0.5 rad; none along the straining direction.
  CHECK(snubbing_factor(micro, 0.0) == 1.0);
  CHECK(snubbing_factor(micro, 0.5) == mc::test::relative(std::exp(0.05), 1e-14));
  // (5.8): no spalling along the normal; at θ = 60° and P_N = 1 N, with the matrix's f_t = 3 MPa:
  // sin 30°/(500 · 3 MPa · 40 µm · cos² 30°) = 11.1 µm.
  CHECK(spalling_length(micro, 1.0, 0.0, 3e6) == 0.0);
  CHECK(spalling_length(micro, 1.0, M_PI / 3, 3e6) == mc::test::relative(0.5 / (500 * 3e6 * 40e-6 * 0.75), 1e-14));
  CHECK(spalling_length(f, 1.0, M_PI / 3, 3e6) == 0.0);  // k_sp = 0: spalling off
}

namespace {

// Květoň §6.1: the 10 mm fibre, 35 % (3.5 mm) on one side of the crack and 6.5 mm on the other.
TwoSidedPullout kveton_crossing(double short_side = kShort, double long_side = 6.5e-3) {
  TwoSidedPullout t;
  t.embedment[0] = long_side, t.embedment[1] = short_side;
  return t;
}

}  // namespace

TEST_CASE("two_sided_pullout_debonds_both_sides_alike_then_the_short_side_pulls_out") {
  const FibreMaterial f = kveton_fibre();
  const double vd = full_debonding_slip(f, kShort);
  // Both sides debond with one law: the opening splits in halves, at the debonding force of either.
  {
    TwoSidedPullout t = kveton_crossing();
    const double p = open_crack(f, t, vd);
    CHECK(t.pullout[0] == mc::test::relative(0.5 * vd, 1e-12));
    CHECK(t.pullout[1] == mc::test::relative(0.5 * vd, 1e-12));
    CHECK(p == mc::test::relative(debonding_force(f, 0.5 * vd), 1e-12));
  }
  // Past 2 v_d of the short side: it is debonded whole and slides at P_0 (1 − s/L)(1 + β s/d), below what the long
  // side held; the long side holds its v_d(short) of pull-out.
  TwoSidedPullout t = kveton_crossing();
  const double slide = 0.5e-3;
  const double p = open_crack(f, t, 2 * vd + slide);
  CHECK(t.pullout[0] == mc::test::relative(vd, 1e-12));
  CHECK(t.pullout[1] == mc::test::relative(vd + slide, 1e-12));
  CHECK(p == mc::test::relative(sliding_force(f, kShort, vd + slide), 1e-12));
  CHECK(p < pullout_resistance(f, 6.5e-3, t.pullout[0]));
  // Out: the short side gone, no force.
  CHECK(open_crack(f, t, 2 * vd + kShort) == 0.0);
}

TEST_CASE("two_sided_pullout_is_in_equilibrium_along_the_whole_opening_and_independent_of_the_steps") {
  // Sides of 3.5 and 6.5 mm (§6.1), 3.5 and 16.5 mm, and 5 and 16.5 mm: with β_f = 0.01 a slide hardens where
  // β L > d (L > 4 mm); the 5 mm side's rises to 1.0125 P_0 = 1.272 N, above the 1.2566 N the long side held at its
  // drop when G_d = 0, so the long side debonds again while the short one slides.
  const double sides[][2] = {{kShort, 6.5e-3}, {kShort, 16.5e-3}, {5e-3, 16.5e-3}};
  for (const auto& side : sides)
    for (const double beta : {-0.01, 0.0, 0.01})
      for (const double g : {0.0, 5.0}) {
        const double short_side = side[0], long_side = side[1];
        CAPTURE(short_side);
        CAPTURE(long_side);
        CAPTURE(beta);
        CAPTURE(g);
        const FibreMaterial f = kveton_fibre(g, beta);
        TwoSidedPullout stepped = kveton_crossing(short_side, long_side);
        const double w_end = 1.2 * (short_side + full_debonding_slip(f, long_side));
        double long_after_drop = 0;  // the long side's largest pull-out while the short one slides
        double worst_sum = 0, worst_joint = 0, worst_weaker = 0, worst_stronger = 0;
        bool short_debonded_first = true;
        for (int k = 1; k <= 3000; ++k) {
          const double w = w_end * k / 3000.0;
          const double p = open_crack(f, stepped, w);
          worst_sum = std::max(worst_sum, std::abs(stepped.pullout[0] + stepped.pullout[1] - w) / w);
          double r[2];
          bool debonding[2];
          for (int i = 0; i < 2; ++i) {
            r[i] = pullout_resistance(f, stepped.embedment[i], stepped.pullout[i]);
            debonding[i] = stepped.pullout[i] < full_debonding_slip(f, stepped.embedment[i]);
          }
          if (p == 0) continue;  // pulled out
          // The force is what the weaker side slides at; the other resists at least as much.
          worst_weaker = std::max(worst_weaker, std::abs(std::min(r[0], r[1]) - p) / p);
          worst_stronger = std::max(worst_stronger, (p - std::max(r[0], r[1])) / p);
          // Both still debonding: both slide, at one force.
          if (debonding[0] && debonding[1]) worst_joint = std::max(worst_joint, std::abs(r[0] - r[1]) / p);
          // The long side (0) is never debonded whole while the short one (1) is not.
          if (!debonding[0] && debonding[1]) short_debonded_first = false;
          if (!debonding[1]) long_after_drop = std::max(long_after_drop, stepped.pullout[0]);
        }
        // Round-off: the opening is shared exactly, the debonding sides' forces agree to the closed form's bits.
        CHECK(worst_sum < 1e-12);
        CHECK(worst_weaker < 1e-12);
        CHECK(worst_stronger < 1e-12);
        CHECK(worst_joint < 1e-10);
        CHECK(short_debonded_first);
        // Only the hardening 5 mm slide, with no bond energy to drop from, loads the long side again.
        const bool reloads = short_side == 5e-3 && beta > 0 && g == 0;
        CHECK((long_after_drop > full_debonding_slip(f, short_side) * (1 + 1e-9)) == reloads);
        // One step to the same opening reaches the same pull-outs: the split does not depend on the path.
        for (const double w : {0.3 * w_end, 0.6 * w_end, w_end}) {
          TwoSidedPullout jumped = kveton_crossing(short_side, long_side), walked = jumped;
          open_crack(f, jumped, w);
          for (int k = 1; k <= 1000; ++k) open_crack(f, walked, w * k / 1000.0);
          CHECK(jumped.pullout[0] == mc::test::relative(walked.pullout[0], 1e-9));
          CHECK(jumped.pullout[1] == mc::test::relative(walked.pullout[1], 1e-9));
        }
      }
}

TEST_CASE("two_sided_pullout_work_is_both_sides_debonding_and_the_short_sides_slide") {
  // β_f ≤ 0.01 on a 3.5 mm side (β L < d): the short side's slide softens, the long side holds from the drop on.
  // ∫F dw = 2 ∫₀^{v_d} P_deb dv + P_0 L (1/2 + β L/(6 d)), v_d and P_0 of the short side: the debonding half of each
  // side and the short side's slide, = pullout_work(short) + its debonding work again. Simpson's rule on the two
  // smooth pieces of F(w), either side of the drop at 2 v_d (G_d 5 N/m: no √ at the start): to 1e-10.
  for (const double beta : {-0.01, 0.0, 0.01}) {
    CAPTURE(beta);
    const FibreMaterial f = kveton_fibre(5.0, beta);
    const double vd = full_debonding_slip(f, kShort);
    // At w = 0 the crossing has not moved and carries nothing; from w = 0+ on it carries √(π² E_f d_f³ G_d/2) and
    // more: the integrand is taken from the right.
    auto force_at = [&](double w) {
      TwoSidedPullout t = kveton_crossing();
      return open_crack(f, t, std::max(w, 1e-15 * vd));
    };
    const double debonding = simpson(force_at, 0.0, 2 * vd, 2000);
    const double sliding = simpson(force_at, 2 * vd * (1 + 1e-15), 2 * vd + kShort, 2000);
    const double side_debonding = simpson([&](double v) { return debonding_force(f, v); }, 0.0, vd, 2000);
    MESSAGE("beta ", beta, ": both sides' debonding / closed form - 1 = ", debonding / (2 * side_debonding) - 1,
            ", the short side's slide / closed form - 1 = ", sliding / (pullout_work(f, kShort) - side_debonding) - 1);
    CHECK((debonding + sliding) == mc::test::relative(pullout_work(f, kShort) + side_debonding, 1e-10));
  }
}

TEST_CASE("fibre_bridge_breaks_for_good_where_the_snubbed_force_reaches_the_inclined_strength") {
  const FibreMaterial f = kveton_fibre();
  const double d = f.diameter, strength = f.tensile_strength * 0.25 * M_PI * d * d;  // 1.2566 N
  const double k = 0.5 * M_PI * M_PI * f.modulus * d * d * d;
  // The debonding pull-out at which (5.1) carries P: (P²/k − G_d)/τ_0, each side of a debonding crack v = w/2.
  auto breaking_opening = [&](double p) { return 2 * (p * p / k - f.debonding_energy) / f.friction_stress; };
  // Květoň §6.1: the 20 mm fibre (7 mm on its short side) breaks while it debonds, at 2 × 80.8 µm; the 10 mm one
  // never does: it pulls out of its 3.5 mm side.
  {
    FibreBridge long_fibre;
    long_fibre.sides.embedment[0] = 13e-3, long_fibre.sides.embedment[1] = 7e-3;
    const double w = breaking_opening(strength);
    CHECK(w == mc::test::relative(161.6e-6, 1e-3));
    CHECK(bridge_force(f, long_fibre, 0.99 * w, 0.0) > 0.9 * strength);
    CHECK(!long_fibre.ruptured);
    CHECK(bridge_force(f, long_fibre, 1.01 * w, 0.0) == 0.0);
    CHECK(long_fibre.ruptured);
    // For good: closed and opened again, it carries nothing.
    CHECK(bridge_force(f, long_fibre, 0.0, 0.0) == 0.0);
    CHECK(bridge_force(f, long_fibre, 0.5 * w, 0.0) == 0.0);
  }
  {
    FibreBridge short_fibre;
    short_fibre.sides.embedment[0] = 6.5e-3, short_fibre.sides.embedment[1] = kShort;
    // Its largest force at 2 v_d, where the short side is debonded whole: 1.097 N, below the 1.2566 N it can bear.
    const double vd = full_debonding_slip(f, kShort), out = 2 * vd + kShort;
    double largest = 0;
    for (int i = 1; i <= 1000; ++i) largest = std::max(largest, bridge_force(f, short_fibre, 2 * vd * i / 1000, 0.0));
    for (int i = 1; i <= 1000; ++i)
      largest = std::max(largest, bridge_force(f, short_fibre, 2 * vd + kShort * i / 1000, 0.0));
    CHECK(!short_fibre.ruptured);
    CHECK(largest == mc::test::relative(debonding_force(f, vd), 1e-12));
    CHECK(bridge_force(f, short_fibre, out, 0.0) == 0.0);  // pulled out
  }
  // Inclined 0.5 rad with k_sn 0.1 and k_rup 0.33 (§6.4): the force is snubbed up by e^0.05 and the strength cut by
  // e^-0.165, so the long fibre breaks at the debonding force 1.2566 e^-0.215 N = 1.0134 N, sooner.
  FibreMaterial micro = f;
  micro.snubbing_coefficient = 0.1, micro.rupture_coefficient = 0.33;
  FibreBridge inclined;
  inclined.sides.embedment[0] = 13e-3, inclined.sides.embedment[1] = 7e-3;
  const double w = breaking_opening(strength * std::exp(-0.215));
  CHECK(bridge_force(micro, inclined, 0.99 * w, 0.5) > 0.0);
  CHECK(bridge_force(micro, inclined, 1.01 * w, 0.5) == 0.0);
  CHECK(inclined.ruptured);
}

TEST_CASE("fibre_bridge_unloads_on_its_secant_keeps_its_slip_and_resumes_the_law_where_it_left_it") {
  const FibreMaterial f = kveton_fibre();
  const double area = 0.25 * M_PI * f.diameter * f.diameter;
  auto fresh = [] {
    FibreBridge b;
    b.sides.embedment[0] = 6.5e-3, b.sides.embedment[1] = kShort;
    return b;
  };
  // The elastic start: below P(0)/k the bonded fibre opens elastically, k = E_f A_f/d_f = 942.5 kN/m.
  FibreBridge start = fresh();
  const double k = bonded_stiffness(f);
  CHECK(k == mc::test::relative(f.modulus * area / f.diameter, 1e-14));
  CHECK(bridge_force(f, start, 1e-8, 0.0) == mc::test::relative(k * 1e-8, 1e-14));
  // Loaded to 40 µm, halfway through debonding: both sides pulled 20 µm, on (5.1).
  FibreBridge b = fresh(), monotone = fresh();
  const double w1 = 40e-6, f1 = bridge_force(f, b, w1, 0.0);
  CHECK(f1 == mc::test::relative(debonding_force(f, 0.5 * w1), 1e-10));
  CHECK(unloading_stiffness(b) == mc::test::relative(f1 / w1, 1e-14));
  // Unloaded along the secant to the origin: a third off the opening, a third off the force; closed, none.
  CHECK(bridge_force(f, b, w1 * 2 / 3, 0.0) == mc::test::relative(f1 * 2 / 3, 1e-12));
  CHECK(bridge_force(f, b, 0.0, 0.0) == 0.0);
  CHECK(b.sides.pullout[0] + b.sides.pullout[1] == mc::test::relative(w1, 1e-12));  // the slip stays
  // Reloaded: the same line up, the law from the largest opening on, as if never unloaded.
  CHECK(bridge_force(f, b, w1, 0.0) == mc::test::relative(f1, 1e-12));
  bridge_force(f, monotone, w1, 0.0);
  for (double w : {60e-6, 120e-6, 1e-3})
    CHECK(bridge_force(f, b, w, 0.0) == mc::test::relative(bridge_force(f, monotone, w, 0.0), 1e-12));
}
