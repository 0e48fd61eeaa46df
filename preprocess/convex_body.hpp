// Exact convex geometry for the aggregate placement (aggregate_placement.hpp): the checks that no aggregate
// overlaps another or a keep-out zone, beyond what the status matrix's grid can see.
#pragma once
#include <array>
#include <vector>

#include "engine/dim.hpp"
#include "preprocess/aggregate_placement.hpp"  // AlignedBox
#include "preprocess/aggregate_shape.hpp"

namespace mc {

// A convex shape as the intersection of half-spaces n·x ≤ off (unit outward n), with its vertices and centroid,
// and in 3D its triangles and its edges (a point, the direction and the normals of the two faces that meet there):
// what the exact tests of the placement need, built once per orientation and translated per position.
struct Edge {
  Vec<3> p, dir, n1, n2, n21;  // n21 = n2 × n1
};

template <int D>
struct Body {
  std::vector<Vec<D>> v, n;
  std::vector<double> off;
  std::vector<std::array<int, 3>> tri;
  std::vector<Edge> e;
  Vec<D> c, lo, hi;
};

Body<2> make_body(const Polygon& p);
Body<3> make_body(const Polyhedron& p);

// `a` translated by c, into `out` (its storage reused).
template <int D>
void move_body(const Body<D>& a, const Vec<D>& c, Body<D>& out);

// Is x in the closed body?
template <int D>
bool inside(const Body<D>& b, const Vec<D>& x);

// Separating axis theorem, exact: the faces of A − B are the faces of A, those of −B and, in 3D, the edge pairs
// that form a face of it; A and B are apart when the origin is outside one of them. Touching shapes are apart.
template <int D>
bool separated(const Body<D>& a, const Body<D>& b);

// Distance from x to the body (0 inside).
double distance(const Body<2>& b, const Vec<2>& x);
double distance(const Body<3>& b, const Vec<3>& x);

// The box as a polygon (counter-clockwise) / a polyhedron of outward triangles.
Polygon box_shape(const AlignedBox<2>& box);
Polyhedron box_shape(const AlignedBox<3>& box);

}  // namespace mc
