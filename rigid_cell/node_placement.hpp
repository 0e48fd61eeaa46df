// The nodes of the rigid cells: random sequential addition with a minimum distance l_min (Květoň §3.1). A
// candidate is drawn uniformly in the shape's bounding box and kept when it lies inside the shape, at least
// l_min/2 below its surface (so that it stays l_min from its own mirror image) and at least l_min from every node
// kept so far; the distance test asks a k-d tree (nanoflann). Placement stops after `max_rejections` candidates in a
// row were refused: the domain is then saturated to within about 1/max_rejections of its free volume.
#pragma once
#include <cstdint>
#include <vector>

#include "rigid_cell/specimen_shape.hpp"

namespace mc::rigid_cell {

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
