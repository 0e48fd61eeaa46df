// One cohesive CPM contact pulled apart (Šmilauer 15–16): σ_N = (1 − ω) k_N ε_N with ω = g(κ), κ the largest
// tensile strain so far. Unloading goes back along the secant to the origin, compression is undamaged, and
// reloading retraces the secant until κ, then follows the envelope. The contact is made at the start between
// spheres within R_I (r_a + r_b); spheres that meet later get non-cohesive contacts, which carry no tension.
//
// Tolerances: the stresses are read back from the force of the very strain the test imposed, so the closed
// forms hold to round-off. The strain (d − L)/L of ε ~ 1e-4 loses ~1e-16/1e-4 of its digits to the distance:
// 1e-9 of k_N ε_0 (a thousandfold margin) bounds every stress difference.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "contact_models/cpm.hpp"
#include "tests/common/cpm_pair.hpp"
#include "tests/common/relative.hpp"

using namespace mc;

namespace {

// The closed form of the document: ω = 1 − (ε_0/κ) exp(−(κ − ε_0)/ε_f) above ε_0 (see Cpm::damage on the
// printed ε_f/κ).
double g_of(const CpmParams& p, double kappa) {
  const double e0 = p.crack_onset_strain, ef = e0 * p.relative_ductility;
  return kappa <= e0 ? 0.0 : 1.0 - e0 / kappa * std::exp(-(kappa - e0) / ef);
}

// σ_N of (15) along a strain history, κ the running maximum.
std::vector<double> closed_form(const CpmParams& p, const std::vector<double>& eps) {
  std::vector<double> s;
  double kappa = 0;
  for (double e : eps) {
    kappa = std::max(kappa, e);
    s.push_back((e > 0 ? 1.0 - g_of(p, kappa) : 1.0) * p.modulus * e);
  }
  return s;
}

double max_deviation(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0;
  for (std::size_t k = 0; k < a.size(); ++k) m = std::max(m, std::abs(a[k] - b[k]));
  return m;
}

}  // namespace

TEST_CASE("cpm: the tensile stress-strain curve is (1 - omega) k_N eps with omega = g(kappa)") {
  const CpmParams p = test::cpm_params();
  auto c = test::cpm_pair(p);
  c.strain_to(20 * p.crack_onset_strain, 2e-7);  // 10 000 steps, far into the softening tail
  const auto expected = closed_form(p, c.eps);
  const double ft = p.modulus * p.crack_onset_strain;
  const double dev = max_deviation(c.sigma_n, expected);
  const double peak = *std::max_element(c.sigma_n.begin(), c.sigma_n.end());
  MESSAGE("max |sigma - (1-omega) k_N eps| / (k_N eps_0) = ", dev / ft, ", peak / (k_N eps_0) = ", peak / ft,
          ", kappa / eps_0 = ", c.state().kappa / p.crack_onset_strain);
  CHECK(dev < 1e-9 * ft);
  // The peak is k_N ε_0 (the local tensile strength), reached at ε_0, then the exponential softening.
  CHECK(peak == mc::test::relative(ft, 2e-3));  // the sampling: strain steps of 2e-3 ε_0
  const double e_last = c.eps.back();                // σ = k_N ε_0 exp(−(κ − ε_0)/ε_f) on the envelope
  CHECK(c.sigma_n.back() == mc::test::relative(ft * std::exp(-(e_last - p.crack_onset_strain) / 3e-3), 1e-9));
  CHECK(c.state().kappa == mc::test::relative(c.eps.back(), 1e-12));
  // No shear was imposed, so none appears.
  CHECK(*std::max_element(c.sigma_t.begin(), c.sigma_t.end()) < 1e-9 * ft);
  // The first damage went to the crack log once, as a tensile yield; nothing broke (break_damage = 1).
  REQUIRE(c.w.cracks.size() == 1);
  CHECK(c.w.cracks[0].kind == CrackKind::Yield);
  CHECK(c.w.cracks[0].mode == CrackMode::Tensile);
  CHECK(c.w.bond_count() == 1);
}

TEST_CASE("cpm: unloading is secant to the origin, compression undamaged, reloading retraces the secant") {
  const CpmParams p = test::cpm_params();
  const double e0 = p.crack_onset_strain;
  auto c = test::cpm_pair(p);
  c.strain_to(3 * e0, 2e-7);  // into softening: κ = 3 ε_0
  const std::size_t unload = c.eps.size();
  c.strain_to(-2 * e0, 2e-7);  // back through the origin into compression
  const std::size_t reload = c.eps.size();
  c.strain_to(6 * e0, 2e-7);  // past the old κ, onto the envelope again
  const auto expected = closed_form(p, c.eps);
  const double ft = p.modulus * e0;
  CHECK(max_deviation(c.sigma_n, expected) < 1e-9 * ft);
  // The unloading branch is one straight line through the origin, of slope (1 − g(3 ε_0)) k_N.
  const double secant = (1 - g_of(p, 3 * e0)) * p.modulus;
  for (std::size_t k = unload; k < reload; ++k)
    if (c.eps[k] > 0)
      CHECK(c.sigma_n[k] == mc::test::relative(secant * c.eps[k], 1e-9));
    else
      CHECK(c.sigma_n[k] == mc::test::relative(p.modulus * c.eps[k], 1e-9));  // compression: k_N
  // Reloading below κ retraces it; κ grows again only past 3 ε_0.
  double kappa_mid = 0;
  for (std::size_t k = reload; k < c.eps.size(); ++k)
    if (c.eps[k] > 0 && c.eps[k] < 2.9 * e0) CHECK(c.sigma_n[k] == mc::test::relative(secant * c.eps[k], 1e-9));
  kappa_mid = c.state().kappa;
  MESSAGE("secant slope / k_N = ", secant / p.modulus, ", final kappa / eps_0 = ", kappa_mid / e0);
  CHECK(kappa_mid == mc::test::relative(c.eps.back(), 1e-12));
}

TEST_CASE("cpm: never_damage keeps a cohesive contact elastic in tension") {
  CpmParams p = test::cpm_params();
  p.never_damage = true;
  auto c = test::cpm_pair(p);
  c.strain_to(10 * p.crack_onset_strain, 1e-6);
  for (std::size_t k = 0; k < c.eps.size(); ++k)
    CHECK(c.sigma_n[k] ==
          doctest::Approx(p.modulus * c.eps[k]).epsilon(1e-9).scale(1e-9 * p.modulus * p.crack_onset_strain));
  CHECK(c.w.cracks.empty());
}

TEST_CASE("cpm: a contact damaged to break_damage breaks, and the spheres then part without force") {
  CpmParams p = test::cpm_params();
  p.break_damage = 0.9;
  auto c = test::cpm_pair(p);
  c.strain_to(200 * p.crack_onset_strain, 5e-6);
  // ω = 0.9 at κ: 1 − (ε_0/κ) e^{−(κ − ε_0)/ε_f} = 0.9; after that no cohesion, no tension.
  REQUIRE(c.w.cracks.size() == 2);
  CHECK(c.w.cracks[0].kind == CrackKind::Yield);
  CHECK(c.w.cracks[1].kind == CrackKind::Break);
  CHECK(c.w.cracks[1].mode == CrackMode::Tensile);
  CHECK(c.w.bond_count() == 0);
  CHECK(std::abs(c.sigma_n.back()) == 0.0);
  std::size_t broke = 0;
  while (broke < c.eps.size() && g_of(p, c.eps[broke]) < 0.9) ++broke;
  MESSAGE("broke at eps / eps_0 = ", c.eps[broke] / p.crack_onset_strain, " (omega = ", g_of(p, c.eps[broke]), ")");
  CHECK(c.w.cracks[1].step == static_cast<std::int64_t>(broke) + 1);
}

TEST_CASE("cpm: cohesive contacts within the interaction radius, non-cohesive ones for spheres that meet later") {
  const CpmParams p = test::cpm_params();  // R_I = 1.5
  auto w = test::single_model_world<3, Cpm>(p);
  const double r = test::kCpmR;
  // Centre distances 2.9 r (≤ 1.5·2r: cohesive), 3.1 r (beyond: no contact) and the same pair moved to touch.
  w.particles.add(Vec<3>(0, 0, 0), r, 2600, 0);
  w.particles.add(Vec<3>(2.9 * r, 0, 0), r, 2600, 0);
  w.particles.add(Vec<3>(0, 10 * r, 0), r, 2600, 0);
  w.particles.add(Vec<3>(3.1 * r, 10 * r, 0), r, 2600, 0);
  w.particles.fix.assign(4, 0xff);
  w.init();
  CHECK(w.install_bonds(0.0, 1) == 1);
  CHECK(w.bond_count() == 1);
  // The 3.1 r pair approaches: no force while apart, compression only while overlapping, measured from
  // touching (L = r_a + r_b): σ_N = k_N ε_N, ε_N = −overlap/(2r); and no tension when it parts again.
  const double speed = 1.1e-4 * r / w.dt;  // 1.1 r closed in 10 000 steps, then 50 more into overlap
  w.particles.v[3] = Vec<3>(-speed, 0, 0);
  const auto& set = static_cast<const ContactSet<Cpm, 3>&>(*w.sets[0]);
  double max_dev = 0, peak = 0;
  for (int k = 0; k < 20200; ++k) {
    const double overlap = 2 * r - (w.particles.x[3] - w.particles.x[2]).norm();
    if (k == 10050) w.particles.v[3] = Vec<3>(speed, 0, 0);  // reverse: part again
    w.step();
    const auto& pairs = set.pairs();
    const auto it = std::find(pairs.begin(), pairs.end(), Pair{2, 3});
    const double f = it == pairs.end() ? 0.0 : w.contact_force(0, it - pairs.begin())[0];
    const double expected = overlap > 0 ? 30e9 * overlap / (2 * r) * M_PI * r * r : 0.0;  // force on B along +x
    max_dev = std::max(max_dev, std::abs(f - expected));
    peak = std::max(peak, expected);
    if (it != pairs.end()) CHECK(!Cpm::bonded<3>(set.state(it - pairs.begin())));
  }
  MESSAGE("non-cohesive contact: peak force ", peak, " N, max deviation ", max_dev, " N");
  CHECK(peak > 0);
  CHECK(max_dev < 1e-9 * peak);
  CHECK(w.bond_count() == 1);
}
