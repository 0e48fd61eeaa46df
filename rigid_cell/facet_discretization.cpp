#include "rigid_cell/facet_discretization.hpp"

#include <algorithm>
#include <limits>

namespace mc::rigid_cell {

namespace {

// A part below this fraction of its facet's area (a sliver between two round-off-close vertices) is left out: it
// would carry nothing and hold no point.
constexpr double kSliver = 1e-12;

template <int D>
Facet<D> part_of(const Facet<D>& f, const Vec<D>& p, const Vec<D>& q) {
  Facet<D> part = f;
  if constexpr (D == 2) {
    part.vertices = {p, q};
    part.area = f.area * (q - p).norm() / (f.vertices[1] - f.vertices[0]).norm();
    part.centroid = 0.5 * (p + q);
  } else {
    part.vertices = {f.centroid, p, q};
    part.area = 0.5 * (p - f.centroid).cross(q - f.centroid).norm();
    part.centroid = (f.centroid + p + q) / 3.0;
  }
  return part;
}

// How far inside the part x lies: its smallest barycentric coordinate (2D: of the segment, 3D: of the triangle).
double inside(const Facet<2>& part, const Vec<2>& x) {
  const Vec<2> p = part.vertices[0], q = part.vertices[1];
  const double t = (x - p).dot(q - p) / (q - p).squaredNorm();
  return std::min(t, 1 - t);
}

double inside(const Facet<3>& part, const Vec<3>& x) {
  const Vec<3>& n = part.normal;
  const Vec<3> a = part.vertices[0], b = part.vertices[1], c = part.vertices[2];
  const double whole = (b - a).cross(c - a).dot(n);
  return std::min({(b - x).cross(c - x).dot(n) / whole, (c - x).cross(a - x).dot(n) / whole,
                   (a - x).cross(b - x).dot(n) / whole});
}

}  // namespace

template <int D>
FacetParts<D> discretize_facets(const Tessellation<D>& t) {
  FacetParts<D> out;
  out.parts.cells = t.cells;
  out.first.reserve(t.contacts + 1);
  for (std::size_t k = 0; k < t.contacts; ++k) {
    const Facet<D>& f = t.facets[k];
    out.first.push_back(out.parts.facets.size());
    const std::size_t n = f.vertices.size();
    for (std::size_t i = 0; i < (D == 2 ? 2 : n); ++i) {
      Facet<D> part = D == 2 ? (i == 0 ? part_of(f, f.vertices[0], f.centroid) : part_of(f, f.centroid, f.vertices[1]))
                             : part_of(f, f.vertices[i], f.vertices[(i + 1) % n]);
      if (part.area > kSliver * f.area) out.parts.facets.push_back(std::move(part));
    }
  }
  out.first.push_back(out.parts.facets.size());
  out.parts.contacts = out.parts.facets.size();
  out.parts.facets.insert(out.parts.facets.end(), t.facets.begin() + static_cast<std::ptrdiff_t>(t.contacts),
                          t.facets.end());
  return out;
}

std::size_t facet_of_part(const std::vector<std::size_t>& first, std::size_t part) {
  return static_cast<std::size_t>(std::upper_bound(first.begin(), first.end(), part) - first.begin() - 1);
}

template <int D>
std::size_t part_holding(const Tessellation<D>& parts, const std::vector<std::size_t>& first, std::size_t f,
                         const Vec<D>& x) {
  std::size_t best = first[f];
  double most = -std::numeric_limits<double>::infinity();
  for (std::size_t k = first[f]; k < first[f + 1]; ++k) {
    const double s = inside(parts.facets[k], x);
    if (s > most) most = s, best = k;
  }
  return best;
}

template FacetParts<2> discretize_facets(const Tessellation<2>&);
template FacetParts<3> discretize_facets(const Tessellation<3>&);
template std::size_t part_holding(const Tessellation<2>&, const std::vector<std::size_t>&, std::size_t,
                                  const Vec<2>&);
template std::size_t part_holding(const Tessellation<3>&, const std::vector<std::size_t>&, std::size_t,
                                  const Vec<3>&);

}  // namespace mc::rigid_cell
