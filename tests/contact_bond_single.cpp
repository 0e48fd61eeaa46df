// One contact bond between two particles, driven kinematically: in tension the normal spring pulls with
// k_n·δ until the force reaches the normal strength, then the pair lets go; in shear under a fixed compression
// the shear spring holds well past μ·F_n (no slip while bonded) until the shear strength, then the pair slides
// at μ·F_n (PFC contact bond, Tang 2013 §3.3.3, Fig. 3.6). Energy released with the crack closes the balance.
#include <doctest/doctest.h>

#include <cmath>

#include "contact_models/contact_bond.hpp"
#include "tests/common/relative.hpp"
#include "tests/common/test_worlds.hpp"

using namespace mc;

namespace {

constexpr double kR = 1e-3;

ContactBondParams params(double normal, double shear) {
  return test::glued_bond_params<ContactBondParams>(normal, shear);
}

template <int D>
void tension_break() {
  const auto p = params(5.0, 1e9);
  // Bonded across a small gap (within the 1 % tolerance): the bond starts unstrained there.
  auto w = test::held_bonded_pair<D, ContactBond>(p, kR, kR, -0.002 * kR);
  const auto c = ContactBond::pair<D>(p, kR, kR);
  const double rate = p.bond_normal_strength.mean / c.kn / (4000 * w.dt);  // breaks after ~4000 steps
  w.particles.v[1][0] = rate;
  test::start_energy(w);
  auto& set = static_cast<ContactSet<ContactBond, D>&>(*w.sets[0]);
  double last = 0, stretch = 0, stiffness_ratio = 0;
  for (int step = 0; step < 10000 && w.cracks.empty(); ++step) {
    w.step();
    if (!w.cracks.empty()) break;
    last = -w.contact_force(0, 0)[0];  // tension on B points back to A
    if (step == 1000) stiffness_ratio = last / (c.kn * stretch);
    stretch += rate * w.dt;  // the force pass of this step saw the particles before this step's move
  }
  REQUIRE(w.cracks.size() == 1);
  CHECK(w.cracks[0].mode == CrackMode::Tensile);
  // F = k_n δ from the bonded position; δ ~ 1e-9 m is a difference of coordinates ~ 1e-3 m: round-off ~ 1e-7.
  CHECK(stiffness_ratio == mc::test::relative(1.0, 1e-6));
  // Each step adds 1/4000 of the strength: the last intact force sits within 0.025 % below it.
  CHECK(last / p.bond_normal_strength.mean == mc::test::relative(1.0, 5e-4));
  CHECK(last <= p.bond_normal_strength.mean);
  w.step();
  CHECK(w.contact_force(0, 0).norm() == 0.0);  // apart and unbonded: no force
  CHECK(!ContactBond::bonded<D>(set.state(0)));
  // Work of the moving particle = energy released by the crack (the stretched spring). Work is booked with
  // the force at the start of each step: the sum differs from ∫F dx by about one of the 4000 loading steps.
  w.update_energy();
  CHECK(w.energy.dissipated_bonds == mc::test::relative(0.5 * last * last / c.kn, 1e-3));
  CHECK(std::abs(w.energy.residual()) < 1e-3 * w.energy.boundary_work);
}

template <int D>
void shear_break_then_slide() {
  const auto p = params(1e9, 0.5);
  const auto c = ContactBond::pair<D>(p, kR, kR);
  // Pressed so that μF_n is 1.5 % of the shear strength: the bond must hold far beyond the slip limit. The
  // overlap (≥ 2.5e-11 m) stays much larger than the widening of the gap as the pair shears, (F_s/k_s)²/4R.
  const double overlap = 0.05 * p.bond_shear_strength.mean / c.kn;
  auto w = test::held_bonded_pair<D, ContactBond>(p, kR, kR, overlap);
  const double rate = p.bond_shear_strength.mean / c.ks / (4000 * w.dt);
  // Both particles move sideways in opposite senses: the line of centres turns, but only by ~1e-3 rad.
  w.particles.v[1][1] = 0.5 * rate;
  w.particles.v[0][1] = -0.5 * rate;
  test::start_energy(w);
  double last = 0;
  std::int64_t broke_at = -1;
  Vec<D> gap_before = Vec<D>::Zero();  // x_B − x_A where the last step's force pass took the overlap
  for (int step = 0; step < 12000; ++step) {
    gap_before = w.particles.x[1] - w.particles.x[0];
    w.step();
    if (!w.cracks.empty() && broke_at < 0) broke_at = w.step_count;
    if (broke_at < 0) last = -w.contact_force(0, 0)[1];  // the shear force on B opposes its motion (+y)
  }
  REQUIRE(w.cracks.size() == 1);
  CHECK(w.cracks[0].mode == CrackMode::Shear);
  CHECK(last / p.bond_shear_strength.mean == mc::test::relative(1.0, 5e-4));  // held to its strength without slipping
  // Sliding after the break: |F_s| = μ F_n exactly (the normal force is that of the overlap).
  const Vec<D> f = w.contact_force(0, 0);
  const Vec<D> n = (w.particles.x[1] - w.particles.x[0]).normalized();
  const double f_n = f.dot(n), f_s = (f - f.dot(n) * n).norm();
  CHECK(f_s / (p.contact.friction * f_n) == mc::test::relative(1.0, 1e-6));  // round-off of |F_s| ≪ |F|
  // The overlap of the positions the last force pass saw (the step then moved them: in 3D, k_n 2e6 N/m, by 9e-14 m
  // on an overlap of 1.2e-8 m, 8e-6 of it), a difference of coordinates ~ 1e-3 m: round-off ~ 1e-19 m on ≥ 2.5e-11 m.
  CHECK(f_n == mc::test::relative(c.kn * (2 * kR - gap_before.norm()), 1e-6));
  // Work of the moving pair = shear energy released at the break + friction work since; booked with the
  // force at the start of each step (one loading step in 4000).
  w.update_energy();
  CHECK(std::abs(w.energy.residual()) < 1e-3 * w.energy.boundary_work);
}

}  // namespace

TEST_CASE("contact_bond_tension_stiffness_and_break_at_normal_strength_2d") { tension_break<2>(); }
TEST_CASE("contact_bond_tension_stiffness_and_break_at_normal_strength_3d") { tension_break<3>(); }
TEST_CASE("contact_bond_shear_break_at_strength_then_slides_at_mu_fn_2d") { shear_break_then_slide<2>(); }
TEST_CASE("contact_bond_shear_break_at_strength_then_slides_at_mu_fn_3d") { shear_break_then_slide<3>(); }
