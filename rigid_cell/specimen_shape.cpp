#include "rigid_cell/specimen_shape.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/errors.hpp"

namespace mc::rigid_cell {

namespace {

double signed_area(const std::vector<Eigen::Vector2d>& v) {
  double a = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const auto& p = v[i];
    const auto& q = v[(i + 1) % v.size()];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * a;
}

Eigen::Vector2d plane(const Vec<2>& x) { return x; }
Eigen::Vector2d plane(const Vec<3>& x) { return x.head<2>(); }

}  // namespace

template <int D>
SpecimenShape<D> SpecimenShape<D>::polygon(std::vector<Eigen::Vector2d> vertices, double thickness) {
  if (vertices.size() < 3) throw InputError("a specimen outline needs at least 3 vertices");
  if (!(signed_area(vertices) > 0))
    throw InputError("a specimen outline must list its vertices counter-clockwise and enclose an area");
  if (D == 3 && !(thickness > 0)) throw InputError("a specimen's thickness must be positive");
  SpecimenShape s;
  s.polygon_ = std::move(vertices);
  s.thickness_ = D == 3 ? thickness : 1.0;
  return s;
}

template <int D>
SpecimenShape<D> SpecimenShape<D>::box(const Vec<D>& size) {
  const double a = size[0], b = size[1];
  return polygon({{0, 0}, {a, 0}, {a, b}, {0, b}}, D == 3 ? size[D - 1] : 1.0);
}

template <int D>
SpecimenShape<D> SpecimenShape<D>::circle(const Eigen::Vector2d& centre, double radius, double thickness) {
  if (!(radius > 0)) throw InputError("a specimen's radius must be positive");
  if (D == 3 && !(thickness > 0)) throw InputError("a specimen's thickness must be positive");
  SpecimenShape s;
  s.centre_ = centre;
  s.radius_ = radius;
  s.thickness_ = D == 3 ? thickness : 1.0;
  return s;
}

template <int D>
bool SpecimenShape<D>::inside_outline(const Eigen::Vector2d& p) const {
  if (polygon_.empty()) return (p - centre_).norm() < radius_;
  bool in = false;  // crossing number
  for (std::size_t i = 0, j = polygon_.size() - 1; i < polygon_.size(); j = i++) {
    const auto& a = polygon_[i];
    const auto& b = polygon_[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      in = !in;
  }
  return in;
}

template <int D>
double SpecimenShape<D>::outline_depth(const Eigen::Vector2d& p) const {
  if (polygon_.empty()) return radius_ - (p - centre_).norm();
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < polygon_.size(); ++i) {
    const auto& a = polygon_[i];
    const Eigen::Vector2d e = polygon_[(i + 1) % polygon_.size()] - a;
    const double t = std::clamp((p - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
    d = std::min(d, (a + t * e - p).norm());
  }
  return d;
}

// Along u (not normalised: its length scales the distance) from p: the first edge crossed, or the circle.
template <int D>
double SpecimenShape<D>::outline_exit(const Eigen::Vector2d& p, const Eigen::Vector2d& u) const {
  constexpr double kNone = std::numeric_limits<double>::infinity();
  if (polygon_.empty()) {  // |p + t u − c| = r, the positive root
    const Eigen::Vector2d q = p - centre_;
    const double a = u.squaredNorm(), b = q.dot(u), c = q.squaredNorm() - radius_ * radius_;
    if (a == 0) return kNone;
    return (-b + std::sqrt(std::max(0.0, b * b - a * c))) / a;
  }
  double t_min = kNone;
  for (std::size_t i = 0; i < polygon_.size(); ++i) {
    const Eigen::Vector2d a = polygon_[i], e = polygon_[(i + 1) % polygon_.size()] - a;
    const double den = u.x() * e.y() - u.y() * e.x();  // u × e
    if (den == 0) continue;                            // parallel to the edge
    const Eigen::Vector2d w = a - p;
    const double t = (w.x() * e.y() - w.y() * e.x()) / den, s = (w.x() * u.y() - w.y() * u.x()) / den;
    if (t > 0 && s >= 0 && s <= 1) t_min = std::min(t_min, t);
  }
  return t_min;
}

template <int D>
double SpecimenShape<D>::exit_distance(const Vec<D>& x, const Vec<D>& u) const {
  double t = outline_exit(plane(x), plane(u));
  if constexpr (D == 3) {
    if (u[2] > 0) t = std::min(t, (thickness_ - x[2]) / u[2]);
    if (u[2] < 0) t = std::min(t, -x[2] / u[2]);
  }
  return t;
}

template <int D>
bool SpecimenShape<D>::inside(const Vec<D>& x) const {
  if constexpr (D == 3)
    if (!(x[2] > 0 && x[2] < thickness_)) return false;
  return inside_outline(plane(x));
}

template <int D>
bool SpecimenShape<D>::sees(const Vec<D>& a, const Vec<D>& b) const {
  const Eigen::Vector2d p = plane(a), q = plane(b);
  auto side = [](const Eigen::Vector2d& o, const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
    const double c = (u - o).x() * (v - o).y() - (u - o).y() * (v - o).x();
    return (c > 0) - (c < 0);
  };
  for (std::size_t i = 0, j = polygon_.size() - 1; i < polygon_.size(); j = i++) {
    const auto& u = polygon_[j];
    const auto& v = polygon_[i];
    // A proper crossing: each segment's ends strictly on both sides of the other's line.
    if (side(p, q, u) * side(p, q, v) < 0 && side(u, v, p) * side(u, v, q) < 0) return false;
  }
  return true;
}

template <int D>
double SpecimenShape<D>::depth(const Vec<D>& x) const {
  double d = outline_depth(plane(x));
  if constexpr (D == 3) d = std::min({d, x[2], thickness_ - x[2]});
  return d;
}

template <int D>
double SpecimenShape<D>::volume() const {
  const double area = polygon_.empty() ? M_PI * radius_ * radius_ : signed_area(polygon_);
  return area * thickness_;
}

template <int D>
Eigen::AlignedBox2d SpecimenShape<D>::outline_bounds() const {
  Eigen::AlignedBox2d box(centre_.array() - radius_, centre_.array() + radius_);
  if (!polygon_.empty()) {
    box.setEmpty();
    for (const auto& v : polygon_) box.extend(v);
  }
  return box;
}

template <int D>
Vec<D> SpecimenShape<D>::lo() const {
  Vec<D> v = Vec<D>::Zero();  // z from 0
  v.template head<2>() = outline_bounds().min();
  return v;
}

template <int D>
Vec<D> SpecimenShape<D>::hi() const {
  Vec<D> v = Vec<D>::Constant(thickness_);
  v.template head<2>() = outline_bounds().max();
  return v;
}

template <int D>
void SpecimenShape<D>::outline_mirrors(const Eigen::Vector2d& p, double reach,
                                       std::vector<Eigen::Vector2d>& out) const {
  if (polygon_.empty()) {
    const Eigen::Vector2d r = p - centre_;
    const double d = r.norm();
    if (radius_ - d < reach && d > 0) out.push_back(centre_ + r * ((2 * radius_ - d) / d));
    return;
  }
  for (std::size_t i = 0; i < polygon_.size(); ++i) {
    const auto& a = polygon_[i];
    const Eigen::Vector2d e = polygon_[(i + 1) % polygon_.size()] - a;
    const double len = e.norm();
    const double t = (p - a).dot(e) / len;  // along the edge [m]
    const Eigen::Vector2d foot = a + e * (t / len);
    if ((p - foot).norm() >= reach || t < -reach || t > len + reach) continue;
    const Eigen::Vector2d image = 2 * foot - p;
    if (!inside_outline(image)) out.push_back(image);
  }
}

template <int D>
void SpecimenShape<D>::mirrors(const Vec<D>& x, double reach, std::vector<Vec<D>>& out) const {
  std::vector<Eigen::Vector2d> images;
  outline_mirrors(plane(x), reach, images);
  for (const auto& m : images) {
    Vec<D> y = x;
    y.template head<2>() = m;
    out.push_back(y);
  }
  if constexpr (D == 3) {
    if (x[2] < reach) out.push_back({x[0], x[1], -x[2]});
    if (thickness_ - x[2] < reach) out.push_back({x[0], x[1], 2 * thickness_ - x[2]});
  }
}

template class SpecimenShape<2>;
template class SpecimenShape<3>;

}  // namespace mc::rigid_cell
