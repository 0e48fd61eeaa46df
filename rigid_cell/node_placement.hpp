// The nodes of the rigid cells: random sequential addition with a minimum distance l_min (Květoň §3.1). A
// candidate is drawn uniformly in the shape's bounding box and kept when it lies inside the shape, at least
// l_min/2 below its surface (so that it stays l_min from its own mirror image) and at least l_min from every node
// kept so far; the distance test asks a k-d tree (nanoflann). Placement stops after `max_rejections` candidates in a
// row were refused: the domain is then saturated to within about 1/max_rejections of its free volume.
//
// The distance may instead grow away from a box where the crack is expected (adaptive discrete models coarsen the
// same way, e.g. Eliáš 2016): l(x) = min(l_max, l_min + grading · dist(x, box)), two nodes at least the mean of
// their l apart, and l(x)/2 below the surface. The box is filled to saturation first, then the whole shape, so that
// the fine cells are as dense as uniform ones. The crack band of the facet law (3.20) scales each facet by its own
// length, so a coarse facet dissipates the same G_t per unit area; G_t's dependence on l_min through the crack's
// tortuosity holds where the crack runs, in the box.
#pragma once
#include <cstdint>
#include <vector>

#include "rigid_cell/specimen_shape.hpp"

namespace mc::rigid_cell {

template <int D>
struct NodeSpacing {
  double l_min = 0;  // [m]
  double l_max = 0;  // [m]; at most l_min: uniform
  Vec<D> fine_lo = Vec<D>::Zero(), fine_hi = Vec<D>::Zero();
  double grading = 0;  // [m/m]: growth of l per unit distance from the box
  bool uniform() const { return !(l_max > l_min); }
  double largest() const { return uniform() ? l_min : l_max; }
  double at(const Vec<D>& x) const;
};

template <int D>
std::vector<Vec<D>> place_nodes(const SpecimenShape<D>& shape, const NodeSpacing<D>& spacing, std::uint64_t seed,
                                int max_rejections);
template <int D>
std::vector<Vec<D>> place_nodes(const SpecimenShape<D>& shape, double l_min, std::uint64_t seed,
                                int max_rejections);

// The pair of nodes nearest to each other, and their distance (nodes given from outside must keep l_min too).
struct NearestPair {
  int a = -1, b = -1;
  double distance = 0;
};
template <int D>
NearestPair nearest_pair(const std::vector<Vec<D>>& nodes);

}  // namespace mc::rigid_cell
