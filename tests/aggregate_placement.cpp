// Aggregate disposition (Tang 2013 §4.2–4.4). The results are checked with this file's own exact geometry, not
// with the placement's grid or its own tests: no two aggregates overlap (separating axis theorem: every edge
// normal in 2D; every face normal and every edge × edge cross product in 3D), all lie inside the domain and clear
// of the keep-out zones, and the point queries agree with brute force. Then the capability of §4.4: the success
// rate over 50 seeds at 70 % (2D) and 50 % (3D), the grading achieved per range, and 80 % / 60 % reached.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "engine/errors.hpp"
#include "preprocess/aggregate_placement.hpp"
#include "tests/common/relative.hpp"

using namespace mc;

namespace {

double cross2(const Vec<2>& a, const Vec<2>& b) { return a[0] * b[1] - a[1] * b[0]; }

// How far the projections of two point sets on u overlap (negative: the gap between them).
template <int D>
double depth_along(const std::vector<Vec<D>>& a, const std::vector<Vec<D>>& b, const Vec<D>& u) {
  double lo_a = kInf, hi_a = -kInf, lo_b = kInf, hi_b = -kInf;
  for (const auto& x : a) {
    lo_a = std::min(lo_a, u.dot(x));
    hi_a = std::max(hi_a, u.dot(x));
  }
  for (const auto& x : b) {
    lo_b = std::min(lo_b, u.dot(x));
    hi_b = std::max(hi_b, u.dot(x));
  }
  return std::min(hi_a, hi_b) - std::max(lo_a, lo_b);
}

// Convex polygons overlap by more than `tol` when no edge normal of either separates them by more than −tol.
bool polygons_overlap(const Polygon& a, const Polygon& b, double tol) {
  for (const Polygon* p : {&a, &b})
    for (std::size_t i = 0; i < p->v.size(); ++i) {
      const Vec<2> e = p->v[(i + 1) % p->v.size()] - p->v[i];
      if (depth_along<2>(a.v, b.v, Vec<2>(e[1], -e[0]).normalized()) <= tol) return false;
    }
  return true;
}

std::vector<Vec<3>> edges_of(const Polyhedron& p) {
  std::vector<Vec<3>> e;
  for (const auto& t : p.f)
    for (int k = 0; k < 3; ++k)
      if (t[k] < t[(k + 1) % 3]) e.push_back(p.v[t[(k + 1) % 3]] - p.v[t[k]]);
  return e;
}

// Convex polyhedra: face normals of both, then every cross product of an edge of one and an edge of the other.
bool polyhedra_overlap(const Polyhedron& a, const Polyhedron& b, double tol) {
  for (const Polyhedron* p : {&a, &b})
    for (const auto& t : p->f) {
      const Vec<3> n = (p->v[t[1]] - p->v[t[0]]).cross(p->v[t[2]] - p->v[t[0]]).normalized();
      if (depth_along<3>(a.v, b.v, n) <= tol) return false;
    }
  const auto ea = edges_of(a), eb = edges_of(b);
  for (const auto& u : ea)
    for (const auto& w : eb) {
      const Vec<3> axis = u.cross(w);
      if (axis.norm() < 1e-9 * u.norm() * w.norm()) continue;
      if (depth_along<3>(a.v, b.v, Vec<3>(axis.normalized())) <= tol) return false;
    }
  return true;
}

Polygon box_polygon(const AlignedBox<2>& b) {
  return Polygon{{b.lo, Vec<2>(b.hi[0], b.lo[1]), b.hi, Vec<2>(b.lo[0], b.hi[1])}};
}

// An axis-aligned box as a polyhedron: only its face normals and edge directions matter to the test above.
Polyhedron box_polyhedron(const AlignedBox<3>& b) {
  Polyhedron p;
  for (int i = 0; i < 8; ++i)
    p.v.emplace_back(i & 1 ? b.hi[0] : b.lo[0], i & 2 ? b.hi[1] : b.lo[1], i & 4 ? b.hi[2] : b.lo[2]);
  const int q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& s : q) {
    p.f.push_back({s[0], s[1], s[2]});
    p.f.push_back({s[0], s[2], s[3]});
  }
  return p;
}

bool overlaps(const Polygon& a, const Polygon& b, double tol) { return polygons_overlap(a, b, tol); }
bool overlaps(const Polyhedron& a, const Polyhedron& b, double tol) { return polyhedra_overlap(a, b, tol); }
Polygon box_shape(const AlignedBox<2>& b) { return box_polygon(b); }
Polyhedron box_shape(const AlignedBox<3>& b) { return box_polyhedron(b); }

bool holds(const Polygon& p, const Vec<2>& x) {
  for (std::size_t i = 0; i < p.v.size(); ++i)
    if (cross2(p.v[(i + 1) % p.v.size()] - p.v[i], x - p.v[i]) < 0) return false;
  return true;
}

bool holds(const Polyhedron& p, const Vec<3>& x) {
  for (const auto& t : p.f)
    if ((p.v[t[1]] - p.v[t[0]]).cross(p.v[t[2]] - p.v[t[0]]).dot(x - p.v[t[0]]) > 0) return false;
  return true;
}

double segment_distance(const Vec<3>& x, const Vec<3>& a, const Vec<3>& b) {
  const Vec<3> e = b - a;
  const double t = std::clamp(e.dot(x - a) / e.squaredNorm(), 0.0, 1.0);
  return (a + t * e - x).norm();
}

// Distance from x to a convex shape: 0 inside; else the nearest edge (2D) or face (3D: the foot of the
// perpendicular if it falls in the triangle, otherwise the nearest of its three edges).
double distance_to(const Polygon& p, const Vec<2>& x) {
  if (holds(p, x)) return 0;
  double best = kInf;
  for (std::size_t i = 0; i < p.v.size(); ++i) {
    const Vec<2> a = p.v[i], b = p.v[(i + 1) % p.v.size()];
    best = std::min(best, segment_distance(Vec<3>(x[0], x[1], 0), Vec<3>(a[0], a[1], 0), Vec<3>(b[0], b[1], 0)));
  }
  return best;
}

double distance_to(const Polyhedron& p, const Vec<3>& x) {
  if (holds(p, x)) return 0;
  double best = kInf;
  for (const auto& t : p.f) {
    const Vec<3> a = p.v[t[0]], b = p.v[t[1]], c = p.v[t[2]];
    const Vec<3> n = (b - a).cross(c - a).normalized();
    const Vec<3> foot = x - n.dot(x - a) * n;
    const bool in = (b - a).cross(foot - a).dot(n) >= 0 && (c - b).cross(foot - b).dot(n) >= 0 &&
                    (a - c).cross(foot - c).dot(n) >= 0;
    best = std::min(best,
                    in ? std::abs(n.dot(x - a))
                       : std::min({segment_distance(x, a, b), segment_distance(x, b, c), segment_distance(x, c, a)}));
  }
  return best;
}

// Every check of the placed aggregates against the spec, by this file's geometry.
template <int D>
void check_layout(const PlacementSpec<D>& spec, const AggregateLayout<D>& lay) {
  const double tol = 1e-9;  // [mm] of penetration counted as overlap (round-off is ~1e-13)
  const auto& ag = lay.aggregates;
  REQUIRE(!ag.empty());
  double content_sum = 0, domain = 1;
  for (int k = 0; k < D; ++k) domain *= spec.hi[k] - spec.lo[k];
  int pairs = 0, overlapping = 0, outside = 0, in_keep_out = 0;
  for (std::size_t i = 0; i < ag.size(); ++i) {
    content_sum += ag[i].content;
    CHECK(content(ag[i].shape) == mc::test::relative(ag[i].content, 1e-10));
    for (const auto& x : ag[i].shape.v)
      for (int k = 0; k < D; ++k) outside += x[k] < spec.lo[k] - tol || x[k] > spec.hi[k] + tol;
    for (const auto& b : spec.keep_out_boxes) in_keep_out += overlaps(ag[i].shape, box_shape(b), tol);
    for (const auto& b : spec.keep_out_balls) in_keep_out += distance_to(ag[i].shape, b.centre) < b.radius - tol;
    for (std::size_t j = i + 1; j < ag.size(); ++j) {
      bool boxes = true;
      for (int k = 0; k < D; ++k) boxes = boxes && ag[i].lo[k] < ag[j].hi[k] && ag[j].lo[k] < ag[i].hi[k];
      if (!boxes) continue;
      ++pairs;
      overlapping += overlaps(ag[i].shape, ag[j].shape, tol);
    }
  }
  MESSAGE(D, "D: ", ag.size(), " aggregates, ", pairs, " pairs with meeting bounding boxes tested exactly");
  // The test itself sees overlaps: an aggregate against itself moved by a tenth of its size.
  auto moved = ag[0].shape;
  translate(moved, Vec<D>::Constant(0.1 * ag[0].size));
  CHECK(overlaps(ag[0].shape, moved, tol));
  // The keep-out zones were pressed against: some aggregate comes within 3 mm of each ball.
  for (const auto& b : spec.keep_out_balls) {
    double nearest = kInf;
    for (const auto& a : ag) nearest = std::min(nearest, distance_to(a.shape, b.centre));
    CHECK(nearest < b.radius + 3);
  }
  CHECK(overlapping == 0);
  CHECK(outside == 0);
  CHECK(in_keep_out == 0);
  CHECK(lay.achieved_fraction == mc::test::relative(content_sum / domain, 1e-12));
}

PlacementSpec<2> notched_beam(double fraction, std::uint64_t seed) {
  PlacementSpec<2> s;
  s.lo = Vec<2>(0, 0);
  s.hi = Vec<2>(400, 100);  // mm
  s.grading = tang_table_4_1();
  s.fraction = fraction;
  s.seed = seed;
  s.keep_out_boxes.push_back({Vec<2>(198, 0), Vec<2>(202, 20)});  // a 4 mm wide, 20 mm deep notch
  s.keep_out_balls.push_back({Vec<2>(200, 20), 10});              // mortar 10 mm around its tip
  return s;
}

// Table 4.1 without its finest range (8–16, 16–32, 32–64 mm at 2 : 3 : 3): an eighth as many aggregates as the full
// grading at the same fraction, so that 50 seeds in a 100 mm cube fit in a test.
Grading coarse_table_4_1() { return Grading{{{8, 16, 0.25}, {16, 32, 0.375}, {32, 64, 0.375}}}; }

PlacementSpec<3> cube(double side, const Grading& g, double fraction, std::uint64_t seed) {
  PlacementSpec<3> s;
  s.lo = Vec<3>::Zero();
  s.hi = Vec<3>::Constant(side);
  s.grading = g;
  s.fraction = fraction;
  s.seed = seed;
  return s;
}

template <int D>
void check_shares(const AggregateLayout<D>& lay) {
  for (const auto& r : lay.ranges) CHECK(std::abs(r.achieved_share - r.target_share) <= 0.02);
}

}  // namespace

TEST_CASE("placed_polygons_never_overlap_and_stay_in_the_beam_clear_of_the_notch_2d") {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const auto spec = notched_beam(0.7, seed);
    const auto lay = place_aggregates(spec);
    CHECK(lay.reached);
    check_layout(spec, lay);
  }
}

TEST_CASE("placed_polyhedra_never_overlap_and_stay_in_the_cube_clear_of_keep_out_zones_3d") {
  auto spec = cube(100, coarse_table_4_1(), 0.5, 7);
  spec.keep_out_boxes.push_back({Vec<3>(48, 0, 0), Vec<3>(52, 25, 100)});
  spec.keep_out_balls.push_back({Vec<3>(50, 25, 50), 8});
  const auto lay = place_aggregates(spec);
  CHECK(lay.reached);
  check_layout(spec, lay);
}

TEST_CASE("aggregate_at_and_status_at_agree_with_brute_force") {
  const auto spec = notched_beam(0.6, 4);
  const auto lay = place_aggregates(spec);
  RandomStream rng(99);
  int in_aggregate = 0, grid_agrees = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const Vec<2> x(rng.uniform(0, 400), rng.uniform(0, 100));
    int brute = 0;
    for (std::size_t k = 0; k < lay.aggregates.size() && !brute; ++k)
      if (holds(lay.aggregates[k].shape, x)) brute = static_cast<int>(k) + 1;
    REQUIRE(lay.aggregate_at(x) == brute);
    in_aggregate += brute > 0;
    // The grid's answer is the aggregate holding the centre of x's cell.
    const auto& g = lay.grid;
    Vec<2> centre;
    for (int k = 0; k < 2; ++k) centre[k] = g.lo[k] + (std::floor((x[k] - g.lo[k]) / g.h[k]) + 0.5) * g.h[k];
    int at_centre = 0;
    for (std::size_t k = 0; k < lay.aggregates.size() && !at_centre; ++k)
      if (holds(lay.aggregates[k].shape, centre)) at_centre = static_cast<int>(k) + 1;
    REQUIRE(lay.status_at(x) == at_centre);
    grid_agrees += lay.status_at(x) == brute;
  }
  // Points fall in aggregates as often as the area fraction says (binomial σ = √(0.24/20000) = 0.0035);
  // the grid misreads only points near outlines.
  CHECK(std::abs(static_cast<double>(in_aggregate) / n - lay.achieved_fraction) < 4 * 0.0035);
  CHECK(static_cast<double>(grid_agrees) / n > 0.95);
  // Cells in aggregates: the fraction again, to the grid's resolution.
  std::int64_t taken = 0, kept_out = 0;
  for (auto s : lay.grid.status) {
    taken += s > 0;
    kept_out += s == StatusGrid<2>::kKeepOut;
  }
  CHECK(std::abs(static_cast<double>(taken) / lay.grid.cells() - lay.achieved_fraction) < 0.01);
  CHECK(kept_out > 0);
  // Grid cells between D_min/10 and D_min/5 (4.6).
  for (int k = 0; k < 2; ++k) {
    CHECK(lay.grid.h[k] <= 4.0 / 5);
    CHECK(lay.grid.h[k] >= 4.0 / 10);
  }
  // 3D, exactly as well, on a small cube.
  const auto lay3 = place_aggregates(cube(50, Grading{{{8, 16, 0.5}, {16, 24, 0.5}}}, 0.4, 5));
  for (int i = 0; i < 5000; ++i) {
    const Vec<3> x(rng.uniform(0, 50), rng.uniform(0, 50), rng.uniform(0, 50));
    int brute = 0;
    for (std::size_t k = 0; k < lay3.aggregates.size() && !brute; ++k)
      if (holds(lay3.aggregates[k].shape, x)) brute = static_cast<int>(k) + 1;
    REQUIRE(lay3.aggregate_at(x) == brute);
  }
  CHECK(lay.aggregate_at(Vec<2>(-1, 50)) == 0);
}

TEST_CASE("aggregate_placement_is_reproducible_and_refuses_bad_specifications") {
  const auto a = place_aggregates(notched_beam(0.5, 21)), b = place_aggregates(notched_beam(0.5, 21));
  REQUIRE(a.aggregates.size() == b.aggregates.size());
  for (std::size_t i = 0; i < a.aggregates.size(); ++i) CHECK(a.aggregates[i].centroid == b.aggregates[i].centroid);
  CHECK(a.grid.status == b.grid.status);
  const auto c = place_aggregates(notched_beam(0.5, 22));
  CHECK(c.aggregates[0].centroid != a.aggregates[0].centroid);

  auto bad = notched_beam(1.2, 1);
  CHECK_THROWS_AS(place_aggregates(bad), InputError);
  bad = notched_beam(0.5, 1);
  bad.cells_per_dmin = 3;  // cells of D_min/3: coarser than (4.6) allows
  CHECK_THROWS_AS(place_aggregates(bad), InputError);
  bad = notched_beam(0.5, 1);
  bad.hi = Vec<2>(400, 0);
  CHECK_THROWS_AS(place_aggregates(bad), InputError);
  bad = notched_beam(0.5, 1);
  bad.keep_out_balls[0].radius = 0;
  CHECK_THROWS_AS(place_aggregates(bad), InputError);
}

// Tang §4.4, Fig. 4.17: 70 % of the 400 x 100 mm beam with Table 4.1 (4–64 mm at 2:2:3:3) for at least 48 of 50
// seeds; every range's share of the placed area within 0.02 of its target share.
TEST_CASE("capability_2d_70_percent_of_beam_in_95_percent_of_50_seeds_shares_within_2_percent") {
  int reached = 0;
  for (std::uint64_t seed = 1; seed <= 50; ++seed) {
    PlacementSpec<2> s;
    s.hi = Vec<2>(400, 100);
    s.fraction = 0.7;
    s.seed = seed;
    const auto lay = place_aggregates(s);
    reached += lay.reached;
    if (lay.reached) CHECK(lay.achieved_fraction == mc::test::relative(0.7, 1e-3));
    check_shares(lay);
  }
  MESSAGE("2D 70 %: reached for ", reached, " of 50 seeds");
  CHECK(reached >= 48);
}

// Tang §4.3: up to 80 % in 2D. Same beam and grading; the first of seeds 1–10 that reaches it will do
// (the benchmark measures 27 of 50 seeds on a 200 mm square).
TEST_CASE("capability_2d_80_percent_of_beam_is_reachable") {
  bool done = false;
  for (std::uint64_t seed = 1; seed <= 10 && !done; ++seed) {
    PlacementSpec<2> s;
    s.hi = Vec<2>(400, 100);
    s.fraction = 0.8;
    s.seed = seed;
    const auto lay = place_aggregates(s);
    done = lay.reached;
    if (done) {
      MESSAGE("2D 80 %: reached with seed ", seed);
      check_shares(lay);
    }
  }
  CHECK(done);
}

// Tang §4.4, Fig. 4.18: 50 % of a 100 mm cube for at least 48 of 50 seeds, shares within 0.02. With Table 4.1
// less its finest range (8–64 mm at 2:3:3, ~410 aggregates a seed) to keep the test short; the full Table 4.1
// (~2400 aggregates, 0.2 s a seed) is in benchmarks/aggregate_generation.
TEST_CASE("capability_3d_50_percent_of_cube_in_95_percent_of_50_seeds_shares_within_2_percent") {
  int reached = 0;
  for (std::uint64_t seed = 1; seed <= 50; ++seed) {
    const auto lay = place_aggregates(cube(100, coarse_table_4_1(), 0.5, seed));
    reached += lay.reached;
    if (lay.reached) CHECK(lay.achieved_fraction == mc::test::relative(0.5, 1e-3));
    check_shares(lay);
  }
  MESSAGE("3D 50 %: reached for ", reached, " of 50 seeds");
  CHECK(reached >= 48);
}

// Tang §4.3: up to 60 % in 3D, with the full Table 4.1 in the 100 mm cube (~2900 aggregates); the first of seeds
// 1–5 that reaches it will do (the benchmark measures 16 of 20 seeds).
TEST_CASE("capability_3d_60_percent_of_cube_is_reachable") {
  bool done = false;
  for (std::uint64_t seed = 1; seed <= 5 && !done; ++seed) {
    const auto lay = place_aggregates(cube(100, tang_table_4_1(), 0.6, seed));
    done = lay.reached;
    if (done) {
      MESSAGE("3D 60 %: reached with seed ", seed, ", ", lay.aggregates.size(), " aggregates");
      check_shares(lay);
    }
  }
  CHECK(done);
}
