#include "preprocess/aggregate_shape.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "engine/errors.hpp"
#include "preprocess/shape_growth.hpp"

namespace mc {

namespace {

double cross2(const Vec<2>& a, const Vec<2>& b) { return a[0] * b[1] - a[1] * b[0]; }

double smallest_angle(const std::vector<Vec<2>>& v) {
  const std::size_t n = v.size();
  double smallest = M_PI;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec<2> a = v[(i + n - 1) % n] - v[i], b = v[(i + 1) % n] - v[i];
    smallest = std::min(smallest, std::acos(std::clamp(a.dot(b) / (a.norm() * b.norm()), -1.0, 1.0)));
  }
  return smallest;
}

}  // namespace

void check_shape_params(const char* what, double d, const ShapeParams& p) {
  std::ostringstream m;
  if (!(d > 0) || !std::isfinite(d)) {
    m << what << ": size d = " << d << " must be positive and finite";
    throw InputError(m.str());
  }
  if (!(p.l_min > 0 && 2 * p.l_min < p.l_max && p.l_max < 1)) {
    m << what << ": edge limits l_min = " << p.l_min << ", l_max = " << p.l_max
      << " (fractions of d) must satisfy 0 < l_min < l_max / 2 and l_max < 1 (a new vertex splits an edge longer "
         "than L_max into two longer than L_min)";
    throw InputError(m.str());
  }
  if (!(p.min_seed_angle >= 0 && p.min_seed_angle < 55)) {
    m << what << ": min_seed_angle = " << p.min_seed_angle << " deg must be in [0, 55) (a triangle has one angle "
      << "of at most 60 deg)";
    throw InputError(m.str());
  }
}

double signed_area(const Vec<2>& a, const Vec<2>& b, const Vec<2>& p) { return 0.5 * cross2(b - a, p - a); }

double signed_volume(const Vec<3>& a, const Vec<3>& b, const Vec<3>& c, const Vec<3>& p) {
  return (b - a).cross(c - a).dot(p - a) / 6.0;
}

Polygon random_polygon(double d, const ShapeParams& params, RandomStream& rng) {
  check_shape_params("random polygon", d, params);
  const double r = 0.5 * d, l_max = params.l_max * d, l_min = params.l_min * d;
  const double min_angle = params.min_seed_angle * M_PI / 180;
  Polygon p;
  // Seed: one vertex on each of m equal arcs.
  for (int tries = 0;; ++tries) {
    const int m = rng.uniform() < 0.5 ? 3 : 4;
    const double start = rng.uniform(0, 2 * M_PI);
    p.v.clear();
    for (int k = 0; k < m; ++k) {
      const double a = start + 2 * M_PI * (k + (tries < 1000 ? rng.uniform() : 0.5)) / m;
      p.v.emplace_back(r * std::cos(a), r * std::sin(a));
    }
    double shortest = kInf;
    for (int k = 0; k < m; ++k) shortest = std::min(shortest, (p.v[(k + 1) % m] - p.v[k]).norm());
    if ((smallest_angle(p.v) >= min_angle && shortest > l_min) || tries >= 1000) break;  // or the regular seed
  }
  // Growth.
  for (int step = 0; step < kMaxSteps; ++step) {
    const int n = static_cast<int>(p.v.size());
    std::vector<int> long_edges;
    for (int i = 0; i < n; ++i)
      if ((p.v[(i + 1) % n] - p.v[i]).norm() > l_max) long_edges.push_back(i);
    if (long_edges.empty()) break;
    const int i = long_edges[rng.below(long_edges.size())], j = (i + 1) % n;
    const Vec<2> ai = p.v[i], aj = p.v[j], e = aj - ai;
    const double len = e.norm();
    const Vec<2> normal(e[1] / len, -e[0] / len);  // outward for a counter-clockwise polygon
    const Vec<2> e_prev = ai - p.v[(i + n - 1) % n], e_next = p.v[(j + 1) % n] - aj;
    bool grown = false;
    for (int t = 0; t < kTriesPerEdge && !grown; ++t) {
      const Vec<2> a = ai + rng.uniform(l_min / len, 1 - l_min / len) * e;
      double push = to_sphere(a, normal, r);
      // (4.1) on the neighbouring edges: S(a_i−1, a_i, P) > 0 and S(a_j, a_j+1, P) > 0, linear in the push.
      const double sp = cross2(e_prev, normal), sn = cross2(e_next, normal);
      if (sp < 0) push = std::min(push, cross2(e_prev, a - ai) / -sp);
      if (sn < 0) push = std::min(push, cross2(e_next, a - aj) / -sn);
      if (!(push > 0)) continue;
      const Vec<2> q = a + rng.uniform(kPushLo, kPushHi) * push * normal;
      if (signed_area(p.v[(i + n - 1) % n], ai, q) <= 0 || signed_area(aj, p.v[(j + 1) % n], q) <= 0) continue;
      p.v.insert(p.v.begin() + i + 1, q);
      grown = true;
    }
    if (!grown) break;  // cannot happen for an edge longer than 2 L_min inside the circle; a guard only
  }
  return p;
}

template <>
Polygon random_shape<2>(double d, const ShapeParams& params, RandomStream& rng) {
  return random_polygon(d, params, rng);
}
template <>
Polyhedron random_shape<3>(double d, const ShapeParams& params, RandomStream& rng) {
  return random_polyhedron(d, params, rng);
}

double area(const Polygon& p) {
  const std::size_t n = p.v.size();
  double s = 0;
  for (std::size_t i = 0; i < n; ++i) s += cross2(p.v[i], p.v[(i + 1) % n]);
  return 0.5 * s;
}

Vec<2> centroid(const Polygon& p) {
  const std::size_t n = p.v.size();
  // Relative to the first vertex: no cancellation for shapes far from the origin.
  const Vec<2> o = p.v[0];
  double s = 0;
  Vec<2> m = Vec<2>::Zero();
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const Vec<2> a = p.v[i] - o, b = p.v[i + 1] - o;
    const double w = cross2(a, b);
    s += w;
    m += w * (a + b);
  }
  return o + m / (3 * s);
}

double volume(const Polyhedron& p) {
  const Vec<3> o = p.v[0];
  double s = 0;
  for (const auto& t : p.f) s += (p.v[t[0]] - o).dot((p.v[t[1]] - o).cross(p.v[t[2]] - o));
  return s / 6;
}

Vec<3> centroid(const Polyhedron& p) {
  const Vec<3> o = p.v[0];
  double s = 0;
  Vec<3> m = Vec<3>::Zero();
  for (const auto& t : p.f) {
    const Vec<3> a = p.v[t[0]] - o, b = p.v[t[1]] - o, c = p.v[t[2]] - o;
    const double w = a.dot(b.cross(c));
    s += w;
    m += w * (a + b + c);
  }
  return o + m / (4 * s);
}

bool contains(const Polygon& p, const Vec<2>& x) {
  const std::size_t n = p.v.size();
  for (std::size_t i = 0; i < n; ++i)
    if (signed_area(p.v[i], p.v[(i + 1) % n], x) < 0) return false;
  return true;
}

bool contains(const Polyhedron& p, const Vec<3>& x) {
  for (const auto& t : p.f)
    if (signed_volume(p.v[t[0]], p.v[t[1]], p.v[t[2]], x) > 0) return false;
  return true;
}

bool is_convex(const Polygon& p, double margin) {
  const std::size_t n = p.v.size();
  if (n < 3) return false;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec<2> a = p.v[i], e = p.v[(i + 1) % n] - a;
    const double len = e.norm();
    for (std::size_t k = 0; k < n; ++k)
      if (k != i && k != (i + 1) % n && !(cross2(e, p.v[k] - a) / len > margin)) return false;
  }
  return true;
}

bool is_convex(const Polyhedron& p, double margin) {
  if (p.f.size() < 4) return false;
  for (const auto& t : p.f) {
    const Vec<3> a = p.v[t[0]], n = (p.v[t[1]] - a).cross(p.v[t[2]] - a);
    const double len = n.norm();
    if (!(len > 0)) return false;
    for (int k = 0; k < static_cast<int>(p.v.size()); ++k)
      if (k != t[0] && k != t[1] && k != t[2] && !(n.dot(p.v[k] - a) / len < -margin)) return false;
  }
  return true;
}

void translate(Polygon& p, const Vec<2>& by) {
  for (auto& x : p.v) x += by;
}
void translate(Polyhedron& p, const Vec<3>& by) {
  for (auto& x : p.v) x += by;
}
void scale(Polygon& p, double s) {
  for (auto& x : p.v) x *= s;
}
void scale(Polyhedron& p, double s) {
  for (auto& x : p.v) x *= s;
}
void rotate(Polygon& p, double angle) {
  const Eigen::Rotation2Dd rot(angle);
  for (auto& x : p.v) x = rot * x;
}
void rotate(Polyhedron& p, const Eigen::Matrix3d& rotation) {
  for (auto& x : p.v) x = rotation * x;
}

Eigen::Matrix3d random_rotation(RandomStream& rng) {
  const double u1 = rng.uniform(), u2 = 2 * M_PI * rng.uniform(), u3 = 2 * M_PI * rng.uniform();
  const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
  return Eigen::Quaterniond(b * std::cos(u3), a * std::sin(u2), a * std::cos(u2), b * std::sin(u3)).toRotationMatrix();
}

Polygon section(const Polyhedron& p, int axis, double value) {
  const int u = (axis + 1) % 3, w = (axis + 2) % 3;
  std::vector<Vec<2>> pts;
  for (const auto& t : p.f)
    for (int k = 0; k < 3; ++k) {
      const Vec<3> a = p.v[t[k]], b = p.v[t[(k + 1) % 3]];
      const double sa = a[axis] - value, sb = b[axis] - value;
      if (sa == 0) pts.emplace_back(a[u], a[w]);
      if ((sa < 0 && sb > 0) || (sa > 0 && sb < 0)) {
        const Vec<3> x = a + (sa / (sa - sb)) * (b - a);
        pts.emplace_back(x[u], x[w]);
      }
    }
  Polygon out;
  if (pts.size() < 3) return out;
  // Each crossing is found from both faces of its edge: sort round the mean, then drop repeats.
  Vec<2> mid = Vec<2>::Zero();
  for (const auto& x : pts) mid += x;
  mid /= static_cast<double>(pts.size());
  std::sort(pts.begin(), pts.end(), [&](const Vec<2>& a, const Vec<2>& b) {
    return std::atan2(a[1] - mid[1], a[0] - mid[0]) < std::atan2(b[1] - mid[1], b[0] - mid[0]);
  });
  double extent = 0;
  for (const auto& x : pts) extent = std::max(extent, (x - mid).norm());
  for (const auto& x : pts)
    if (out.v.empty() || (x - out.v.back()).norm() > 1e-12 * extent) out.v.push_back(x);
  while (out.v.size() > 1 && (out.v.front() - out.v.back()).norm() <= 1e-12 * extent) out.v.pop_back();
  if (out.v.size() < 3 || !(area(out) > 0)) out.v.clear();
  return out;
}

namespace {

// Is there an edge of `a` whose line has all of `b` on its outer side (touching allowed)?
bool separated_by_edge(const Polygon& a, const Polygon& b) {
  const std::size_t n = a.v.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec<2> o = a.v[i], e = a.v[(i + 1) % n] - o;
    bool all_out = true;
    for (const auto& x : b.v)
      if (cross2(e, x - o) > 0) {
        all_out = false;
        break;
      }
    if (all_out) return true;
  }
  return false;
}

bool separated_by_face(const Polyhedron& a, const Polyhedron& b) {
  for (const auto& t : a.f) {
    const Vec<3> o = a.v[t[0]], n = (a.v[t[1]] - o).cross(a.v[t[2]] - o);
    bool all_out = true;
    for (const auto& x : b.v)
      if (n.dot(x - o) < 0) {
        all_out = false;
        break;
      }
    if (all_out) return true;
  }
  return false;
}

std::vector<Vec<3>> edge_directions(const Polyhedron& p) {
  std::vector<Vec<3>> out;
  for (const auto& t : p.f)
    for (int k = 0; k < 3; ++k)
      if (t[k] < t[(k + 1) % 3]) out.push_back(p.v[t[(k + 1) % 3]] - p.v[t[k]]);
  return out;
}

}  // namespace

bool overlap(const Polygon& a, const Polygon& b) { return !separated_by_edge(a, b) && !separated_by_edge(b, a); }

bool overlap(const Polyhedron& a, const Polyhedron& b) {
  if (separated_by_face(a, b) || separated_by_face(b, a)) return false;
  const auto ea = edge_directions(a), eb = edge_directions(b);
  for (const auto& u : ea)
    for (const auto& w : eb) {
      const Vec<3> axis = u.cross(w);
      if (axis.squaredNorm() <= 1e-24 * u.squaredNorm() * w.squaredNorm()) continue;  // parallel edges
      double lo_a = kInf, hi_a = -kInf, lo_b = kInf, hi_b = -kInf;
      for (const auto& x : a.v) {
        const double s = axis.dot(x);
        lo_a = std::min(lo_a, s);
        hi_a = std::max(hi_a, s);
      }
      for (const auto& x : b.v) {
        const double s = axis.dot(x);
        lo_b = std::min(lo_b, s);
        hi_b = std::max(hi_b, s);
      }
      if (hi_a <= lo_b || hi_b <= lo_a) return false;
    }
  return true;
}

}  // namespace mc
