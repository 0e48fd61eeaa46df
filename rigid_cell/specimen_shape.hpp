// The specimens the rigid-cell model fills with cells: a plane outline (a polygon or a circle), in 3D extruded
// along z through a thickness. Boxes, discs and cylinders (Brazilian test), notched beams, L-shapes and
// compact-tension specimens (Květoň ch. 9) are all of this kind. In 2D a specimen has unit thickness (1 m), as the
// explicit engine's discs.
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "engine/dim.hpp"

namespace mc::rigid_cell {

template <int D>
class SpecimenShape {
 public:
  // A simple polygon, its vertices counter-clockwise [m]; thickness [m] is ignored in 2D.
  static SpecimenShape polygon(std::vector<Eigen::Vector2d> vertices, double thickness);
  static SpecimenShape box(const Vec<D>& size);
  static SpecimenShape circle(const Eigen::Vector2d& centre, double radius, double thickness);

  bool inside(const Vec<D>& x) const;
  // Whether the straight segment between two points inside stays inside: it crosses no edge of the outline (a
  // circle's and a convex polygon's always do; across a notch they do not).
  bool sees(const Vec<D>& a, const Vec<D>& b) const;
  // The distance from a point inside to the nearest boundary surface.
  double depth(const Vec<D>& x) const;
  // The distance from a point inside along the unit direction u to where the line first leaves the shape.
  double exit_distance(const Vec<D>& x, const Vec<D>& u) const;
  double volume() const;  // 2D: area × 1 m
  Vec<D> lo() const;
  Vec<D> hi() const;
  // Appends the mirror images of x (inside) across each boundary surface nearer than `reach`: across an edge's
  // line, when the foot lies on the edge or within `reach` of it; across the tangent of a circle; across the end
  // planes in 3D. An image inside the shape (a re-entrant corner) is no image. With every node near the surface
  // mirrored, the Voronoi faces between nodes and images lie on the surface (Květoň §3.1).
  void mirrors(const Vec<D>& x, double reach, std::vector<Vec<D>>& out) const;

 private:
  std::vector<Eigen::Vector2d> polygon_;  // empty for a circle
  Eigen::Vector2d centre_ = Eigen::Vector2d::Zero();
  double radius_ = 0, thickness_ = 1;

  Eigen::AlignedBox2d outline_bounds() const;
  bool inside_outline(const Eigen::Vector2d& p) const;
  double outline_depth(const Eigen::Vector2d& p) const;
  double outline_exit(const Eigen::Vector2d& p, const Eigen::Vector2d& u) const;
  void outline_mirrors(const Eigen::Vector2d& p, double reach, std::vector<Eigen::Vector2d>& out) const;
};

extern template class SpecimenShape<2>;
extern template class SpecimenShape<3>;

}  // namespace mc::rigid_cell
