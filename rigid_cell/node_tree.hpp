// Nodes in a nanoflann k-d tree: the adaptor over a list of points, and the static and dynamic trees on it, for the
// node placement (l_min between nodes) and the fibres (the cell holding a point is the nearest node's).
#pragma once
#include <vector>

// nanoflann 1.4 leaves a dynamic tree's bounding box unset until its first point, which GCC flags.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <nanoflann.hpp>
#pragma GCC diagnostic pop

#include "engine/dim.hpp"

namespace mc::rigid_cell {

template <int D>
struct NodeCloud {
  const std::vector<Vec<D>>& x;
  std::size_t kdtree_get_point_count() const { return x.size(); }
  double kdtree_get_pt(std::size_t i, int k) const { return x[i][k]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const { return false; }
};

template <int D>
using DynamicNodeTree = nanoflann::KDTreeSingleIndexDynamicAdaptor<
    nanoflann::L2_Simple_Adaptor<double, NodeCloud<D>, double, std::size_t>, NodeCloud<D>, D, std::size_t>;

template <int D>
using StaticNodeTree = nanoflann::KDTreeSingleIndexAdaptor<
    nanoflann::L2_Simple_Adaptor<double, NodeCloud<D>, double, std::size_t>, NodeCloud<D>, D, std::size_t>;

}  // namespace mc::rigid_cell
