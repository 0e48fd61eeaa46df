// PFC material genesis (preprocess/dense_packing): the grown packing has the porosity asked for, the settled
// one carries the isotropic stress asked for with hardly any overlap, floaters are few, and the same seed gives
// the same packing bit for bit.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "engine/cell_grid.hpp"
#include "preprocess/dense_packing.hpp"
#include "tests/common/relative.hpp"

using namespace mc;

namespace {

template <int D>
DensePackingSpec<D> spec(std::uint64_t seed) {
  DensePackingSpec<D> s;
  s.lo = Vec<D>::Zero();
  s.hi = Vec<D>::Constant(D == 2 ? 12e-3 : 10e-3);
  if constexpr (D == 2) s.hi[1] = 24e-3;
  s.radius_min = D == 2 ? 0.3e-3 : 0.5e-3;
  s.porosity = D == 2 ? 0.16 : 0.36;  // Tang §5.2: the porosities of his PFC2D / PFC3D specimens
  s.stress = 1e5;
  s.modulus = 20e9;
  s.density = 2400;
  s.seed = seed;
  return s;
}

template <int D>
void genesis() {
  const auto s = spec<D>(5);
  PackingReport rep;
  const Packing<D> p = dense_packing<D>(s, &rep);
  MESSAGE(D, "D: ", rep.count, " particles, porosity grown ", rep.porosity_grown, ", final ", rep.porosity_final,
          ", stress ", rep.stress_final, " Pa, floaters ", rep.after.floaters, ", coordination ",
          rep.after.coordination, ", steps ", rep.steps);
  REQUIRE(p.x.size() > 200);
  // Grown to exactly the porosity asked for (the radii are scaled to it; round-off only).
  CHECK(rep.porosity_grown == mc::test::relative(s.porosity, 1e-9));
  // Relieved to the isotropic stress within the genesis' 2 % tolerance; the packing loosens to its jammed
  // porosity at that stress (a few % above the grown one, see dense_packing.hpp), never denser than grown.
  CHECK(rep.stress_final == mc::test::relative(s.stress, 0.02));
  // These boxes are only 12–20 diameters wide: the looser layers along the walls weigh in (≈ +10 %).
  CHECK(rep.porosity_final >= rep.porosity_grown);
  CHECK(rep.porosity_final < 1.20 * s.porosity);
  // Rattlers: frictionless packings jammed at σ0/E_c = 5e-6 hold 10–20 % (more along walls).
  CHECK(rep.after.floaters < 0.25 * rep.count);
  // Without floater removal the report counts the packing as it is: floaters are the particles with fewer than
  // D + 1 neighbours closer than 1e-3 R_min, counted here afresh; the coordination is 2 C / N of the same.
  REQUIRE(rep.floater_contacts == D + 1);
  CHECK(rep.floaters_grown == 0);
  int floaters = 0, ends = 0;
  std::vector<int> near(p.x.size(), 0);
  for (const Pair& pr : candidate_pairs<D>(p.x, p.radius, 1e-3 * s.radius_min)) {
    const double gap = (p.x[pr[1]] - p.x[pr[0]]).norm() - p.radius[pr[0]] - p.radius[pr[1]];
    if (gap < 1e-3 * s.radius_min) ends += 2, ++near[pr[0]], ++near[pr[1]];
  }
  for (int k : near) floaters += k < D + 1;
  CHECK(rep.after.floaters == floaters);
  CHECK(rep.after.floater_share == mc::test::relative(double(floaters) / p.x.size(), 1e-12));
  CHECK(rep.after.coordination == mc::test::relative(double(ends) / p.x.size(), 1e-12));
  CHECK(rep.before.floaters == rep.after.floaters);
  // Inside the box, and overlaps of the order σ0/E_c R only (≈ 5e-6 R), far below the 1e-3 R asserted.
  double worst = 0;
  for (std::size_t i = 0; i < p.x.size(); ++i)
    for (int k = 0; k < D; ++k) {
      CHECK(p.x[i][k] > s.lo[k]);
      CHECK(p.x[i][k] < s.hi[k]);
    }
  for (const Pair& pr : candidate_pairs<D>(p.x, p.radius, 0.0)) {
    const double overlap = p.radius[pr[0]] + p.radius[pr[1]] - (p.x[pr[1]] - p.x[pr[0]]).norm();
    worst = std::max(worst, overlap / std::min(p.radius[pr[0]], p.radius[pr[1]]));
  }
  CHECK(worst < 1e-3);
  // Reproducible by seed, and a different seed gives a different packing (checked in 2D: the same code).
  if constexpr (D == 3) return;
  const Packing<D> again = dense_packing<D>(s);
  REQUIRE(again.x.size() == p.x.size());
  bool same = true;
  for (std::size_t i = 0; i < p.x.size(); ++i) same = same && again.x[i] == p.x[i] && again.radius[i] == p.radius[i];
  CHECK(same);
  const Packing<D> other = dense_packing<D>(spec<D>(6));
  CHECK((other.x.size() != p.x.size() || other.x[0] != p.x[0]));
}

}  // namespace

TEST_CASE("dense_packing_genesis_reaches_porosity_and_stress_and_is_reproducible_2d") { genesis<2>(); }
TEST_CASE("dense_packing_genesis_reaches_porosity_and_stress_and_is_reproducible_3d") { genesis<3>(); }

// A Brazilian disc (2D) or cylinder (3D) is carved from the packing of its box: every centre lies within the
// inscribed circle, and the share of the box's particles kept is the circle's share of the box's section (π/4 for
// a square section), within the sampling of a few hundred particles and the looser layer along the walls, which
// the corners cut away hold more of in a box only 7 (3D) to 20 (2D) diameters wide (±10 %; measured +1.5 %, +7 %).
template <int D>
void carved_cylinder() {
  auto s = spec<D>(5);
  s.hi = Vec<D>::Constant(12e-3);
  if constexpr (D == 3) s.radius_min = 0.8e-3;  // some 600 spheres: seconds
  const Packing<D> box = dense_packing<D>(s);
  s.shape = DensePackingSpec<D>::Shape::Cylinder;
  const Packing<D> disc = dense_packing<D>(s);
  const Eigen::Vector2d centre(6e-3, 6e-3);
  for (const auto& x : disc.x) CHECK((x.template head<2>() - centre).norm() <= 6e-3);
  const double kept = double(disc.x.size()) / box.x.size();
  MESSAGE(D, "D: ", disc.x.size(), " of ", box.x.size(), " particles kept (", kept, ")");
  CHECK(kept == mc::test::relative(M_PI / 4, 0.10));
}

TEST_CASE("dense_packing_carves_the_inscribed_disc_2d") { carved_cylinder<2>(); }
TEST_CASE("dense_packing_carves_the_inscribed_cylinder_3d") { carved_cylinder<3>(); }
