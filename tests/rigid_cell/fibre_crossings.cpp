// Fibres against the facets of a rigid-cell tessellation (rigid_cell/fibre_crossings.hpp): on cubic cells, where
// each crossing is known; on a random tessellation, against every facet tried one by one; and past the surface
// facets of no area that cells clipped near an edge of the specimen keep.
#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "rigid_cell/fibre_crossings.hpp"
#include "rigid_cell/node_placement.hpp"
#include "tests/common/relative.hpp"
#include "tests/rigid_cell/cubic_grid.hpp"

using namespace mc;
using namespace mc::rigid_cell;

namespace {

// Where the segment crosses the facet's plane inside its polygon: the distance from a, or −1. `margin` gets how far
// inside the polygon the point lies (negative: outside), so that crossings within round-off of an edge are known.
double brute_crossing(const Facet<3>& f, const Fibre& fib, double& margin) {
  const Vec<3> d = fib.b - fib.a;
  const double along = d.dot(f.normal);
  margin = -1;
  if (along == 0) return -1;
  const double s = (f.centroid - fib.a).dot(f.normal) / along;
  if (s <= 0 || s >= 1) return -1;
  const Vec<3> p = fib.a + s * d;
  margin = std::numeric_limits<double>::infinity();
  const std::size_t n = f.vertices.size();
  double sign = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const Vec<3> e = f.vertices[(k + 1) % n] - f.vertices[k];
    if (e.norm() < 1e-12) continue;  // a corner the tessellation lists twice, within round-off: no edge
    const double side = e.cross(p - f.vertices[k]).dot(f.normal) / e.norm();
    if (sign == 0) sign = side > 0 ? 1 : -1;
    margin = std::min(margin, sign * side);
  }
  return margin > 0 ? s * d.norm() : -1;
}

}  // namespace

TEST_CASE("fibre_through_cubic_cells_crosses_each_facet_plane_between_its_ends") {
  const double h = 0.01;
  const auto shape = SpecimenShape<3>::box(Vec<3>(5 * h, 4 * h, 3 * h));
  const std::vector<Vec<3>> nodes = test::cubic_grid_nodes(h, 5, 4, 3);
  const auto t = tessellate(nodes, shape, 1.5 * h);
  // Along x from 2 mm to 38 mm, off every edge: the planes x = 10, 20, 30 mm; back along −x the same, reversed.
  const Vec<3> a(0.002, 0.0152, 0.0147), b(0.038, 0.0152, 0.0147);
  const auto forth = fibre_crossings(t, {{a, b}});
  REQUIRE(forth.size() == 3);
  for (int k = 0; k < 3; ++k) {
    CHECK(forth[k].at == test::relative(0.008 + 0.01 * k, 1e-12));
    CHECK(std::abs(std::abs(forth[k].cosine) - 1) < 1e-12);
    CHECK(forth[k].point[0] == test::relative(0.01 * (k + 1), 1e-12));
  }
  const auto back = fibre_crossings(t, {{b, a}});
  REQUIRE(back.size() == 3);
  for (int k = 0; k < 3; ++k) {
    CHECK(back[k].facet == forth[2 - k].facet);
    CHECK(back[k].cosine == -forth[2 - k].cosine);
  }
}

TEST_CASE("fibre_walk_through_random_cells_finds_every_facet_it_crosses_in_order") {
  const auto shape = SpecimenShape<3>::box(Vec<3>(0.03, 0.02, 0.01));
  const auto nodes = place_nodes(shape, 2e-3, 7, 2000);
  const auto t = tessellate(nodes, shape, 6e-3);
  FibrePlacement p;
  p.volume_fraction = 0.002, p.length = 8e-3, p.diameter = 40e-6;
  RandomStream rng(11);
  const auto fibres = place_fibres(shape, p, rng);
  REQUIRE(fibres.size() > 1000);
  const auto found = fibre_crossings(t, fibres);
  // Every contact facet tried against every fibre: the same facets, at the same distances, in order.
  std::size_t at = 0, checked = 0, near_edge = 0, missed = 0, extra = 0;
  double worst_distance = 0;
  for (std::size_t i = 0; i < fibres.size(); ++i) {
    std::vector<std::pair<double, int>> expected;
    bool ambiguous = false;
    for (std::size_t f = 0; f < t.contacts; ++f) {
      double margin = 0;
      const double s = brute_crossing(t.facets[f], fibres[i], margin);
      if (std::abs(margin) < 1e-12) ambiguous = true;
      if (s >= 0) expected.emplace_back(s, static_cast<int>(f));
    }
    std::sort(expected.begin(), expected.end());
    std::vector<std::pair<double, int>> walked;
    for (; at < found.size() && found[at].fibre == static_cast<int>(i); ++at)
      walked.emplace_back(found[at].at, found[at].facet);
    if (ambiguous) {  // through an edge within round-off: either neighbour is right
      ++near_edge;
      continue;
    }
    ++checked;
    for (std::size_t k = 0; k < std::min(walked.size(), expected.size()); ++k) {
      missed += walked[k].second != expected[k].second;
      worst_distance = std::max(worst_distance, std::abs(walked[k].first - expected[k].first));
    }
    missed += expected.size() > walked.size() ? expected.size() - walked.size() : 0;
    extra += walked.size() > expected.size() ? walked.size() - expected.size() : 0;
  }
  MESSAGE(fibres.size(), " fibres, ", found.size(), " crossings, ", checked, " checked against every facet (",
          near_edge, " through an edge within 1e-12 m left out)");
  CHECK(at == found.size());
  CHECK(checked > fibres.size() * 9 / 10);
  CHECK(missed == 0);
  CHECK(extra == 0);
  CHECK(worst_distance < 1e-14);
}

TEST_CASE("fibre_crossings_of_the_tension_prism_take_a_fraction_of_a_second") {
  // Květoň §6.3's prism, 60 × 20 × 10 mm, l_min 2.5 mm, 2 % of 8 mm PVA fibres: about 24 000 fibres.
  const auto shape = SpecimenShape<3>::box(Vec<3>(0.06, 0.02, 0.01));
  const auto nodes = place_nodes(shape, 2.5e-3, 7, 2000);
  const auto t = tessellate(nodes, shape, 7.5e-3);
  FibrePlacement p;
  p.volume_fraction = 0.02, p.length = 8e-3, p.diameter = 40e-6;
  RandomStream rng(13);
  const auto t0 = std::chrono::steady_clock::now();
  const auto fibres = place_fibres(shape, p, rng);
  const auto t1 = std::chrono::steady_clock::now();
  const auto found = fibre_crossings(t, fibres);
  const auto t2 = std::chrono::steady_clock::now();
  const double placing = std::chrono::duration<double>(t1 - t0).count();
  const double crossing = std::chrono::duration<double>(t2 - t1).count();
  MESSAGE(t.cells.size(), " cells, ", fibres.size(), " fibres placed in ", placing, " s, ", found.size(),
          " crossings found in ", crossing, " s");
  // A fibre of 8 mm through cells about 2.5 mm across crosses a few facets: between 1 and 4 on average.
  const double per_fibre = static_cast<double>(found.size()) / fibres.size();
  CHECK(per_fibre > 1);
  CHECK(per_fibre < 4);
  CHECK(crossing < 2.0);  // measured about 0.05 s: a loose bound against an all-against-all search (minutes)
}

TEST_CASE("tessellation_keeps_no_face_of_no_area_where_cells_are_clipped_at_an_edge_and_fibre_walks_stay_inside") {
  // The §6.5 prism, 100 × 40 × 10 mm, on cells of l_min 5 mm (half as many across its thickness as the thesis's):
  // cells clipped by the surface near an edge of the box had kept 608 surface facets of no area (below 6·10⁻²¹ m²),
  // whose centroid and normal are round-off; one sent a fibre's walk out of the specimen mid-way. 2 % of 8 mm fibres
  // at random (about 8·10⁴) meet those cells.
  const auto shape = SpecimenShape<3>::box(Vec<3>(0.1, 0.04, 0.01));
  const auto t = tessellate(place_nodes(shape, 5e-3, 5, 3000), shape, 15e-3);
  std::size_t degenerate = 0;
  for (std::size_t f = 0; f < t.facets.size(); ++f) degenerate += !(t.facets[f].area > 1e-18);
  CHECK_MESSAGE(degenerate == 0, degenerate, " facets of less than 1e-18 m2");
  FibrePlacement p;
  p.volume_fraction = 0.02, p.length = 8e-3, p.diameter = 40e-6;
  RandomStream rng(3);
  const auto fibres = place_fibres(shape, p, rng);
  std::vector<FibreCrossing> found;
  REQUIRE_NOTHROW(found = fibre_crossings(t, fibres));  // each walk ends in the cell of its fibre's end
  // Every crossing a contact facet's, on the fibre between its ends, inside the specimen.
  for (const FibreCrossing& c : found) {
    CHECK(static_cast<std::size_t>(c.facet) < t.contacts);
    CHECK(c.at > 0);
    CHECK(c.at < p.length);
    CHECK(shape.inside(c.point));
  }
}
