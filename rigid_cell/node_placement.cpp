#include "rigid_cell/node_placement.hpp"

#include <limits>

#include "engine/random_stream.hpp"
#include "rigid_cell/node_tree.hpp"

namespace mc::rigid_cell {

namespace {

// Stops the search at the first node within the radius.
struct AnyWithin {
  using DistanceType = double;
  using IndexType = std::size_t;
  double radius2;
  bool found = false;
  std::size_t size() const { return found ? 1 : 0; }
  bool full() const { return found; }
  double worstDist() const { return radius2; }
  bool addPoint(double d2, std::size_t) {
    if (d2 < radius2) found = true;
    return !found;
  }
};

}  // namespace

template <int D>
std::vector<Vec<D>> place_nodes(const SpecimenShape<D>& shape, double l_min, std::uint64_t seed,
                                int max_rejections) {
  std::vector<Vec<D>> nodes;
  NodeCloud<D> cloud{nodes};
  DynamicNodeTree<D> tree(D, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  const Vec<D> lo = shape.lo(), hi = shape.hi();
  RandomStream random(seed);
  for (int rejected = 0; rejected < max_rejections;) {
    Vec<D> x;
    for (int k = 0; k < D; ++k) x[k] = random.uniform(lo[k], hi[k]);
    AnyWithin near{l_min * l_min};
    bool keep = shape.inside(x) && shape.depth(x) >= 0.5 * l_min;
    if (keep && !nodes.empty()) {
      tree.findNeighbors(near, x.data(), nanoflann::SearchParams());
      keep = !near.found;
    }
    if (!keep) {
      ++rejected;
      continue;
    }
    rejected = 0;
    nodes.push_back(x);
    tree.addPoints(nodes.size() - 1, nodes.size() - 1);
  }
  return nodes;
}

template <int D>
NearestPair nearest_pair(const std::vector<Vec<D>>& nodes) {
  NearestPair best;
  best.distance = std::numeric_limits<double>::infinity();
  if (nodes.size() < 2) return best;
  NodeCloud<D> cloud{nodes};
  StaticNodeTree<D> tree(D, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  tree.buildIndex();
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    std::size_t idx[2] = {0, 0};
    double d2[2] = {0, 0};
    nanoflann::KNNResultSet<double, std::size_t> result(2);
    result.init(idx, d2);
    tree.findNeighbors(result, nodes[i].data(), nanoflann::SearchParams());
    const std::size_t j = idx[0] == i ? idx[1] : idx[0];
    const double d = std::sqrt(idx[0] == i ? d2[1] : d2[0]);
    if (d < best.distance) best = {static_cast<int>(std::min(i, j)), static_cast<int>(std::max(i, j)), d};
  }
  return best;
}

template std::vector<Vec<2>> place_nodes(const SpecimenShape<2>&, double, std::uint64_t, int);
template std::vector<Vec<3>> place_nodes(const SpecimenShape<3>&, double, std::uint64_t, int);
template NearestPair nearest_pair(const std::vector<Vec<2>>&);
template NearestPair nearest_pair(const std::vector<Vec<3>>&);

}  // namespace mc::rigid_cell
