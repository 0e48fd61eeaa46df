#include "preprocess/convex_body.hpp"

#include <algorithm>

namespace mc {

namespace {

template <int D>
void bound(Body<D>& b) {
  b.lo = b.hi = b.v[0];
  for (const auto& x : b.v) {
    b.lo = b.lo.cwiseMin(x);
    b.hi = b.hi.cwiseMax(x);
  }
}

template <int D>
bool boxes_meet(const Vec<D>& alo, const Vec<D>& ahi, const Vec<D>& blo, const Vec<D>& bhi) {
  for (int k = 0; k < D; ++k)
    if (ahi[k] <= blo[k] || bhi[k] <= alo[k]) return false;
  return true;
}

template <int D>
bool face_separates(const Body<D>& a, const Body<D>& b) {
  for (std::size_t i = 0; i < a.n.size(); ++i) {
    if (a.n[i].dot(b.c) < a.off[i]) continue;  // b's centroid behind the face: so is part of b
    bool all_out = true;
    for (const auto& x : b.v)
      if (a.n[i].dot(x) < a.off[i]) {
        all_out = false;
        break;
      }
    if (all_out) return true;
  }
  return false;
}

template <int D>
bool strictly_inside(const Body<D>& b, const Vec<D>& x) {
  for (std::size_t i = 0; i < b.n.size(); ++i)
    if (!(b.n[i].dot(x) < b.off[i])) return false;
  return true;
}

// Do edge ea of A and edge eb of B meet on the Gauss map, so that their cross product is a face normal of the
// Minkowski difference A − B? With a, b the normals of the faces at ea and c, d those at eb negated (B turned to
// −B): arcs a–b and c–d cross when c, d lie on opposite sides of the plane of a, b, a, b on opposite sides of that
// of c, d, and they lie in the same hemisphere. (b × a and d × c = n2 × n1 of each edge are kept with it.)
bool minkowski_face(const Edge& ea, const Edge& eb) {
  const double cba = -eb.n1.dot(ea.n21), dba = -eb.n2.dot(ea.n21);
  if (cba * dba >= 0) return false;
  const double adc = ea.n1.dot(eb.n21), bdc = ea.n2.dot(eb.n21);
  return adc * bdc < 0 && cba * bdc > 0;
}

Vec<3> closest_on_triangle(const Vec<3>& p, const Vec<3>& a, const Vec<3>& b, const Vec<3>& c) {
  // Voronoi regions of the vertices, then the edges, then the inside.
  const Vec<3> ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec<3> bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const Vec<3> cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double s = 1 / (va + vb + vc);
  return a + vb * s * ab + vc * s * ac;
}

}  // namespace

Body<2> make_body(const Polygon& p) {
  Body<2> b;
  b.v = p.v;
  const std::size_t m = p.v.size();
  for (std::size_t i = 0; i < m; ++i) {
    const Vec<2> e = p.v[(i + 1) % m] - p.v[i];
    const Vec<2> n = Vec<2>(e[1], -e[0]).normalized();
    b.n.push_back(n);
    b.off.push_back(n.dot(p.v[i]));
  }
  b.c = centroid(p);
  bound(b);
  return b;
}

Body<3> make_body(const Polyhedron& p) {
  Body<3> b;
  b.v = p.v;
  b.tri = p.f;
  const int nv = static_cast<int>(p.v.size());
  std::vector<int> face_of(static_cast<std::size_t>(nv) * nv, -1);  // directed edge (a, b) → its face
  for (int f = 0; f < static_cast<int>(p.f.size()); ++f) {
    const auto& t = p.f[f];
    const Vec<3> n = (p.v[t[1]] - p.v[t[0]]).cross(p.v[t[2]] - p.v[t[0]]).normalized();
    b.n.push_back(n);
    b.off.push_back(n.dot(p.v[t[0]]));
    for (int k = 0; k < 3; ++k) face_of[t[k] * nv + t[(k + 1) % 3]] = f;
  }
  for (int f = 0; f < static_cast<int>(p.f.size()); ++f)
    for (int k = 0; k < 3; ++k) {
      const int i = p.f[f][k], j = p.f[f][(k + 1) % 3];
      if (i < j) {
        const Vec<3> n1 = b.n[f], n2 = b.n[face_of[j * nv + i]];
        b.e.push_back({p.v[i], p.v[j] - p.v[i], n1, n2, n2.cross(n1)});
      }
    }
  b.c = centroid(p);
  bound(b);
  return b;
}

template <int D>
void move_body(const Body<D>& a, const Vec<D>& c, Body<D>& out) {
  out.v.resize(a.v.size());
  for (std::size_t i = 0; i < a.v.size(); ++i) out.v[i] = a.v[i] + c;
  out.n = a.n;
  out.off.resize(a.off.size());
  for (std::size_t i = 0; i < a.off.size(); ++i) out.off[i] = a.off[i] + a.n[i].dot(c);
  out.e = a.e;
  if constexpr (D == 3)
    for (auto& e : out.e) e.p += c;
  out.tri = a.tri;
  out.c = a.c + c;
  out.lo = a.lo + c;
  out.hi = a.hi + c;
}

template <int D>
bool inside(const Body<D>& b, const Vec<D>& x) {
  for (std::size_t i = 0; i < b.n.size(); ++i)
    if (b.n[i].dot(x) > b.off[i]) return false;
  return true;
}

template <int D>
bool separated(const Body<D>& a, const Body<D>& b) {
  if (!boxes_meet<D>(a.lo, a.hi, b.lo, b.hi)) return true;
  if (face_separates(a, b) || face_separates(b, a)) return true;
  if constexpr (D == 3) {
    for (const auto& x : b.v)  // a vertex strictly inside the other: overlap, no need to look further
      if (strictly_inside(a, x)) return false;
    for (const auto& x : a.v)
      if (strictly_inside(b, x)) return false;
    for (const auto& ea : a.e)
      for (const auto& eb : b.e) {
        if (!minkowski_face(ea, eb)) continue;
        Vec<3> axis = ea.dir.cross(eb.dir);
        const double len = axis.norm();
        if (!(len > 1e-12 * ea.dir.norm() * eb.dir.norm())) continue;  // parallel edges make no face
        axis /= len;
        if (axis.dot(ea.p - a.c) < 0) axis = -axis;
        if (axis.dot(eb.p - ea.p) >= 0) return true;
      }
  }
  return false;
}

double distance(const Body<2>& b, const Vec<2>& x) {
  if (inside(b, x)) return 0;
  double best = kInf;
  const std::size_t m = b.v.size();
  for (std::size_t i = 0; i < m; ++i) {
    const Vec<2> a = b.v[i], e = b.v[(i + 1) % m] - a;
    const double t = std::clamp(e.dot(x - a) / e.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (a + t * e - x).norm());
  }
  return best;
}

double distance(const Body<3>& b, const Vec<3>& x) {
  if (inside(b, x)) return 0;
  double best = kInf;
  for (const auto& t : b.tri)
    best = std::min(best, (closest_on_triangle(x, b.v[t[0]], b.v[t[1]], b.v[t[2]]) - x).norm());
  return best;
}

Polygon box_shape(const AlignedBox<2>& box) {
  return Polygon{{box.lo, Vec<2>(box.hi[0], box.lo[1]), box.hi, Vec<2>(box.lo[0], box.hi[1])}};
}

Polyhedron box_shape(const AlignedBox<3>& box) {
  Polyhedron p;
  for (int i = 0; i < 8; ++i)
    p.v.emplace_back(i & 1 ? box.hi[0] : box.lo[0], i & 2 ? box.hi[1] : box.lo[1], i & 4 ? box.hi[2] : box.lo[2]);
  const Vec<3> mid = 0.5 * (box.lo + box.hi);
  // Each side (axis k, low or high) as two triangles, turned to face outwards.
  for (int k = 0; k < 3; ++k)
    for (int side = 0; side < 2; ++side) {
      std::array<int, 4> q{};
      int m = 0;
      for (int i = 0; i < 8; ++i)
        if (((i >> k) & 1) == side) q[m++] = i;
      // q holds the side's corners in bit order: 0, 1, 3, 2 goes round it.
      for (const auto& t : {std::array<int, 3>{q[0], q[1], q[3]}, std::array<int, 3>{q[0], q[3], q[2]}}) {
        const Vec<3> n = (p.v[t[1]] - p.v[t[0]]).cross(p.v[t[2]] - p.v[t[0]]);
        if (n.dot(p.v[t[0]] - mid) > 0)
          p.f.push_back(t);
        else
          p.f.push_back({t[0], t[2], t[1]});
      }
    }
  return p;
}

template void move_body<2>(const Body<2>&, const Vec<2>&, Body<2>&);
template void move_body<3>(const Body<3>&, const Vec<3>&, Body<3>&);
template bool inside<2>(const Body<2>&, const Vec<2>&);
template bool inside<3>(const Body<3>&, const Vec<3>&);
template bool separated<2>(const Body<2>&, const Body<2>&);
template bool separated<3>(const Body<3>&, const Body<3>&);

}  // namespace mc
