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

}  // namespace

TEST_CASE("parallel_bond_in_lanes_gives_the_one_contact_bits_through_failure") {
  World<3> lanes = pulled_block(false), one = pulled_block(true);
  REQUIRE(lanes.particles.size() >= 8 * kLanes);
  const std::size_t bonds = lanes.bond_count();
  for (int s = 0; s < 6000; ++s) {
    lanes.step(), one.step();
    if (!same_bits(lanes.particles.x, one.particles.x) || !same_bits(lanes.particles.w, one.particles.w)) {
      FAIL("positions or spins differ at step ", s + 1);
      break;
    }
  }
  CHECK(same_bits(lanes.particles.v, one.particles.v));
  CHECK(lanes.cracks.size() == one.cracks.size());
  CHECK(pairs_with_other_bytes(static_cast<const ContactSet<ParallelBond, 3>&>(*lanes.sets[0]),
                               static_cast<const ContactSet<ParallelBond, 3>&>(*one.sets[0])) == 0);
  // The run went through failure: the block parted along a band of broken bonds, in tension and in shear.
  MESSAGE("bonds ", bonds, ", cracks ", lanes.cracks.size());
  CHECK(lanes.cracks.size() > bonds / 8);
  CHECK(lanes.crack_count(CrackKind::Break, CrackMode::Tensile) > 0);
  CHECK(lanes.crack_count(CrackKind::Break, CrackMode::Shear) > 0);
}

TEST_CASE("cpm_in_lanes_gives_the_one_contact_bits_through_damage_hardening_and_breakage") {
  for (const double pull : {2e-5, -2e-5}) {
    World<3> lanes = cpm_block(false, pull), one = cpm_block(true, pull);
    const std::size_t bonds = lanes.bond_count();
    int steps = 0;
    for (; steps < 400; ++steps) {
      lanes.step(), one.step();
      if (!same_bits(lanes.particles.x, one.particles.x) || !same_bits(lanes.particles.w, one.particles.w)) break;
    }
    CHECK_MESSAGE(steps == 400, "pull ", pull, ": positions or spins differ at step ", steps + 1);
    CHECK(same_bits(lanes.particles.v, one.particles.v));
    CHECK(lanes.cracks.size() == one.cracks.size());
    const auto& a = static_cast<const ContactSet<Cpm, 3>&>(*lanes.sets[0]);
    const auto& b = static_cast<const ContactSet<Cpm, 3>&>(*one.sets[0]);
    CHECK(pairs_with_other_bytes(a, b) == 0);
    // The run went through what the lanes must carry: contacts damaged past ε_0 (κ > ε_0 = 1e-4) and broken in
    // both runs, plastic hardening in compression.
    std::size_t damaged = 0, hardened = 0;
    for (std::size_t c = 0; c < a.pairs().size(); ++c) {
      const auto st = a.state(c);
      damaged += Cpm::bonded<3>(st) && st.kappa > 1e-4, hardened += st.eps_pl < 0;
    }
    MESSAGE("pull ", pull, ": bonds ", bonds, ", broken ", bonds - lanes.bond_count(), ", damaged ", damaged,
            ", hardened ", hardened);
    CHECK(lanes.crack_count(CrackKind::Break, CrackMode::Tensile) > 0);
    CHECK(damaged > 0);
    if (pull < 0) CHECK(hardened > bonds / 10);
  }
}
