// The parallel bond run kLanes contacts at a time (contact_models/parallel_bond_lanes.hpp)
// must give the same bits as the one-contact law it mirrors. Energy tracing runs every contact through the
// one-contact law and changes no force, so a world stepped with tracing and one stepped without must agree to
// the last bit, through bonds carrying load, slipping grain contacts, bonds breaking and pieces flying apart.
#include <doctest/doctest.h>

#include <cstring>
#include <vector>

#include "contact_models/parallel_bond.hpp"
#include "engine/lanes.hpp"
#include "engine/random_stream.hpp"
#include "tests/common/test_worlds.hpp"

using namespace mc;

namespace {

// A 3D block of shrunk-at-random spheres on a layered hexagonal lattice (about 8 × 12 × 8 mm), bottom held, top
// pulled up at 0.3 m/s and sheared sideways at 0.1 m/s: the bonds load, yield to none, then break in tension and
// shear; the broken pairs slide with friction and part.
World<3> pulled_block(bool traced) {
  ParallelBondParams p;
  p.contact.modulus = 5e9, p.contact.kn_ks_ratio = 2.5, p.contact.friction = 0.5;
  p.modulus = 10e9, p.kn_ks_ratio = 2.5;
  p.tensile_mean = 10e6, p.tensile_std = 2e6;
  p.shear_mean = 4e6, p.shear_std = 1e6;
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

bool same_bits(const std::vector<Vec<3>>& a, const std::vector<Vec<3>>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec<3>)) == 0;
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
  // The run went through failure: the block parted along a band of broken bonds, in tension and in shear.
  MESSAGE("bonds ", bonds, ", cracks ", lanes.cracks.size());
  CHECK(lanes.cracks.size() > bonds / 8);
  CHECK(lanes.crack_count(CrackKind::Break, CrackMode::Tensile) > 0);
  CHECK(lanes.crack_count(CrackKind::Break, CrackMode::Shear) > 0);
}
