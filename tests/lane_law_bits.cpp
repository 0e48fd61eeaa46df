// The parallel bond and the CPM run kLanes contacts at a time (contact_models/parallel_bond_lanes.hpp,
// cpm_lanes.hpp) must give the same bits as the one-contact laws they mirror. Energy tracing runs every contact through
// the one-contact law and changes no force, so a world stepped with tracing and one stepped without must agree to the
// last bit, through bonds carrying load, slipping grain contacts, bonds breaking and pieces flying apart.
#include <doctest/doctest.h>

#include <cstring>
#include <vector>

#include "contact_models/cpm.hpp"
#include "contact_models/parallel_bond.hpp"
#include "engine/lanes.hpp"
#include "engine/random_stream.hpp"
#include "io/sphere_list.hpp"
#include "tests/common/cpm_pair.hpp"
#include "tests/common/test_worlds.hpp"

using namespace mc;

namespace {

// A 3D block of shrunk-at-random spheres on a layered hexagonal lattice (about 8 × 12 × 8 mm), bottom held, top
// pulled up at 0.3 m/s and sheared sideways at 0.1 m/s: the bonds load, yield to none, then break in tension and
// shear; the broken pairs slide with friction and part.
World<3> pulled_block(bool traced) {
  ParallelBondParams p;
  p.contact.modulus = 5e9, p.contact.kn_ks_ratio = 2.5, p.contact.friction = 0.5;
  p.bond_modulus.mean = 10e9, p.bond_kn_ks_ratio = 2.5;
  p.bond_tensile_strength.mean = 10e6, p.bond_tensile_strength.std = 2e6;
  p.bond_shear_strength.mean = 4e6, p.bond_shear_strength.std = 1e6;
  auto w = test::single_model_world<3, ParallelBond>(p);
  RandomStream rng(7);
  const double r = 1e-3, dx = 2 * r, dy = std::sqrt(3.0) * r;
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 7; ++j)
      for (int i = 0; i < 4; ++i) {
        const int n =
            w.particles.add(Vec<3>((i + 0.5 * (j % 2)) * dx, j * dy, k * dx), r * (1 - 0.15 * rng.uniform()), 2600, 0);
        if (j == 0 || j == 6) w.particles.fix[n] = 0xff;
        if (j == 6) w.particles.v[n] = Vec<3>(0.5, 0.05, 0);
      }
  w.local_damping = 0.05;
  w.trace_energy = traced;
  w.init();
  w.install_bonds(0.5, 5);
  return w;
}

// The CPM specimen of the scenes (2007 spheres), its end layers moved apart (`pull` > 0) or together at `pull` of
// the length per step, and sheared sideways at a fifth of it. The stiffness factors vary from sphere to sphere
// (heterogeneity), the confinement is on, and cohesive contacts break at ω = 0.9: in tension the contacts damage
// and break, in compression they harden, yield on the logarithmic surface, and broken pairs touch again.
World<3> cpm_block(bool traced, double pull) {
  const auto list = read_sphere_list<3>(MESOCRACK_SOURCE_DIR "/scenes/specimens/cpm_1x1x2.spheres");
  CpmParams p = test::cpm_params();
  p.break_damage = 0.9;
  p.confinement = -1e5;
  p.hardening_strain = -1e-3;
  auto w = test::single_model_world<3, Cpm>(p);
  RandomStream rng(11);
  for (int i = 0; i < list.size(); ++i) {
    const int n = w.particles.add(list.x[i], list.radius[i], 4800, 0);
    if (i % 3 == 0) w.particles.stiffness[n] = 0.8 + 0.4 * rng.uniform();
  }
  w.local_damping = 0.2;
  w.trace_energy = traced;
  w.init();
  w.install_bonds(0.0, 1);
  const double v = pull * 0.09 / w.dt;
  for (int i = 0; i < list.size(); ++i)
    if (list.tag[i] != 0) {
      w.particles.fix[i] = 0xff;
      const double sign = list.tag[i] == 2 ? 1.0 : -1.0;
      w.particles.v[i] = Vec<3>(0.2 * sign * std::abs(v), 0, sign * v);
    }
  return w;
}

bool same_bits(const std::vector<Vec<3>>& a, const std::vector<Vec<3>>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec<3>)) == 0;
}

// The pairs whose states' bytes differ between two contact sets of the same pairs.
template <class Set>
std::size_t pairs_with_other_bytes(const Set& a, const Set& b) {
  REQUIRE(a.pairs() == b.pairs());
  std::size_t differ = 0;
  for (std::size_t c = 0; c < a.pairs().size(); ++c) {
    const auto sa = a.state(c), sb = b.state(c);
    differ += std::memcmp(static_cast<const void*>(&sa), static_cast<const void*>(&sb), sizeof sa) != 0;
  }
  return differ;
}

// Each model with a lane law, the specimen it is run on and what the run must have gone through, so that equal bits
// mean something: the same checks, typed over the cases.
struct ParallelBondThroughFailure {
  using Model = ParallelBond;
  static constexpr int kSteps = 6000;
  static World<3> make(bool traced) { return pulled_block(traced); }
  // The block parted along a band of broken bonds, in tension and in shear.
  static void went_through(const World<3>& w, const ContactSet<Model, 3>&, std::size_t bonds) {
    MESSAGE("bonds ", bonds, ", cracks ", w.cracks.size());
    CHECK(w.cracks.size() > bonds / 8);
    CHECK(w.crack_count(CrackKind::Break, CrackMode::Tensile) > 0);
    CHECK(w.crack_count(CrackKind::Break, CrackMode::Shear) > 0);
  }
};

// CPM contacts damaged past ε_0 (κ > ε_0 = 1e-4) and broken; in compression, plastic hardening as well.
template <int Sign>
struct CpmThroughDamage {
  using Model = Cpm;
  static constexpr int kSteps = 400;
  static World<3> make(bool traced) { return cpm_block(traced, Sign * 2e-5); }
  static void went_through(const World<3>& w, const ContactSet<Model, 3>& set, std::size_t bonds) {
    std::size_t damaged = 0, hardened = 0;
    for (std::size_t c = 0; c < set.pairs().size(); ++c) {
      const auto st = set.state(c);
      damaged += Cpm::bonded<3>(st) && st.kappa > 1e-4, hardened += st.eps_pl < 0;
    }
    MESSAGE("pull ", Sign, ": bonds ", bonds, ", broken ", bonds - w.bond_count(), ", damaged ", damaged,
            ", hardened ", hardened);
    CHECK(w.crack_count(CrackKind::Break, CrackMode::Tensile) > 0);
    CHECK(damaged > 0);
    if (Sign < 0) CHECK(hardened > bonds / 10);
  }
};
using CpmPulled = CpmThroughDamage<1>;
using CpmPushed = CpmThroughDamage<-1>;

}  // namespace

// A world stepped in lanes (no energy tracing) and one stepped a contact at a time (tracing) keep the same positions,
// spins, velocities, crack logs and contact states to the last bit.
TEST_CASE_TEMPLATE("law_in_lanes_gives_the_one_contact_bits_through_what_the_specimen_goes_through", Case,
                   ParallelBondThroughFailure, CpmPulled, CpmPushed) {
  using Set = ContactSet<typename Case::Model, 3>;
  World<3> lanes = Case::make(false), one = Case::make(true);
  REQUIRE(lanes.particles.size() >= 8 * kLanes);
  const std::size_t bonds = lanes.bond_count();
  int steps = 0;
  for (; steps < Case::kSteps; ++steps) {
    lanes.step(), one.step();
    if (!same_bits(lanes.particles.x, one.particles.x) || !same_bits(lanes.particles.w, one.particles.w)) break;
  }
  CHECK_MESSAGE(steps == Case::kSteps, "positions or spins differ at step ", steps + 1);
  CHECK(same_bits(lanes.particles.v, one.particles.v));
  CHECK(lanes.cracks.size() == one.cracks.size());
  const auto& a = static_cast<const Set&>(*lanes.sets[0]);
  CHECK(pairs_with_other_bytes(a, static_cast<const Set&>(*one.sets[0])) == 0);
  Case::went_through(lanes, a, bonds);
}
