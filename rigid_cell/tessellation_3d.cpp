// The 3D tessellation: CGAL's Delaunay_triangulation_3; a Voronoi face is the polygon of the circumcentres of the
// tetrahedra around a Delaunay edge, in the order CGAL's circulator visits them.
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Delaunay_triangulation_cell_base_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>

#include "rigid_cell/tessellation_build.hpp"

namespace mc::rigid_cell {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_3<int, K>;  // the node's index (mirror images after the nodes)
using Cb = CGAL::Triangulation_cell_base_with_info_3<int, K, CGAL::Delaunay_triangulation_cell_base_3<K>>;
using Delaunay = CGAL::Delaunay_triangulation_3<K, CGAL::Triangulation_data_structure_3<Vb, Cb>>;

// A tetrahedron below this fraction of its longest edge cubed is flat (an exact one is 0.118).
constexpr double kFlat = 1e-9;
// A face below this fraction of its nodes' distance squared has no area.
constexpr double kNoArea = 1e-10;

// Area and centroid of a plane polygon with normal n, by a fan from its first vertex.
void area_and_centroid(Facet<3>& f) {
  double area = 0;
  Vec<3> moment = Vec<3>::Zero();
  const auto& v = f.vertices;
  for (std::size_t i = 1; i + 1 < v.size(); ++i) {
    const double a = 0.5 * (v[i] - v[0]).cross(v[i + 1] - v[0]).dot(f.normal);
    area += a;
    moment += a * (v[0] + v[i] + v[i + 1]) / 3.0;
  }
  f.area = std::abs(area);
  f.centroid = area != 0 ? Vec<3>(moment / area) : v[0];
}

}  // namespace

template <>
Tessellation<3> tessellate(const std::vector<Vec<3>>& nodes, const SpecimenShape<3>& shape, double reach) {
  const int n = static_cast<int>(nodes.size());
  const std::vector<Vec<3>> points = nodes_and_images(nodes, shape, reach);

  std::vector<std::pair<K::Point_3, int>> input;
  input.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    input.push_back({{points[i].x(), points[i].y(), points[i].z()}, int(i)});
  Delaunay dt(input.begin(), input.end());
  if (dt.dimension() < 3) throw_unbounded(0, nodes.at(0));  // too few nodes and images to enclose a cell

  // A node and a neighbour mirrored across one plane, with their images, are four coplanar points on one
  // circle: the exact predicates split them into a flat tetrahedron, whose circumcentre is undefined. Its true
  // neighbours' centres bound the Voronoi edge dual to that circle, so a face simply leaves the flat one out.
  std::vector<Vec<3>> centre;
  std::vector<std::array<int, 4>> key;
  std::vector<bool> flat;
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) {
    std::array<std::pair<int, Vec<3>>, 4> v;
    for (int k = 0; k < 4; ++k) {
      const K::Point_3& q = c->vertex(k)->point();
      v[k] = {c->vertex(k)->info(), Vec<3>(q.x(), q.y(), q.z())};
    }
    std::sort(v.begin(), v.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    Vec<3> p[4];
    for (int k = 0; k < 4; ++k) p[k] = v[k].second;
    double edge = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) edge = std::max(edge, (p[i] - p[j]).norm());
    const double volume = std::abs((p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0]))) / 6;
    c->info() = static_cast<int>(centre.size());
    flat.push_back(volume < kFlat * edge * edge * edge);
    const auto [o, sorted] = circumcentre<3>(v);
    centre.push_back(o);
    key.push_back(sorted);
  }

  Tessellation<3> t;
  std::vector<Facet<3>> surface;
  for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
    int a = e->first->vertex(e->second)->info(), b = e->first->vertex(e->third)->info();
    if (a >= n && b >= n) continue;  // between two images
    if (a > b) std::swap(a, b);
    Facet<3> facet;
    facet.a = a;
    facet.b = b < n ? b : -1;
    std::vector<int> around;
    auto c = dt.incident_cells(*e), done = c;
    do {
      if (dt.is_infinite(c)) throw_unbounded(a, nodes[a]);
      if (!flat[c->info()]) around.push_back(c->info());
    } while (++c != done);
    if (around.size() < 3) continue;  // a face of zero area
    // The polygon from the tetrahedron of least key, towards its neighbour of lesser key: where CGAL's circulator
    // starts depends on its memory layout, and the face's area, centroid and pyramids would round with it.
    const auto least = std::min_element(around.begin(), around.end(), [&](int x, int y) { return key[x] < key[y]; });
    std::rotate(around.begin(), least, around.end());
    if (key[around.back()] < key[around[1]]) std::reverse(around.begin() + 1, around.end());
    for (int k : around) facet.vertices.push_back(centre[k]);
    const Vec<3> d = points[b] - points[a];
    facet.length = d.norm();
    facet.normal = d / facet.length;
    area_and_centroid(facet);
    // A cell clipped near an edge or a corner of the specimen may keep a surface face of no area (10⁻²¹ m² and
    // below, against 10⁻⁵ m² for a face of a 5 mm cell) whose centroid and normal are round-off (a centroid 10¹² m
    // away): it bounds nothing, and one of them sent a fibre's walk through the cells out of the specimen mid-way.
    if (facet.b < 0 && !(facet.area > kNoArea * facet.length * facet.length)) continue;
    (facet.b >= 0 ? t.facets : surface).push_back(std::move(facet));
  }
  finish(t, nodes, std::move(surface), shape);
  return t;
}

}  // namespace mc::rigid_cell
