#include "rigid_cell/tessellation.hpp"

#include "rigid_cell/tessellation_build.hpp"

#include <algorithm>
#include <sstream>
#include <tuple>

#include "engine/errors.hpp"
#include "rigid_cell/node_placement.hpp"

namespace mc::rigid_cell {

template <int D>
void check_nodes(const std::vector<Vec<D>>& nodes, const SpecimenShape<D>& shape) {
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (!shape.inside(nodes[i])) {
      std::ostringstream m;
      m << "rigid cells: node " << i << " at (" << nodes[i].transpose() << ") m lies outside the specimen";
      throw InputError(m.str());
    }
  }
  const NearestPair p = nearest_pair(nodes);
  if (p.a >= 0 && p.distance < 1e-9 * (shape.hi() - shape.lo()).norm()) {
    std::ostringstream m;
    m << "rigid cells: nodes " << p.a << " and " << p.b << " coincide (" << p.distance << " m apart, at ("
      << nodes[p.a].transpose() << ") m)";
    throw InputError(m.str());
  }
}

template <int D>
std::vector<Vec<D>> nodes_and_images(const std::vector<Vec<D>>& nodes, const SpecimenShape<D>& shape, double reach) {
  check_nodes(nodes, shape);
  std::vector<Vec<D>> points = nodes;
  for (const auto& x : nodes) shape.mirrors(x, reach, points);
  return points;
}

template <int D>
void throw_unbounded(int cell, const Vec<D>& node) {
  std::ostringstream m;
  m << "rigid cells: cell " << cell << " (node at (" << node.transpose()
    << ") m) is unbounded: its node is farther from the surface than the mirroring reach";
  throw InputError(m.str());
}

template <int D>
[[noreturn]] void throw_contact_outside(const Facet<D>& f, const std::vector<Vec<D>>& nodes) {
  std::ostringstream m;
  m << "rigid cells: cells " << f.a << " and " << f.b << " (nodes at (" << nodes[f.a].transpose() << ") and ("
    << nodes[f.b].transpose() << ") m) meet at (" << f.centroid.transpose()
    << ") m across a gap of the outline (the line between their nodes leaves the specimen): a notch or slit there "
       "is too narrow for the cells beside it (their mirror images across its faces fall among the cells on its "
       "other side, where images are dropped); make it at least 2 l wide, or the cells finer there";
  throw InputError(m.str());
}

template <int D>
void finish(Tessellation<D>& t, const std::vector<Vec<D>>& nodes, std::vector<Facet<D>> surface,
            const SpecimenShape<D>& shape) {
  for (const auto& f : t.facets)
    if (!shape.sees(nodes[f.a], nodes[f.b])) throw_contact_outside(f, nodes);
  std::sort(t.facets.begin(), t.facets.end(),
            [](const Facet<D>& x, const Facet<D>& y) { return std::tie(x.a, x.b) < std::tie(y.a, y.b); });
  // A node as far from two faces has two surface facets of one length: their normals tell them apart.
  std::sort(surface.begin(), surface.end(), [](const Facet<D>& x, const Facet<D>& y) {
    return std::tie(x.a, x.length) < std::tie(y.a, y.length) ||
           (std::tie(x.a, x.length) == std::tie(y.a, y.length) &&
            std::lexicographical_compare(x.normal.data(), x.normal.data() + D, y.normal.data(), y.normal.data() + D));
  });
  t.contacts = t.facets.size();
  t.facets.insert(t.facets.end(), surface.begin(), surface.end());
  t.cells.resize(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) t.cells[i].node = nodes[i];
  for (const auto& f : t.facets) {
    for (int c : {f.a, f.b}) {
      if (c < 0) continue;
      std::vector<Vec<D>> about(f.vertices.size());
      for (std::size_t j = 0; j < about.size(); ++j) about[j] = f.vertices[j] - t.cells[c].node;
      t.cells[c].mass += pyramid<D>(about);
    }
  }
}

// Solves 2 (pᵢ − p₀) · (x − p₀) = |pᵢ − p₀|², i = 1..D.
template <int D>
std::pair<Vec<D>, std::array<int, D + 1>> circumcentre(std::array<std::pair<int, Vec<D>>, D + 1> vertices) {
  std::sort(vertices.begin(), vertices.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  Eigen::Matrix<double, D, D> A;
  Vec<D> b;
  for (int i = 0; i < D; ++i) {
    const Vec<D> d = vertices[i + 1].second - vertices[0].second;
    A.row(i) = d.transpose();
    b[i] = 0.5 * d.squaredNorm();
  }
  std::array<int, D + 1> key;
  for (int i = 0; i <= D; ++i) key[i] = vertices[i].first;
  return {vertices[0].second + A.partialPivLu().solve(b), key};
}

template std::pair<Vec<2>, std::array<int, 3>> circumcentre<2>(std::array<std::pair<int, Vec<2>>, 3>);
template std::pair<Vec<3>, std::array<int, 4>> circumcentre<3>(std::array<std::pair<int, Vec<3>>, 4>);
template void throw_unbounded(int, const Vec<2>&);
template void throw_unbounded(int, const Vec<3>&);
template void finish(Tessellation<2>&, const std::vector<Vec<2>>&, std::vector<Facet<2>>, const SpecimenShape<2>&);
template void finish(Tessellation<3>&, const std::vector<Vec<3>>&, std::vector<Facet<3>>, const SpecimenShape<3>&);
template std::vector<Vec<2>> nodes_and_images(const std::vector<Vec<2>>&, const SpecimenShape<2>&, double);
template std::vector<Vec<3>> nodes_and_images(const std::vector<Vec<3>>&, const SpecimenShape<3>&, double);
template void check_nodes(const std::vector<Vec<2>>&, const SpecimenShape<2>&);
template void check_nodes(const std::vector<Vec<3>>&, const SpecimenShape<3>&);

}  // namespace mc::rigid_cell
