// The 2D tessellation: CGAL's Delaunay_triangulation_2; a Voronoi face is the segment between the circumcentres of
// the two triangles on a Delaunay edge.
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>

#include "rigid_cell/tessellation_build.hpp"

namespace mc::rigid_cell {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;  // the node's index (mirror images after the nodes)
using Fb = CGAL::Triangulation_face_base_with_info_2<int, K>;    // the index of the triangle's circumcentre
using Delaunay = CGAL::Delaunay_triangulation_2<K, CGAL::Triangulation_data_structure_2<Vb, Fb>>;

}  // namespace

template <>
Tessellation<2> tessellate(const std::vector<Vec<2>>& nodes, const SpecimenShape<2>& shape, double reach) {
  const int n = static_cast<int>(nodes.size());
  const std::vector<Vec<2>> points = nodes_and_images(nodes, shape, reach);

  std::vector<std::pair<K::Point_2, int>> input;
  input.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) input.push_back({{points[i].x(), points[i].y()}, int(i)});
  Delaunay dt;
  dt.insert(input.begin(), input.end());
  if (dt.dimension() < 2) throw_unbounded(0, nodes.at(0));  // too few nodes and images to enclose a cell

  std::vector<Vec<2>> centre;
  std::vector<std::array<int, 3>> key;
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
    std::array<std::pair<int, Vec<2>>, 3> v;
    for (int k = 0; k < 3; ++k) {
      const K::Point_2& p = f->vertex(k)->point();
      v[k] = {f->vertex(k)->info(), Vec<2>(p.x(), p.y())};
    }
    const auto [c, sorted] = circumcentre<2>(v);
    f->info() = static_cast<int>(centre.size());
    centre.push_back(c);
    key.push_back(sorted);
  }

  Tessellation<2> t;
  std::vector<Facet<2>> surface;
  for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
    const auto f = e->first;
    const int i = e->second;
    int a = f->vertex(f->cw(i))->info(), b = f->vertex(f->ccw(i))->info();
    if (a >= n && b >= n) continue;  // between two images
    if (a > b) std::swap(a, b);
    const auto g = f->neighbor(i);
    // A node's cell is unbounded exactly when one of its edges borders an infinite triangle.
    if (dt.is_infinite(f) || dt.is_infinite(g)) throw_unbounded(a, nodes[a]);
    Facet<2> facet;
    facet.a = a;
    facet.b = b < n ? b : -1;
    int first = f->info(), second = g->info();
    if (key[second] < key[first]) std::swap(first, second);  // an order of the ends CGAL's layout does not set
    facet.vertices = {centre[first], centre[second]};
    const Vec<2> d = points[b] - points[a];
    facet.length = d.norm();
    facet.normal = d / facet.length;
    facet.area = (facet.vertices[1] - facet.vertices[0]).norm();
    facet.centroid = 0.5 * (facet.vertices[0] + facet.vertices[1]);
    (facet.b >= 0 ? t.facets : surface).push_back(std::move(facet));
  }
  finish(t, nodes, std::move(surface), shape);
  return t;
}

}  // namespace mc::rigid_cell
