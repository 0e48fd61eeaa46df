#include "rigid_cell/node_placement.hpp"

#include <algorithm>
#include <limits>

#include "engine/random_stream.hpp"
#include "rigid_cell/node_tree.hpp"

namespace mc::rigid_cell {

namespace {

// Stops the search at the first node nearer than the mean of its spacing and the candidate's.
struct AnyTooNear {
  using DistanceType = double;
  using IndexType = std::size_t;
  const std::vector<double>& spacing;  // of each node kept
  double own, radius2;                 // the candidate's spacing; the search radius², the farthest a node may matter
  bool found = false;
  std::size_t size() const { return found ? 1 : 0; }
  bool full() const { return found; }
  double worstDist() const { return radius2; }
  bool addPoint(double d2, std::size_t i) {
    const double least = 0.5 * (own + spacing[i]);
    if (d2 < least * least) found = true;
    return !found;
  }
};

// Random sequential addition of candidates drawn in [lo, hi], until max_rejections in a row were refused.
template <int D>
void add_nodes(const SpecimenShape<D>& shape, const NodeSpacing<D>& spacing, const Vec<D>& lo, const Vec<D>& hi,
               RandomStream& random, int max_rejections, std::vector<Vec<D>>& nodes, std::vector<double>& own,
               DynamicNodeTree<D>& tree) {
  const double largest = spacing.largest();
  for (int rejected = 0; rejected < max_rejections;) {
    Vec<D> x;
    for (int k = 0; k < D; ++k) x[k] = random.uniform(lo[k], hi[k]);
    const double l = spacing.at(x);
    bool keep = shape.inside(x) && shape.depth(x) >= 0.5 * l;
    if (keep && !nodes.empty()) {
      const double reach = 0.5 * (l + largest);
      AnyTooNear near{own, l, reach * reach};
      tree.findNeighbors(near, x.data(), nanoflann::SearchParams());
      keep = !near.found;
    }
    if (!keep) {
      ++rejected;
      continue;
    }
    rejected = 0;
    nodes.push_back(x);
    own.push_back(l);
    tree.addPoints(nodes.size() - 1, nodes.size() - 1);
  }
}

}  // namespace

template <int D>
double NodeSpacing<D>::at(const Vec<D>& x) const {
  if (uniform()) return l_min;
  const double away = (x - x.cwiseMax(fine_lo).cwiseMin(fine_hi)).norm();
  return std::min(l_max, l_min + grading * away);
}

template <int D>
std::vector<Vec<D>> place_nodes(const SpecimenShape<D>& shape, const NodeSpacing<D>& spacing, std::uint64_t seed,
                                int max_rejections) {
  std::vector<Vec<D>> nodes;
  std::vector<double> own;
  NodeCloud<D> cloud{nodes};
  DynamicNodeTree<D> tree(D, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  const Vec<D> lo = shape.lo(), hi = shape.hi();
  RandomStream random(seed);
  if (!spacing.uniform()) {
    const Vec<D> fine_lo = spacing.fine_lo.cwiseMax(lo), fine_hi = spacing.fine_hi.cwiseMin(hi);
    if ((fine_hi - fine_lo).minCoeff() > 0)
      add_nodes(shape, spacing, fine_lo, fine_hi, random, max_rejections, nodes, own, tree);
  }
  add_nodes(shape, spacing, lo, hi, random, max_rejections, nodes, own, tree);
  return nodes;
}

template <int D>
std::vector<Vec<D>> place_nodes(const SpecimenShape<D>& shape, double l_min, std::uint64_t seed,
                                int max_rejections) {
  return place_nodes(shape, NodeSpacing<D>{.l_min = l_min, .l_max = l_min}, seed, max_rejections);
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

template struct NodeSpacing<2>;
template struct NodeSpacing<3>;
template std::vector<Vec<2>> place_nodes(const SpecimenShape<2>&, const NodeSpacing<2>&, std::uint64_t, int);
template std::vector<Vec<3>> place_nodes(const SpecimenShape<3>&, const NodeSpacing<3>&, std::uint64_t, int);
template std::vector<Vec<2>> place_nodes(const SpecimenShape<2>&, double, std::uint64_t, int);
template std::vector<Vec<3>> place_nodes(const SpecimenShape<3>&, double, std::uint64_t, int);
template NearestPair nearest_pair(const std::vector<Vec<2>>&);
template NearestPair nearest_pair(const std::vector<Vec<3>>&);

}  // namespace mc::rigid_cell
