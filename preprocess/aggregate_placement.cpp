#include "preprocess/aggregate_placement.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "engine/errors.hpp"

namespace mc {

namespace {

// Relocations by translation after an overlap before a fresh position is drawn.
constexpr int kShifts = 3;

// A convex shape as the intersection of half-spaces n·x ≤ off (unit outward n), with its vertices and centroid,
// and in 3D its triangles and its edges (a point, the direction and the normals of the two faces that meet there):
// what the exact tests of the placement need, built once per orientation and translated per position.
struct Edge {
  Vec<3> p, dir, n1, n2, n21;  // n21 = n2 × n1
};

template <int D>
struct Body {
  std::vector<Vec<D>> v, n;
  std::vector<double> off;
  std::vector<std::array<int, 3>> tri;
  std::vector<Edge> e;
  Vec<D> c, lo, hi;
};

template <int D>
void bound(Body<D>& b) {
  b.lo = b.hi = b.v[0];
  for (const auto& x : b.v) {
    b.lo = b.lo.cwiseMin(x);
    b.hi = b.hi.cwiseMax(x);
  }
}

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

// `a` translated by c, into `out` (its storage reused).
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
      if (a.n[i].dot(x) < a.off[i]) { all_out = false; break; }
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

// Separating axis theorem, exact: the faces of A − B are the faces of A, those of −B and, in 3D, the edge pairs
// that form a face of it; A and B are apart when the origin is outside one of them. Touching shapes are apart.
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

// Distance from x to the body (0 inside).
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
  for (const auto& t : b.tri) best = std::min(best, (closest_on_triangle(x, b.v[t[0]], b.v[t[1]], b.v[t[2]]) - x).norm());
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
        if (n.dot(p.v[t[0]] - mid) > 0) p.f.push_back(t);
        else p.f.push_back({t[0], t[2], t[1]});
      }
    }
  return p;
}

template <int D>
double measure(const Vec<D>& lo, const Vec<D>& hi) {
  double m = 1;
  for (int k = 0; k < D; ++k) m *= hi[k] - lo[k];
  return m;
}

template <int D>
ConvexShape<D> random_turn(const ConvexShape<D>& s, RandomStream& rng) {
  ConvexShape<D> out = s;
  if constexpr (D == 2) rotate(out, rng.uniform(0, 2 * M_PI));
  else rotate(out, random_rotation(rng));
  return out;
}

template <int D>
Vec<D> random_direction(RandomStream& rng) {
  Vec<D> w;
  do {
    for (int k = 0; k < D; ++k) w[k] = rng.uniform(-1, 1);
  } while (w.squaredNorm() > 1 || w.squaredNorm() < 1e-4);
  return w.normalized();
}

template <int D>
void check_spec(const PlacementSpec<D>& s) {
  std::ostringstream m;
  for (int k = 0; k < D; ++k)
    if (!(s.hi[k] > s.lo[k]) || !std::isfinite(s.lo[k]) || !std::isfinite(s.hi[k])) {
      m << "aggregate placement: the domain must have hi > lo along every axis (axis " << k << ": " << s.lo[k]
        << " to " << s.hi[k] << ")";
      throw InputError(m.str());
    }
  if (!(s.fraction > 0 && s.fraction < 1)) {
    m << "aggregate placement: fraction = " << s.fraction << " must be in (0, 1)";
    throw InputError(m.str());
  }
  check_grading(s.grading);
  if (!(s.cells_per_dmin >= 5 && s.cells_per_dmin <= 10)) {
    m << "aggregate placement: cells_per_dmin = " << s.cells_per_dmin
      << " must be in [5, 10] (Tang 4.6: grid cell between D_min/10 and D_min/5)";
    throw InputError(m.str());
  }
  if (s.attempts < 1) throw InputError("aggregate placement: attempts must be at least 1");
  for (const auto& b : s.keep_out_boxes)
    for (int k = 0; k < D; ++k)
      if (!(b.hi[k] > b.lo[k])) throw InputError("aggregate placement: a keep-out box must have hi > lo along every axis");
  for (const auto& b : s.keep_out_balls)
    if (!(b.radius > 0)) throw InputError("aggregate placement: a keep-out ball must have a positive radius");
}

}  // namespace

template <int D>
std::int64_t StatusGrid<D>::cells() const {
  std::int64_t c = 1;
  for (int k = 0; k < D; ++k) c *= n[k];
  return c;
}

template <int D>
std::int64_t StatusGrid<D>::cell_of(const Vec<D>& x) const {
  std::int64_t idx = 0, stride = 1;
  for (int k = 0; k < D; ++k) {
    const double f = std::floor((x[k] - lo[k]) / h[k]);
    if (!(f >= 0 && f < n[k])) return -1;
    idx += static_cast<std::int64_t>(f) * stride;
    stride *= n[k];
  }
  return idx;
}

template <int D>
Vec<D> StatusGrid<D>::centre(std::int64_t cell) const {
  Vec<D> x;
  for (int k = 0; k < D; ++k) {
    x[k] = lo[k] + (static_cast<double>(cell % n[k]) + 0.5) * h[k];
    cell /= n[k];
  }
  return x;
}

template <int D>
std::int32_t StatusGrid<D>::at(const Vec<D>& x) const {
  const std::int64_t c = cell_of(x);
  return c < 0 ? 0 : status[c];
}

template <int D>
int AggregateLayout<D>::status_at(const Vec<D>& x) const {
  return std::max(0, grid.at(x));
}

template <int D>
int AggregateLayout<D>::aggregate_at(const Vec<D>& x) const {
  std::int64_t idx = 0, stride = 1;
  for (int k = 0; k < D; ++k) {
    if (!(x[k] >= lo[k] && x[k] <= hi[k])) return 0;  // every aggregate lies in the domain
    const double f = std::floor((x[k] - lo[k]) / bin_size[k]);
    idx += static_cast<std::int64_t>(std::clamp(f, 0.0, bins_n[k] - 1.0)) * stride;
    stride *= bins_n[k];
  }
  for (int id : bins[idx]) {
    const auto& a = aggregates[id - 1];
    bool in_box = true;
    for (int k = 0; k < D; ++k) in_box = in_box && x[k] >= a.lo[k] && x[k] <= a.hi[k];
    if (in_box && contains(a.shape, x)) return id;
  }
  return 0;
}

template <int D>
AggregateLayout<D> place_aggregates(const PlacementSpec<D>& spec) {
  check_spec(spec);
  RandomStream rng(spec.seed);
  AggregateLayout<D> out;
  out.lo = spec.lo;
  out.hi = spec.hi;
  const double domain = measure<D>(spec.lo, spec.hi);
  double d_min = kInf;
  for (const auto& r : spec.grading.ranges) d_min = std::min(d_min, r.lo);

  // Stage 1: the aggregate database, each shape centred on its centroid.
  std::vector<ConvexShape<D>> made;
  const auto sized = fill_grading(
      spec.grading, spec.fraction * domain, D,
      [&](double d) {
        ConvexShape<D> s = random_shape<D>(d, spec.shape, rng);
        translate(s, Vec<D>(-centroid(s)));
        made.push_back(std::move(s));
        return content(made.back());
      },
      rng, spec.size_draw, spec.fuller_n);

  // The background grid, Tang (4.6).
  StatusGrid<D>& grid = out.grid;
  grid.lo = spec.lo;
  const double h0 = d_min / spec.cells_per_dmin;
  double cells = 1;
  for (int k = 0; k < D; ++k) {
    const double len = spec.hi[k] - spec.lo[k];
    cells *= std::max(1.0, std::ceil(len / h0));
  }
  if (cells > 2147483647.0) {
    std::ostringstream m;
    m << "aggregate placement: the background grid would have " << cells << " cells (cell D_min/"
      << spec.cells_per_dmin << " = " << h0 << "); enlarge D_min or shrink the domain";
    throw InputError(m.str());
  }
  for (int k = 0; k < D; ++k) {
    const double len = spec.hi[k] - spec.lo[k];
    grid.n[k] = static_cast<int>(std::max(1.0, std::ceil(len / h0)));
    grid.h[k] = len / grid.n[k];
  }
  const std::int64_t n_cells = grid.cells();
  grid.status.assign(n_cells, 0);

  // Keep-out zones: exact bodies, and their cells marked.
  std::vector<Body<D>> keep_bodies;
  for (const auto& b : spec.keep_out_boxes) keep_bodies.push_back(make_body(box_shape(b)));
  for (std::int64_t c = 0; c < n_cells; ++c) {
    const Vec<D> x = grid.centre(c);
    bool kept = false;
    for (const auto& b : keep_bodies) kept = kept || inside(b, x);
    for (const auto& b : spec.keep_out_balls) kept = kept || (x - b.centre).norm() <= b.radius;
    if (kept) grid.status[c] = StatusGrid<D>::kKeepOut;
  }
  // Free cells, for drawing positions: swap-remove as they are taken.
  std::vector<std::int32_t> free_cells, where(n_cells, -1);
  free_cells.reserve(n_cells);
  for (std::int64_t c = 0; c < n_cells; ++c)
    if (grid.status[c] == 0) {
      where[c] = static_cast<std::int32_t>(free_cells.size());
      free_cells.push_back(static_cast<std::int32_t>(c));
    }

  // Bins of bounding boxes (about 2 D_min, at most 2²⁰ bins), for the exact tests and aggregate_at.
  {
    double b = 2 * d_min, count;
    do {
      count = 1;
      for (int k = 0; k < D; ++k) count *= std::max(1.0, std::floor((spec.hi[k] - spec.lo[k]) / b));
      if (count > (1 << 20)) b *= 1.25;
    } while (count > (1 << 20));
    std::int64_t total = 1;
    for (int k = 0; k < D; ++k) {
      const double len = spec.hi[k] - spec.lo[k];
      out.bins_n[k] = static_cast<int>(std::max(1.0, std::floor(len / b)));
      out.bin_size[k] = len / out.bins_n[k];
      total *= out.bins_n[k];
    }
    out.bins.assign(total, {});
  }
  auto bin_range = [&](const Vec<D>& lo, const Vec<D>& hi, std::array<int, D>& b0, std::array<int, D>& b1) {
    for (int k = 0; k < D; ++k) {
      b0[k] = std::clamp(static_cast<int>(std::floor((lo[k] - spec.lo[k]) / out.bin_size[k])), 0, out.bins_n[k] - 1);
      b1[k] = std::clamp(static_cast<int>(std::floor((hi[k] - spec.lo[k]) / out.bin_size[k])), 0, out.bins_n[k] - 1);
    }
  };
  auto for_bins = [&](const std::array<int, D>& b0, const std::array<int, D>& b1, auto&& f) {
    std::array<int, 3> i{0, 0, 0};
    const int z0 = D == 3 ? b0[D - 1] : 0, z1 = D == 3 ? b1[D - 1] : 0;
    for (i[2] = z0; i[2] <= z1; ++i[2])
      for (i[1] = b0[1]; i[1] <= b1[1]; ++i[1])
        for (i[0] = b0[0]; i[0] <= b1[0]; ++i[0]) {
          std::int64_t idx = i[0] + static_cast<std::int64_t>(out.bins_n[0]) * i[1];
          if constexpr (D == 3) idx += static_cast<std::int64_t>(out.bins_n[0]) * out.bins_n[1] * i[2];
          f(out.bins[idx]);
        }
  };

  std::vector<Body<D>> placed_bodies;
  std::vector<int> stamp;  // per aggregate: the last test that looked at it
  int test_no = 0;
  std::vector<std::int32_t> covered;
  Body<D> body;

  // Detailed determination: the cells whose centres the body covers, row by row along x (each row clipped by
  // every half-space); false at the first taken cell, whose status goes to `hit`.
  auto rasterise = [&](const Body<D>& b, std::int32_t& hit) {
    covered.clear();
    std::array<int, D> c0, c1;
    for (int k = 0; k < D; ++k) {
      c0[k] = std::max(0, static_cast<int>(std::ceil((b.lo[k] - grid.lo[k]) / grid.h[k] - 0.5)));
      c1[k] = std::min(grid.n[k] - 1, static_cast<int>(std::floor((b.hi[k] - grid.lo[k]) / grid.h[k] - 0.5)));
      if (c1[k] < c0[k]) return true;
    }
    std::array<int, 3> j{0, 0, 0};
    const int z0 = D == 3 ? c0[D - 1] : 0, z1 = D == 3 ? c1[D - 1] : 0;
    for (j[2] = z0; j[2] <= z1; ++j[2])
      for (j[1] = c0[1]; j[1] <= c1[1]; ++j[1]) {
        Vec<D> y;
        for (int k = 1; k < D; ++k) y[k] = grid.lo[k] + (j[k] + 0.5) * grid.h[k];
        double xl = -kInf, xu = kInf;
        for (std::size_t f = 0; f < b.n.size(); ++f) {
          double rhs = b.off[f];
          for (int k = 1; k < D; ++k) rhs -= b.n[f][k] * y[k];
          const double a = b.n[f][0];
          if (a > 1e-14) xu = std::min(xu, rhs / a);
          else if (a < -1e-14) xl = std::max(xl, rhs / a);
          else if (rhs < 0) xu = -kInf;
        }
        if (!(xl <= xu)) continue;
        const int i0 = std::max(c0[0], static_cast<int>(std::ceil((xl - grid.lo[0]) / grid.h[0] - 0.5)));
        const int i1 = std::min(c1[0], static_cast<int>(std::floor((xu - grid.lo[0]) / grid.h[0] - 0.5)));
        std::int64_t row = j[1];
        if constexpr (D == 3) row += static_cast<std::int64_t>(grid.n[1]) * j[2];
        row *= grid.n[0];
        for (int i = i0; i <= i1; ++i) {
          const std::int32_t s = grid.status[row + i];
          if (s != 0) {
            hit = s;
            return false;
          }
          covered.push_back(static_cast<std::int32_t>(row + i));
        }
      }
    return true;
  };

  // What a test found: nothing (placed), a wall (shift back in), or an obstacle to move away from.
  struct Verdict {
    enum Kind { ok, wall, obstacle, hopeless } kind = ok;
    Vec<D> move = Vec<D>::Zero();  // wall: the shift back in; obstacle: its centre
  };
  // Checks 1 and 2 need only the vertices (`tv`, about the centroid, bounding box tlo–thi) and the position c;
  // `body()` gives the exact shape there for the rest, built only for positions that get that far.
  auto test = [&](const std::vector<Vec<D>>& tv, const Vec<D>& tlo, const Vec<D>& thi, const Vec<D>& c,
                  auto&& body_at) {
    Verdict v;
    // 1. Inside the domain.
    for (int k = 0; k < D; ++k) {
      const double under = spec.lo[k] - (tlo[k] + c[k]), over = thi[k] + c[k] - spec.hi[k];
      if (under > 0 && over > 0) return Verdict{Verdict::hopeless, {}};
      const double slack = 1e-12 * (spec.hi[k] - spec.lo[k]);
      if (under > 0) v.move[k] = under + slack;
      if (over > 0) v.move[k] = -over - slack;
    }
    if (v.move != Vec<D>::Zero()) {
      v.kind = Verdict::wall;
      return v;
    }
    // 2. Initial determination on the characteristic points.
    auto probe = [&](const Vec<D>& x) {
      const std::int32_t s = grid.at(x);
      return s > 0 && inside(placed_bodies[s - 1], x) ? s : 0;
    };
    std::int32_t s = probe(c);
    for (std::size_t i = 0; i < tv.size() && s == 0; ++i) {
      s = probe(Vec<D>(tv[i] + c));
      if (s == 0) s = probe(Vec<D>(0.5 * tv[i] + c));
    }
    if (s > 0) return Verdict{Verdict::obstacle, out.aggregates[s - 1].centroid};
    const Body<D>& b = body_at();
    // 3. Keep-out zones, exactly.
    for (const auto& k : keep_bodies)
      if (!separated(b, k)) return Verdict{Verdict::obstacle, Vec<D>(0.5 * (k.lo + k.hi))};
    for (const auto& k : spec.keep_out_balls)
      if (distance(b, k.centre) < k.radius) return Verdict{Verdict::obstacle, k.centre};
    // 4. Detailed determination on the grid.
    std::int32_t hit = 0;
    if (!rasterise(b, hit)) {
      if (hit > 0) return Verdict{Verdict::obstacle, out.aggregates[hit - 1].centroid};
      return Verdict{Verdict::obstacle, c + random_direction<D>(rng)};
    }
    // 5. Exact test against the neighbours.
    ++test_no;
    std::array<int, D> b0, b1;
    bin_range(b.lo, b.hi, b0, b1);
    int clash = 0;
    for_bins(b0, b1, [&](const std::vector<int>& ids) {
      for (int id : ids) {
        if (clash || stamp[id - 1] == test_no) continue;
        stamp[id - 1] = test_no;
        if (!separated(b, placed_bodies[id - 1])) clash = id;
      }
    });
    if (clash) return Verdict{Verdict::obstacle, out.aggregates[clash - 1].centroid};
    return v;
  };

  out.ranges.resize(spec.grading.ranges.size());
  for (std::size_t k = 0; k < spec.grading.ranges.size(); ++k) {
    const auto& r = spec.grading.ranges[k];
    out.ranges[k].lo = r.lo;
    out.ranges[k].hi = r.hi;
    out.ranges[k].target_share = r.share;
    out.ranges[k].target_fraction = r.share * spec.fraction;
  }
  out.target_fraction = spec.fraction;

  // Stages 2–4: take and place, largest first.
  for (const SizedAggregate& sa : sized) {
    ConvexShape<D> local = made[sa.made];
    if (sa.scale != 1) scale(local, sa.scale);
    bool placed = false;
    for (int a = 0; a < spec.attempts && !placed && !free_cells.empty(); ++a) {
      const std::int64_t cell = free_cells[rng.below(free_cells.size())];
      Vec<D> c = grid.centre(cell);
      for (int k = 0; k < D; ++k) c[k] += rng.uniform(-0.5, 0.5) * grid.h[k];
      const ConvexShape<D> turned = random_turn<D>(local, rng);
      Vec<D> tlo = turned.v[0], thi = turned.v[0];
      for (const auto& x : turned.v) {
        tlo = tlo.cwiseMin(x);
        thi = thi.cwiseMax(x);
      }
      bool built = false;
      Body<D> shape_body;
      for (int shift = 0; shift <= kShifts; ++shift) {
        ++out.attempts;
        const Verdict v = test(turned.v, tlo, thi, c, [&]() -> const Body<D>& {
          if (!built) {
            shape_body = make_body(turned);
            built = true;
          }
          move_body(shape_body, c, body);
          return body;
        });
        if (v.kind == Verdict::ok) {
          placed = true;
          break;
        }
        if (v.kind == Verdict::hopeless) break;
        if (v.kind == Verdict::wall) {
          c += v.move;
          continue;
        }
        // Relocation by translation, away from what was hit.
        Vec<D> away = c - v.move;
        away = away.norm() > 1e-9 * sa.size ? Vec<D>(away.normalized()) : random_direction<D>(rng);
        c += rng.uniform(0, 0.5) * sa.size * away;
      }
      if (!placed) continue;
      const int id = static_cast<int>(out.aggregates.size()) + 1;
      for (std::int32_t cc : covered) {
        grid.status[cc] = id;
        const std::int32_t w = where[cc];
        if (w >= 0) {
          const std::int32_t last = free_cells.back();
          free_cells[w] = last;
          where[last] = w;
          free_cells.pop_back();
          where[cc] = -1;
        }
      }
      PlacedAggregate<D> pa;
      pa.shape = turned;
      translate(pa.shape, c);
      pa.centroid = c;
      pa.lo = body.lo;
      pa.hi = body.hi;
      pa.size = sa.size;
      pa.content = sa.content;
      pa.range = sa.range;
      out.aggregates.push_back(std::move(pa));
      placed_bodies.push_back(body);
      stamp.push_back(0);
      std::array<int, D> b0, b1;
      bin_range(body.lo, body.hi, b0, b1);
      for_bins(b0, b1, [&](std::vector<int>& ids) { ids.push_back(id); });
    }
    RangeOutcome& ro = out.ranges[sa.range];
    if (placed) {
      ++ro.placed;
      ro.achieved_fraction += sa.content / domain;
    } else {
      ++ro.failed;
    }
  }
  double total = 0;
  bool all = true;
  for (const auto& r : out.ranges) {
    total += r.achieved_fraction;
    all = all && r.failed == 0;
  }
  for (auto& r : out.ranges) r.achieved_share = total > 0 ? r.achieved_fraction / total : 0;
  out.achieved_fraction = total;
  out.reached = all;
  return out;
}

template struct StatusGrid<2>;
template struct StatusGrid<3>;
template struct AggregateLayout<2>;
template struct AggregateLayout<3>;
template AggregateLayout<2> place_aggregates<2>(const PlacementSpec<2>&);
template AggregateLayout<3> place_aggregates<3>(const PlacementSpec<3>&);

}  // namespace mc
