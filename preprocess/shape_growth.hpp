// What the growth of the random polygons (Tang §4.1.2, aggregate_shape.cpp) and polyhedra (§4.1.3,
// random_polyhedron.cpp) shares.
#pragma once
#include <cmath>

#include "engine/dim.hpp"
#include "preprocess/aggregate_shape.hpp"

namespace mc {

// The push along the outward normal is this fraction of the largest allowed one: never 0 (a vertex on the old
// edge, a straight angle) and never all of it (a vertex on the circle and on a neighbouring edge's line at once).
inline constexpr double kPushLo = 0.1, kPushHi = 0.9;
// Tries to split an edge before giving up on it; growth steps in all (far more than any shape needs).
inline constexpr int kTriesPerEdge = 32, kMaxSteps = 10000;

// Throws InputError for a size d ≤ 0 or limits that do not allow growth; `what` names the shape in the message.
void check_shape_params(const char* what, double d, const ShapeParams& p);

// The largest t ≥ 0 with |a + t u| ≤ r for |a| < r.
template <int D>
double to_sphere(const Vec<D>& a, const Vec<D>& u, double r) {
  const double au = a.dot(u), uu = u.squaredNorm();
  const double disc = au * au - uu * (a.squaredNorm() - r * r);
  return disc <= 0 ? 0.0 : (-au + std::sqrt(disc)) / uu;
}

}  // namespace mc
