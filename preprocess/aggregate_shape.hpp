// Single aggregates, Tang (2013) §4.1, after Gao and Liu (2003): random convex polygons (2D) and polyhedra (3D)
// grown from a small seed inscribed in an auxiliary circle / sphere of diameter d. Every vertex stays inside that
// circle / sphere, so d is the aggregate's size (the sieve size it stands for). The shapes are built around the
// auxiliary centre at the origin; exact area / volume and centroid go with them.
#pragma once
#include <Eigen/Core>
#include <array>
#include <vector>

#include "engine/dim.hpp"
#include "engine/random_stream.hpp"

namespace mc {

// A convex polygon: its vertices counter-clockwise.
struct Polygon {
  std::vector<Vec<2>> v;
};

// A convex polyhedron: its vertices and triangular faces, each face counter-clockwise seen from outside, so that
// (b − a) × (c − a) is the outward normal.
struct Polyhedron {
  std::vector<Vec<3>> v;
  std::vector<std::array<int, 3>> f;
};

template <int D>
struct ShapeOf;
template <>
struct ShapeOf<2> {
  using type = Polygon;
};
template <>
struct ShapeOf<3> {
  using type = Polyhedron;
};
template <int D>
using ConvexShape = typename ShapeOf<D>::type;

// Growth limits, as fractions of the size d (Tang §4.1.2: L_max and L_min).
struct ShapeParams {
  double l_max = 0.5;          // growth goes on while an edge is longer than L_max = l_max · d
  double l_min = 0.15;         // every new edge is longer than L_min = l_min · d; needs l_min < l_max / 2
  double min_seed_angle = 30;  // [deg] no angle of the triangle / quadrilateral seed is sharper (2D)
};

// Tang (4.1): ½ det[[x y 1], [x_i y_i 1], [x_i+1 y_i+1 1]] with P first, i.e. the signed area of the triangle
// (a, b, p): > 0 when p lies left of a → b, which is the inner side of an edge of a counter-clockwise polygon.
double signed_area(const Vec<2>& a, const Vec<2>& b, const Vec<2>& p);

// Tang (4.2): the signed volume ⅙ (b − a) × (c − a) · (p − a) of the tetrahedron (a, b, c, p): < 0 when p lies
// on the inner side of the face (a, b, c) of a polyhedron with outward counter-clockwise faces (Tang §4.1.3:
// "V_k must be negative").
double signed_volume(const Vec<3>& a, const Vec<3>& b, const Vec<3>& c, const Vec<3>& p);

// Tang §4.1.2. Seed: a triangle or a quadrilateral (even odds), one vertex at a random point of each of the 3 or 4
// equal arcs of the circle of diameter d (arcs from a random angle), redrawn while an angle is sharper than
// min_seed_angle or an edge is not longer than L_min. Growth: while some edge is longer than L_max, one of them (at
// random) gets a new vertex P pushed out along its outward normal from a random point A of it, A at least L_min from
// both ends (so both new edges are longer than L_min). The push is a random 10–90 % of the most that keeps the polygon
// inside the circle and convex: P stays on the inner side of the two neighbouring edges (S(P a_i−1 a_i) > 0 and S(P
// a_i+1 a_i+2) > 0, (4.1)). Throws InputError for d ≤ 0 or limits that do not allow growth.
Polygon random_polygon(double d, const ShapeParams& params, RandomStream& rng);

// Tang §4.1.3. Seed: an octahedron whose 6 vertices lie on the sphere of diameter d near ±x, ±y, ±z (each
// direction tilted at random by up to ~20°), turned by a uniform random rotation, redrawn unless strictly convex.
// Growth: the longest edge longer than L_max is split at a random point A at least L_min from both ends; the new
// vertex P is pushed out from A along V = n_m + n_n (the unit outward normals of the two faces sharing the edge), by a
// random 10–90 % of the most that keeps P inside the sphere and on the inner side of every other face
// (V_k < 0, (4.2)), which keeps the polyhedron convex: its two faces become four. An edge that cannot be split with
// the new edges to the two opposite vertices longer than L_min (a thin face; 32 tries) is left as it is: about
// 0.4 % of the edges end longer than L_max (up to ~0.62 d at the default limits). Throws InputError like the polygon.
Polyhedron random_polyhedron(double d, const ShapeParams& params, RandomStream& rng);

template <int D>
ConvexShape<D> random_shape(double d, const ShapeParams& params, RandomStream& rng);

// Exact area (shoelace) / volume (sum of tetrahedra from the origin) and centroid.
double area(const Polygon& p);
double volume(const Polyhedron& p);
inline double content(const Polygon& p) { return area(p); }
inline double content(const Polyhedron& p) { return volume(p); }
Vec<2> centroid(const Polygon& p);
Vec<3> centroid(const Polyhedron& p);

// Is x in the closed shape (the signed area / volume test, (4.1) / (4.2))?
bool contains(const Polygon& p, const Vec<2>& x);
bool contains(const Polyhedron& p, const Vec<3>& x);

// Is every vertex strictly on the inner side of every edge / face it is not on, by `margin` (a length)?
bool is_convex(const Polygon& p, double margin = 0);
bool is_convex(const Polyhedron& p, double margin = 0);

// Rigid motions and scaling about the origin.
void translate(Polygon& p, const Vec<2>& by);
void translate(Polyhedron& p, const Vec<3>& by);
void scale(Polygon& p, double s);
void scale(Polyhedron& p, double s);
void rotate(Polygon& p, double angle);
void rotate(Polyhedron& p, const Eigen::Matrix3d& rotation);
// A rotation uniform over SO(3) (Shoemake's unit quaternion from three uniforms).
Eigen::Matrix3d random_rotation(RandomStream& rng);

// The section of a convex polyhedron by the plane x[axis] = value: a convex polygon, counter-clockwise, in the
// two other coordinates taken in cyclic order (axis 2: (x, y); axis 0: (y, z); axis 1: (z, x)). Empty (no vertex)
// when the plane misses the polyhedron or only touches it. For drawing a slice of a 3D mesostructure.
Polygon section(const Polyhedron& p, int axis, double value);

// Exact intersection of two convex shapes by the separating axis theorem: the edge normals of both (2D); the face
// normals of both and the cross products of their edges (3D). Shapes that only touch do not overlap.
bool overlap(const Polygon& a, const Polygon& b);
bool overlap(const Polyhedron& a, const Polyhedron& b);

}  // namespace mc
