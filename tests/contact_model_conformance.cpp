// What every registered contact model must do, checked the same way for each (as LAMMPS and HOOMD check every
// style): typed over RegisteredModels (scene/model_registry.hpp), on the parameters its key table gives as examples,
// so a model added to the registry is checked with nothing added here.
//  0. Its key table is its own (named after it), documents every key and gives an example for each required one.
//  1. The stiffness it reports (what the timestep is estimated from, Tang 3.22–3.24) is the force it answers a
//     small increment with: normal, shear and, for models that carry moments, rotation.
//  2. The energy it reports stored, plus what it reports dissipated, is the work done on it along a load–unload
//     path (compression, shear there and back, bending and twisting there and back, release).
//  3. A world of it restored from a checkpoint steps on to the same bits as one never stopped.
#include <doctest/doctest.h>

#include <cmath>
#include <tuple>
#include <type_traits>
#include <vector>

#include "scene/model_registry.hpp"
#include "tests/common/relative.hpp"
#include "tests/common/test_worlds.hpp"

using namespace mc;

namespace {

// Sample parameters for each model: its key table's examples, read as a scene's [[contacts]] entry would be. They
// are a concrete's, and the loads below stay far inside them: no bond breaks or yields, no contact slips.
template <class M>
typename M::Params sample_params() {
  const TomlDoc doc = TomlDoc::parse_text(example_entry(M::keys()), std::string(M::name) + " examples");
  return read_keys<typename M::Params>(doc.root(), M::keys());
}

constexpr double kR = 1e-3;   // both radii [m]
constexpr double kU0 = 2e-5;  // the contact's overlap when loading starts (≥ 1 % of R, where Hertz–Mindlin
                              // reports its tangent stiffness rather than a floor)
constexpr double kDt = 1e-7;  // [s]

// One contact on the x axis, A at rest, B moving with v_rel and spinning relative to A with w_rel for one step.
template <class M, int D>
struct SingleContact {
  typename M::Params params = sample_params<M>();
  typename M::Coeffs coeffs = M::template pair<D>(params, kR, kR, 1.0, 1.0);
  typename M::template State<D> state{};
  ContactGeometry<D> g{};
  ContactForce<D> last{};

  SingleContact() {
    g.n = Vec<D>::UnitX();
    g.overlap = kU0;
    g.v_rel = Vec<D>::Zero();
    g.w_rel = Rot<D>::Zero();
    g.spin_n = 0;
    g.r_a = g.r_b = kR;
    g.m_a = g.m_b = 2600 * Dim<D>::volume(kR);
    g.k_a = g.k_b = 1;
    g.dt = kDt;
    if constexpr (BondModel<M, D>) {
      PairRandom rng(1, Pair{0, 1});
      M::template install<D>(params, g, state, rng);
    }
    last = M::template force<D, true>(coeffs, g, state);  // the force at the start, with no motion
  }
  // One step: B moves by du (the overlap shrinks by du·n) and turns by dtheta relative to A.
  ContactForce<D> step(const Vec<D>& du, const Rot<D>& dtheta) {
    g.v_rel = du / kDt;
    g.w_rel = dtheta / kDt;
    g.overlap -= du.dot(g.n);
    last = M::template force<D, true>(coeffs, g, state);
    return last;
  }
  ContactStiffness stiffness() const { return M::template stiffness<D>(coeffs, g, state); }
  double stored() const { return M::template strain_energy<D>(coeffs, g, state); }
};

template <int D>
Rot<D> about(int axis, double angle) {
  Rot<D> r = Rot<D>::Zero();
  r[D == 2 ? 0 : axis] = angle;
  return r;
}

// 1. Force against the reported stiffness, one small increment at a time.
template <class M, int D>
void stiffness_matches_force() {
  SingleContact<M, D> c;
  const ContactStiffness k = c.stiffness();
  REQUIRE(k.normal > 0);
  REQUIRE(k.shear > 0);
  constexpr double du = 1e-10;  // 5e-6 of the overlap: Hertz–Mindlin's secant is then its tangent to 4e-6
  const double f0n = c.last.force.dot(Vec<D>::UnitX());
  const double f1n = c.step(-du * Vec<D>::UnitX(), Rot<D>::Zero()).force.dot(Vec<D>::UnitX());
  CHECK((f1n - f0n) / du == mc::test::relative(k.normal, 1e-4));
  const double f0s = c.last.force[1];
  const double f1s = c.step(du * Vec<D>::UnitY(), Rot<D>::Zero()).force[1];
  CHECK(-(f1s - f0s) / du == mc::test::relative(c.stiffness().shear, 1e-4));
  // Rotation: a bond's bending moment (about z) and, in 3D, its twisting moment (about the normal, x); the
  // reported rotational stiffness is their sum (the timestep's bound for any axis). Models without moments
  // answer a turn with none.
  constexpr double dtheta = 1e-9;
  const double rot = c.stiffness().rotational;
  const Rot<D> m0 = c.last.moment;
  const double bend = -(c.step(Vec<D>::Zero(), about<D>(2, dtheta)).moment - m0)[D == 2 ? 0 : 2] / dtheta;
  double twist = 0;
  if constexpr (D == 3) {
    const Rot<D> m1 = c.last.moment;
    twist = -(c.step(Vec<D>::Zero(), about<D>(0, dtheta)).moment - m1)[0] / dtheta;
  }
  MESSAGE(std::string(M::name), " ", D, "D: k_n ", k.normal, ", k_s ", k.shear, ", rotational ", rot, " = bending ",
          bend, " + twisting ", twist);
  CHECK(bend + twist == doctest::Approx(rot).epsilon(1e-6).scale(1e-30));
}

// 2. Stored + dissipated = work, along a load–unload path. The work is summed with the trapezoid rule over each
// step's increments, exact for linear springs; for Hertz–Mindlin's F ∝ u^{3/2} its error over 200 steps of
// 5e-4 of the overlap each is ~1e-8 of the work.
template <class M, int D>
void stored_energy_is_work_done() {
  SingleContact<M, D> c;
  const double e0 = c.stored();
  double work = 0, dissipated = 0, worst = 0, scale = 0;
  auto go = [&](const Vec<D>& du, const Rot<D>& dtheta, int steps) {
    for (int k = 0; k < steps; ++k) {
      const ContactForce<D> before = c.last;
      const ContactForce<D> after = c.step(du, dtheta);
      // Work done on the contact: against the force and moment it exerts on B, through B's displacement and turn
      // relative to A.
      work -= 0.5 * (before.force + after.force).dot(du) + 0.5 * (before.moment + after.moment).dot(dtheta);
      dissipated += after.dissipated;
      scale = std::max(scale, std::abs(work));
      worst = std::max(worst, std::abs(c.stored() - e0 + dissipated - work));
    }
  };
  const Vec<D> in = -1e-8 * Vec<D>::UnitX(), across = 1e-9 * Vec<D>::UnitY();
  go(in, Rot<D>::Zero(), 100);                                      // compress by half the starting overlap
  go(across, Rot<D>::Zero(), 50), go(-across, Rot<D>::Zero(), 50);  // shear there and back
  go(Vec<D>::Zero(), about<D>(2, 1e-7), 50), go(Vec<D>::Zero(), about<D>(2, -1e-7), 50);                        // bend
  if constexpr (D == 3) go(Vec<D>::Zero(), about<D>(0, 1e-7), 50), go(Vec<D>::Zero(), about<D>(0, -1e-7), 50);  // twist
  go(-in, Rot<D>::Zero(), 100);  // release
  MESSAGE(std::string(M::name), " ", D, "D: work ", work, " J, stored ", c.stored() - e0, " J, dissipated ", dissipated,
          " J, worst imbalance ", worst, " J of a largest work ", scale, " J");
  REQUIRE(scale > 0);
  CHECK(worst <= 1e-6 * scale);
  CHECK(std::abs(c.stored() - e0) <= 1e-6 * scale);  // elastic throughout: back where it started
}

// 3. Checkpoint round trip: three bonded, moving, spinning particles; saved at step 40 and restored into a fresh
// world, both step on 40 more and must agree to the bit (positions, velocities, spins, contact states).
template <class M, int D>
World<D> moving_triplet() {
  auto w = test::single_model_world<D, M>(sample_params<M>());
  for (int i = 0; i < 3; ++i) {
    Vec<D> x = Vec<D>::Zero();
    x[0] = i * (2 * kR - kU0);
    w.particles.add(x, kR, 2600, 0);
    w.particles.v[i][0] = -0.01 * i;
    w.particles.v[i][1] = 0.005 * (i - 1);
    w.particles.w[i][0] = 3.0 * (1 - i);
  }
  w.init();
  w.install_bonds(0.01, 9);
  return w;
}

template <class M, int D>
void checkpoint_round_trip_is_exact() {
  auto a = moving_triplet<M, D>();
  for (int k = 0; k < 40; ++k) a.step();
  Archive saved;
  a.save(saved);
  auto b = moving_triplet<M, D>();
  b.restore(saved);
  for (int k = 0; k < 40; ++k) a.step(), b.step();
  CHECK(a.particles.x == b.particles.x);
  CHECK(a.particles.v == b.particles.v);
  CHECK(a.particles.w == b.particles.w);
  CHECK(a.sets[0]->save() == b.sets[0]->save());
  CHECK(a.step_count == 80);
}

template <class M>
void key_table_is_its_own() {
  const KeyTable& keys = M::keys();
  CHECK(keys.name == std::string_view(M::name));  // a model deriving from another declares its own table
  for (const Key& k : keys.keys) {
    CHECK_MESSAGE(!k.doc.empty(), std::string(k.name));
    if (k.need == Need::Required) CHECK_MESSAGE(!k.example.empty(), std::string(k.name));
  }
}

template <class M, int D>
void conformance() {
  SUBCASE("key table is its own") { key_table_is_its_own<M>(); }
  SUBCASE("stiffness matches force") { stiffness_matches_force<M, D>(); }
  SUBCASE("stored energy is work done") { stored_energy_is_work_done<M, D>(); }
  SUBCASE("checkpoint round trip is exact") { checkpoint_round_trip_is_exact<M, D>(); }
}

}  // namespace

TEST_CASE_TEMPLATE_DEFINE("contact_model_conformance_3d", M, conformance_3d) { conformance<M, 3>(); }
TEST_CASE_TEMPLATE_APPLY(conformance_3d, RegisteredModels);

// The models a 2D scene may use: the registered ones less the laws for spheres only.
template <class Models>
struct Planar;
template <class... Models>
struct Planar<std::tuple<Models...>> {
  using type = decltype(std::tuple_cat(
      std::conditional_t<requires { Models::only_3d; }, std::tuple<>, std::tuple<Models>>{}...));
};

TEST_CASE_TEMPLATE_DEFINE("contact_model_conformance_2d", M, conformance_2d) { conformance<M, 2>(); }
TEST_CASE_TEMPLATE_APPLY(conformance_2d, Planar<RegisteredModels>::type);
