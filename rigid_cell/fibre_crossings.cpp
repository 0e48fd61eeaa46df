#include "rigid_cell/fibre_crossings.hpp"

#include <limits>
#include <stdexcept>
#include <string>

#include "rigid_cell/node_tree.hpp"

namespace mc::rigid_cell {

namespace {

int nearest_cell(const StaticNodeTree<3>& tree, const Vec<3>& x) {
  std::size_t i = 0;
  double d2 = 0;
  nanoflann::KNNResultSet<double, std::size_t> result(1);
  result.init(&i, &d2);
  tree.findNeighbors(result, x.data(), nanoflann::SearchParams());
  return static_cast<int>(i);
}

}  // namespace

std::vector<FibreCrossing> fibre_crossings(const Tessellation<3>& t, const std::vector<Fibre>& fibres) {
  // Each cell's facets (every one has an area and a plane: the tessellation keeps no face of no area).
  std::vector<std::vector<int>> facets_of(t.cells.size());
  for (std::size_t f = 0; f < t.facets.size(); ++f) {
    facets_of[static_cast<std::size_t>(t.facets[f].a)].push_back(static_cast<int>(f));
    if (t.facets[f].b >= 0) facets_of[static_cast<std::size_t>(t.facets[f].b)].push_back(static_cast<int>(f));
  }
  std::vector<Vec<3>> nodes;
  nodes.reserve(t.cells.size());
  for (const Cell<3>& c : t.cells) nodes.push_back(c.node);
  const NodeCloud<3> cloud{nodes};
  StaticNodeTree<3> tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  tree.buildIndex();
  std::vector<FibreCrossing> out;
  for (std::size_t i = 0; i < fibres.size(); ++i) {
    const Fibre& fib = fibres[i];
    const double length = (fib.b - fib.a).norm();
    const Vec<3> u = (fib.b - fib.a) / length;
    int cell = nearest_cell(tree, fib.a);
    const int end_cell = nearest_cell(tree, fib.b);
    double at = 0;
    for (int step = 0;; ++step) {
      if (step > 100000)
        throw std::runtime_error("fibre " + std::to_string(i) + ": its walk through the cells does not end");
      // The first facet plane met outwards beyond `at`.
      double exit = std::numeric_limits<double>::infinity();
      int through = -1;
      for (const int f : facets_of[static_cast<std::size_t>(cell)]) {
        const Facet<3>& facet = t.facets[static_cast<std::size_t>(f)];
        const Vec<3> n = facet.a == cell ? facet.normal : Vec<3>(-facet.normal);
        const double along = u.dot(n);
        if (!(along > 0)) continue;
        const double s = (facet.centroid - fib.a).dot(n) / along;
        if (s > at && s < exit) exit = s, through = f;
      }
      if (through < 0 || exit >= length) break;
      const Facet<3>& facet = t.facets[static_cast<std::size_t>(through)];
      if (facet.b < 0) break;  // the specimen's surface: a cut fibre ends here
      out.push_back({static_cast<int>(i), through, exit, u.dot(facet.normal), fib.a + exit * u});
      cell = facet.a == cell ? facet.b : facet.a;
      at = exit;
    }
    if (cell != end_cell && (fib.b - t.cells[static_cast<std::size_t>(cell)].node).norm() >
                                (fib.b - t.cells[static_cast<std::size_t>(end_cell)].node).norm() * (1 + 1e-9))
      throw std::runtime_error("fibre " + std::to_string(i) + ": its walk through the cells ends in cell " +
                               std::to_string(cell) + ", its end lies in cell " + std::to_string(end_cell));
  }
  return out;
}

}  // namespace mc::rigid_cell
