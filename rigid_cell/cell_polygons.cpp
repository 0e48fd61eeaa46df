#include "rigid_cell/cell_polygons.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "rigid_cell/point_motion.hpp"

namespace mc::rigid_cell {

namespace {

template <int D>
bool before(const Vec<D>& x, const Vec<D>& y) {
  return std::lexicographical_compare(x.data(), x.data() + D, y.data(), y.data() + D);
}

// A cell's corners, sorted: the distinct vertices of its facets. A Voronoi vertex is one Delaunay simplex's
// circumcentre, computed once, so every facet that has it holds the same bits.
template <int D>
std::vector<Vec<D>> distinct_corners(const Tessellation<D>& t, const std::vector<std::size_t>& facets) {
  std::vector<Vec<D>> v;
  for (std::size_t f : facets) v.insert(v.end(), t.facets[f].vertices.begin(), t.facets[f].vertices.end());
  std::sort(v.begin(), v.end(), before<D>);
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

// A facet's polygon over a cell's corners, the first of which is corner `first` of the specimen.
template <int D>
std::vector<std::int64_t> polygon(const Facet<D>& f, const std::vector<Vec<D>>& corners, std::int64_t first) {
  std::vector<std::int64_t> p;
  for (const auto& x : f.vertices)
    p.push_back(first + (std::lower_bound(corners.begin(), corners.end(), x, before<D>) - corners.begin()));
  return p;
}

// A 2D cell's outline: its corners counter-clockwise, by their angle about the node (a Voronoi cell is convex and
// holds its node).
std::vector<std::int64_t> outline(const std::vector<Vec<2>>& corners, const Vec<2>& node, std::int64_t first) {
  std::vector<std::int64_t> p(corners.size());
  std::vector<double> angle;
  for (std::size_t k = 0; k < corners.size(); ++k) {
    p[k] = first + static_cast<std::int64_t>(k);
    angle.push_back(std::atan2(corners[k].y() - node.y(), corners[k].x() - node.x()));
  }
  std::sort(p.begin(), p.end(), [&](std::int64_t i, std::int64_t j) { return angle[i - first] < angle[j - first]; });
  return p;
}

}  // namespace

template <int D>
CellPolygons<D>::CellPolygons(const Tessellation<D>& t) {
  const std::size_t n = t.cells.size();
  std::vector<std::vector<std::size_t>> facets_of(n);
  for (std::size_t f = 0; f < t.facets.size(); ++f)
    for (int c : {t.facets[f].a, t.facets[f].b})
      if (c >= 0) facets_of[c].push_back(f);
  std::vector<std::vector<Vec<D>>> corners(n);
  std::vector<std::int64_t> first(n);
  for (std::size_t c = 0; c < n; ++c) {
    corners[c] = distinct_corners(t, facets_of[c]);
    first[c] = static_cast<std::int64_t>(cell_.size());
    for (const auto& x : corners[c]) {
      geometry_.corner.insert(geometry_.corner.end(), x.data(), x.data() + D);
      cell_.push_back(static_cast<int>(c));
    }
    node_.push_back(t.cells[c].node);
    if constexpr (D == 2) {
      geometry_.faces.add(outline(corners[c], t.cells[c].node, first[c]));
      geometry_.face_cell.push_back(static_cast<std::int64_t>(c));
    } else {
      for (std::size_t f : facets_of[c]) {
        geometry_.faces.add(polygon<D>(t.facets[f], corners[c], first[c]));
        geometry_.face_cell.push_back(static_cast<std::int64_t>(c));
      }
    }
  }
  for (const Facet<D>& f : t.facets) {
    geometry_.facets.add(polygon<D>(f, corners[f.a], first[f.a]));
    geometry_.facet_a.push_back(f.a);
    geometry_.facet_b.push_back(f.b);
  }
  geometry_.contacts = t.contacts;
}

template <int D>
std::vector<double> CellPolygons<D>::moved(const Eigen::VectorXd& u) const {
  constexpr int kDofs = D + Dim<D>::rot;
  std::vector<double> x(geometry_.corner.size());
  for (std::size_t k = 0; k < cell_.size(); ++k) {
    const int c = cell_[k];
    const Vec<D> reference = Eigen::Map<const Vec<D>>(geometry_.corner.data() + D * k);
    Eigen::Map<Vec<D>>(x.data() + D * k) =
        reference + point_motion<D>(node_[c], reference) * u.template segment<kDofs>(kDofs * c);
  }
  return x;
}

template class CellPolygons<2>;
template class CellPolygons<3>;

}  // namespace mc::rigid_cell
