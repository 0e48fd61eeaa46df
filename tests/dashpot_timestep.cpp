// Dashpots beside a contact's springs lower the stability limit of central differences from 2/ω to
// (2/ω)(√(1 + ζ²) − ζ) (Belytschko et al.), ζ the damping ratio of the mode, so the critical timestep the engine
// reports must carry that factor, for bonded pairs as for plain contacts. Two free spheres pressed together and bonded
// on the x axis, their dashpots at ζ = 0.9, stepped at the reported critical step itself
// (safety 1): a dashpot only takes energy out, so the springs' and the masses' energy must never rise above its
// start. Two ways to get it wrong, both measured here:
//  - no factor at all (a bond model whose ζ the engine did not see): the step is 1/(√1.81 − 0.9) = 2.25 times too
//    long, beyond the estimate's margin of 1.73 for the normal mode (ω² = 2k_n/m against the estimate's
//    √(m/(k_n + k_s)) with k_s = k_n/2): the bonded pair's energy grew 93-fold, or the guard stopped the run;
//  - the declared ζ for every mode: the shear dashpot also damps the spins, and the mode in which both spheres
//    slide and turn has a seventh of their mass at the contact point, so its ζ is √3.5 times the declared one: the
//    contact and softening bonds blew up within 31 steps (with their rotations held, they were stable).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "contact_models/contact_bond.hpp"
#include "contact_models/parallel_bond.hpp"
#include "contact_models/softening_bond.hpp"
#include "tests/common/test_worlds.hpp"

using namespace mc;

namespace {

constexpr double kZeta = 0.9;
constexpr double kR = 1e-3;  // [m]
// The grain contact beside a parallel bond has its dashpots only while it touches: the pair starts pressed by
// 0.5 % of a radius.
constexpr double kOverlap = 5e-6;  // [m]

LinearParams damped_contact() {
  LinearParams c;
  c.modulus = 1e9;
  c.kn_ks_ratio = 2.0;  // the normal mode governs the estimate (with k_s = k_n the spin would)
  c.friction = 0.5;
  c.damping_ratio = kZeta;
  return c;
}

template <class Model>
typename Model::Params damped_bond();

template <>
ContactBondParams damped_bond<ContactBond>() {
  ContactBondParams p;
  p.contact = damped_contact();
  p.bond_normal_strength.mean = p.bond_shear_strength.mean = 1e12;  // never breaks here
  return p;
}
template <>
SofteningBondParams damped_bond<SofteningBond>() {
  SofteningBondParams p;
  static_cast<ContactBondParams&>(p) = damped_bond<ContactBond>();
  p.bond_plastic_limit = 1e-3;
  return p;
}
template <>
ParallelBondParams damped_bond<ParallelBond>() {
  ParallelBondParams p;
  p.contact = damped_contact();
  p.bond_modulus.mean = 1e6;  // the bond's springs (without dashpots) far softer than the contact's
  p.bond_kn_ks_ratio = 1.0;
  p.bond_tensile_strength.mean = p.bond_shear_strength.mean = 1e15;
  return p;
}

// The largest kinetic + strain energy over the run, relative to the first, for the pair bonded at rest and B set
// moving along x and y (stretching, shearing and turning the bond). A plain contact would not do: pressed, the
// spheres fly apart within a few steps.
template <class Model>
double largest_energy_over_start(int steps) {
  auto w = test::single_model_world<3, Model>(damped_bond<Model>());
  w.particles.add(Vec<3>::Zero(), kR, 2600, 0);
  w.particles.add(Vec<3>(2 * kR - kOverlap, 0, 0), kR, 2600, 0);
  w.timestep.safety = 1.0;
  w.init();
  REQUIRE(w.install_bonds(0.01, 3) == 1);
  w.particles.v[1] = Vec<3>(0.01, 0.004, 0);
  test::start_energy(w);
  const double start = w.energy.initial;
  double largest = start;
  for (int k = 0; k < steps; ++k) {
    w.step();
    w.update_energy();
    largest = std::max(largest, w.energy.kinetic + w.energy.strain);
    if (!std::isfinite(largest)) break;
  }
  return largest / start;
}

template <class Model>
void dashpots_lower_the_step() {
  // 400 steps: the undamped estimate's step multiplies the energy by about 1.2 per step once the
  // unstable mode dominates, so past 400 it is beyond any rounding; the damped one has lost nearly all of it.
  const double ratio = largest_energy_over_start<Model>(400);
  MESSAGE(std::string(Model::name), ": largest energy over the start ", ratio);
  CHECK(ratio <= 1.0 + 1e-12);
}

}  // namespace

TEST_CASE("dashpots_of_a_contact_bond_lower_its_critical_timestep") { dashpots_lower_the_step<ContactBond>(); }
TEST_CASE("dashpots_of_a_softening_bond_lower_its_critical_timestep") { dashpots_lower_the_step<SofteningBond>(); }
TEST_CASE("dashpots_of_a_parallel_bond_lower_its_critical_timestep") { dashpots_lower_the_step<ParallelBond>(); }
