// The CPM specimen of the scenes (2007 spheres, 12 918 cohesive contacts: more than the engine's threshold for
// splitting the contact loop between threads) pulled apart fast enough that contacts damage within 300 steps:
// one and two threads give the same bits, the same crack log in the same order and the same energies.
#include <doctest/doctest.h>
#include <omp.h>

#include <cstring>
#include <vector>

#include "contact_models/cpm.hpp"
#include "io/sphere_list.hpp"
#include "tests/common/cpm_pair.hpp"

using namespace mc;

namespace {

struct Outcome {
  std::vector<Vec<3>> x;
  std::vector<Crack<3>> cracks;
  double dissipated, fractured, strain;
};

Outcome pull(int threads) {
  omp_set_num_threads(threads);
  const auto list = read_sphere_list<3>(MESOCRACK_SOURCE_DIR "/scenes/specimens/cpm_1x1x2.spheres");
  CpmParams p = test::cpm_params();  // the scenes' moduli: a softer, more cohesive concrete
  p.modulus = 24e9;
  p.cohesion = 3.5e6;
  auto w = test::single_model_world<3, Cpm>(p);
  for (int i = 0; i < list.size(); ++i) w.particles.add(list.x[i], list.radius[i], 4800, 0);
  w.local_damping = 0.4;
  w.trace_energy = true;
  w.init();
  w.install_bonds(0.0, 1);
  // The end layers move apart at 2.5e-6 of the length per step, in z only.
  const double v = 2.5e-6 * 0.09 / w.dt;
  for (int i = 0; i < list.size(); ++i)
    if (list.tag[i] != 0) {
      w.particles.fix[i] = 0b100;  // z
      w.particles.v[i] = Vec<3>(0, 0, list.tag[i] == 2 ? v : -v);
    }
  for (int s = 0; s < 300; ++s) w.step();
  w.update_energy();
  return {w.particles.x, w.cracks, w.energy.dissipated_contacts, w.energy.dissipated_bonds, w.energy.strain};
}

}  // namespace

TEST_CASE("cpm: one and two threads give the same bits and the same crack log") {
  const Outcome a = pull(1), b = pull(2);
  omp_set_num_threads(1);
  MESSAGE(a.cracks.size(), " contacts began to damage; dissipated ", a.dissipated + a.fractured, " J, strain energy ", a.strain,
          " J");
  REQUIRE(a.cracks.size() > 100);  // the loop's events, not only its forces, are compared
  REQUIRE(a.x.size() == b.x.size());
  CHECK(std::memcmp(a.x.data(), b.x.data(), a.x.size() * sizeof(Vec<3>)) == 0);
  REQUIRE(a.cracks.size() == b.cracks.size());
  bool same = true;
  for (std::size_t k = 0; k < a.cracks.size(); ++k)
    same = same && a.cracks[k].a == b.cracks[k].a && a.cracks[k].b == b.cracks[k].b &&
           a.cracks[k].step == b.cracks[k].step;
  CHECK(same);
  CHECK(a.dissipated == b.dissipated);
  CHECK(a.fractured == b.fractured);
  CHECK(a.strain == b.strain);
}
