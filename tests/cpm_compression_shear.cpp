// One cohesive CPM contact in compression and in shear (Šmilauer, "Compressive plasticity", "Shear stresses",
// "Confinement extension"). Compression never damages; beyond ε_s the stress follows the hardening line
// k_N (ε_s + K̃_s (ε_N − ε_s)) and unloads elastically with k_N from there. Sheared at a held normal strain, the
// shear stress rises with k_T and is returned radially onto the yield surface: c_T0 (1 − ω) − σ_N tan φ in
// tension, c_T0 [(1 − ω) + Y_0 tan φ ln(1 − σ_N/(c_T0 Y_0))] in compression.
//
// Tolerances: the stresses come from the imposed strains through the closed forms, to round-off: 1e-9 of the
// stresses involved (strains of 1e-4…1e-2 lose ≤ 1e-12 to the distance). Shear moves the normal a little (the
// contact plane tilts by |Δu_T|/L ≲ 1e-3 rad), so the yield check uses the σ_N the contact actually has.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "contact_models/cpm.hpp"
#include "tests/common/cpm_pair.hpp"
#include "tests/common/relative.hpp"

using namespace mc;

TEST_CASE("cpm: compression never damages and hardens from eps_s with modulus K_s k_N") {
  const CpmParams p = test::cpm_params();
  const double es = p.hardening_strain, kn = p.modulus, ks = p.hardening_modulus_ratio;
  auto c = test::cpm_pair(p);
  c.strain_to(3 * es, 2e-6);  // loading: elastic to ε_s, then the hardening line
  const std::size_t unload = c.eps.size();
  c.strain_to(2 * es, 2e-6);  // unloading: elastic with k_N
  const std::size_t reload = c.eps.size();
  c.strain_to(4 * es, 2e-6);  // reloading: elastic back to the line, then along it
  auto line = [&](double e) { return kn * (es + ks * (e - es)); };
  const double scale = std::abs(kn * es);
  double dev = 0;
  for (std::size_t k = 0; k < unload; ++k)
    dev = std::max(dev, std::abs(c.sigma_n[k] - (c.eps[k] > es ? kn * c.eps[k] : line(c.eps[k]))));
  // The plastic strain after loading to 3 ε_s: the line's stress there, unloaded with k_N.
  const double eps_pl = 3 * es - line(3 * es) / kn;
  for (std::size_t k = unload; k < reload; ++k) dev = std::max(dev, std::abs(c.sigma_n[k] - kn * (c.eps[k] - eps_pl)));
  for (std::size_t k = reload; k < c.eps.size(); ++k)
    dev = std::max(dev, std::abs(c.sigma_n[k] - std::max(kn * (c.eps[k] - eps_pl), line(c.eps[k]))));
  MESSAGE("max deviation from the bilinear hardening law / |k_N eps_s| = ", dev / scale,
          ", plastic strain / eps_s = ", c.state().eps_pl / es);
  CHECK(dev < 1e-9 * scale);
  // The tangent beyond ε_s is K̃_s k_N, from two points on the line.
  const std::size_t a = unload / 2 + unload / 4, b = unload - 1;
  CHECK((c.sigma_n[b] - c.sigma_n[a]) / (c.eps[b] - c.eps[a]) == mc::test::relative(ks * kn, 1e-8));
  // Never damaged: κ stayed 0, no crack was logged, the contact is intact.
  CHECK(c.state().kappa == 0.0);
  CHECK(c.w.cracks.empty());
  CHECK(c.w.bond_count() == 1);
}

namespace {

// Holds the normal strain at eps_n and shears along y until well past yield; checks that every stress is
// either inside the surface with |σ_T| = k_T |ε_T| or on it.
struct Sheared {
  double sn, st, eps, omega;  // the last force pass: σ_N, |σ_T|, ε_N; the contact's damage
};
Sheared shear_at(const CpmParams& p, double eps_n, double kappa_first = 0) {
  auto c = test::cpm_pair(p);
  if (kappa_first > 0) c.strain_to(kappa_first, 2e-7);  // damage the contact first
  c.strain_to(eps_n, 2e-7);
  const double omega = Cpm::damage(p, c.state().kappa);
  const auto coeffs = Cpm::pair<3>(p, test::kCpmR, test::kCpmR);
  // Shear strain steps of r_pl/(300 k_T) at the start: yield after about 300 steps, 300 more on the surface
  // (to twice the yield strain: the plane tilts by θ ≲ 2 r_pl/k_T ≲ 2e-2, stretching the pair by θ²/2).
  const double r0 = Cpm::yield_radius(coeffs, p.modulus * eps_n * (eps_n > 0 ? 1 - omega : 1), omega);
  const double vy = r0 / (300 * coeffs.kt) * c.length / c.w.dt;
  int yielded = 0;
  double dev = 0, elastic_dev = 0;
  for (int k = 0; k < 600; ++k) {
    // The tangential displacement since shearing began (B started at y = 0), with this step's: the force pass
    // increments ε_T by the velocity it sees, v Δt, before the move.
    const double ut = c.d()[1] + vy * c.w.dt;
    c.step(Vec<3>(0, vy, 0));
    const double sn = c.sigma_n.back(), st = c.sigma_t.back();
    const double r_pl = Cpm::yield_radius(coeffs, sn, omega);
    if (st < r_pl * (1 - 1e-9)) {
      elastic_dev = std::max(elastic_dev, std::abs(st - coeffs.kt * ut / c.length) / r_pl);
    } else {
      ++yielded;
      dev = std::max(dev, std::abs(st - r_pl) / r_pl);
    }
  }
  MESSAGE("eps_N / eps_0 = ", eps_n / p.crack_onset_strain, ", omega = ", omega, ": sigma_N = ", c.sigma_n.back(),
          " Pa, |sigma_T| = ", c.sigma_t.back(), " Pa, r_pl = ", Cpm::yield_radius(coeffs, c.sigma_n.back(), omega),
          " Pa; on the surface ", yielded, " of 600 steps, max relative deviation ", dev, ", elastic ", elastic_dev);
  CHECK(yielded > 250);
  CHECK(dev < 1e-9);
  // Elastic steps carry k_T ε_T: the tilt of the plane makes |ε_T| differ from u_T/L by O(θ²).
  CHECK(elastic_dev < 1e-4);
  return {c.sigma_n.back(), c.sigma_t.back(), c.eps.back(), omega};
}

}  // namespace

TEST_CASE("cpm: the shear return lands on the linear yield surface in tension") {
  const CpmParams p = test::cpm_params();
  const double e0 = p.crack_onset_strain;
  // Undamaged, at half the onset strain: r_pl = c_T0 − σ_N tan φ.
  const auto [sn, st, e1, w1] = shear_at(p, 0.5 * e0);
  CHECK(st == mc::test::relative(p.cohesion - sn * p.tan_friction, 1e-9));
  // Damaged (κ = 2 ε_0), back at ε_0: r_pl = c_T0 (1 − ω) − σ_N tan φ.
  const auto [sn2, st2, e2, omega] = shear_at(p, e0, 2 * e0);
  CHECK(omega == mc::test::relative(Cpm::damage(p, 2 * e0), 1e-3));  // κ: the last strain before 2 ε_0
  CHECK(st2 == mc::test::relative(p.cohesion * (1 - omega) - sn2 * p.tan_friction, 1e-9));
  // σ_N on the secant; the tilting plane stretched the pair a little (θ²/2 ≈ 4.5e-6), still below κ.
  CHECK(e2 < 2 * e0);
  CHECK(sn2 == mc::test::relative((1 - omega) * p.modulus * e2, 1e-9));
  (void)e1, (void)w1;
}

TEST_CASE("cpm: the shear return lands on the logarithmic yield surface in compression") {
  const CpmParams p = test::cpm_params();
  const auto [sn, st, e1, w1] = shear_at(p, -20 * p.crack_onset_strain);
  (void)e1, (void)w1;
  CHECK(sn < 0);
  const double y0 = p.yield_log_speed;
  const double log_surface = p.cohesion * (1 + y0 * p.tan_friction * std::log(-sn / (p.cohesion * y0) + 1));
  CHECK(st == mc::test::relative(log_surface, 1e-9));
  // Below the linear surface of (23), which the logarithm leaves tangentially at σ_N = 0.
  CHECK(st < p.cohesion - sn * p.tan_friction);
  // With compression_yield = "linear" (Yade's public CpmMat) it is the linear surface again.
  CpmParams lin = p;
  lin.compression_yield = CpmYield::Linear;
  const auto [sn3, st3, e3, w3] = shear_at(lin, -20 * p.crack_onset_strain);
  (void)e3, (void)w3;
  CHECK(st3 == mc::test::relative(p.cohesion - sn3 * p.tan_friction, 1e-9));
}

// The force law takes the logarithmic yield radius only when the trial shear stress passes a lower bound of it
// (Cpm::may_yield, ln(1 + x) ≥ x/(1 + x)). The bound must never pass over a stress the yield radius as computed
// would return: over compressions from 1e-9 to 1e3 times c_T0 Y_0, damages 0–0.99 and trial stresses from 1e-6
// below to 1e-6 above the radius, may_yield is true wherever st > r_pl. Up to x = −σ_N/(c_T0 Y_0) = 1 the bound
// is at least x/(1 + x) / ln(1 + x) ≥ 0.72 of the radius, so a stress of half the radius skips the logarithm.
TEST_CASE("cpm: the lower bound that skips the logarithmic yield radius never skips a yielding contact") {
  const CpmParams p = test::cpm_params();
  const auto c = Cpm::pair<3>(p, test::kCpmR, test::kCpmR);
  const double scale = p.cohesion * p.yield_log_speed;
  int skipped = 0, near = 0, checked = 0;
  for (double x = 1e-9; x < 1e3; x *= 1.37)
    for (double omega : {0.0, 0.3, 0.9, 0.99}) {
      const double sn = -x * scale, r_pl = Cpm::yield_radius(c, sn, omega);
      for (double f : {1 - 1e-6, 1 - 1e-12, 1.0, 1 + 1e-12, 1 + 1e-6}) {
        const double st2 = (f * r_pl) * (f * r_pl);
        ++checked;
        if (st2 > r_pl * r_pl) CHECK_MESSAGE(Cpm::may_yield(c, sn, omega, st2), "x ", x, " omega ", omega, " f ", f);
      }
      if (x <= 1) ++near, skipped += !Cpm::may_yield(c, sn, omega, 0.25 * r_pl * r_pl);
    }
  CHECK(checked > 1000);
  CHECK(near > 100);
  CHECK(skipped == near);
}
