#include "preprocess/aggregate_shape.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <utility>
#include <vector>

#include "preprocess/shape_growth.hpp"

namespace mc {

namespace {

// The unit direction of seed vertex k, ±axis k/2, tilted at random by up to atan(0.36) ≈ 20° when `tilt`.
Vec<3> seed_direction(int k, bool tilt, RandomStream& rng) {
  Vec<3> u = Vec<3>::Zero();
  u[k / 2] = k % 2 == 0 ? 1.0 : -1.0;
  if (tilt) {
    Vec<3> w;
    do {
      w = Vec<3>(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    } while (w.squaredNorm() > 1);
    u += 0.36 * w;
  }
  return u.normalized();
}

// Tang §4.1.3 seed: an octahedron on the sphere of radius r, vertex k near ±axis k/2, turned by a random rotation;
// redrawn unless strictly convex, and after 1000 tries taken untilted. Face (X, Y, Z) for each octant, ordered to
// face outwards.
Polyhedron seed_octahedron(double r, RandomStream& rng) {
  Polyhedron p;
  for (int tries = 0;; ++tries) {
    const Eigen::Matrix3d rot = random_rotation(rng);
    p.v.clear();
    p.f.clear();
    for (int k = 0; k < 6; ++k) p.v.push_back(r * (rot * seed_direction(k, tries < 1000, rng)));
    for (int sx = 0; sx < 2; ++sx)
      for (int sy = 0; sy < 2; ++sy)
        for (int sz = 0; sz < 2; ++sz) {
          const int x = sx, y = 2 + sy, z = 4 + sz;
          if ((sx + sy + sz) % 2 == 0)
            p.f.push_back({x, y, z});  // octant (+,+,+) and its even-sign kin
          else
            p.f.push_back({x, z, y});
        }
    if (is_convex(p, 0.02 * r) || tries >= 1000) break;
  }
  return p;
}

// Tang §4.1.3 growth, longest edge first. Kept up to date: each face's (unnormalised) outward normal and offset
// (n·x ≤ off inside), the face of each directed edge (a, b) in a cap × cap table, and the edges given up.
class PolyhedronGrowth {
 public:
  PolyhedronGrowth(Polyhedron seed, double r, double l_max, double l_min)
      : p_(std::move(seed)), r_(r), l_max_(l_max), l_min_(l_min) {
    for (int f = 0; f < static_cast<int>(p_.f.size()); ++f) face_plane(f);
  }

  // Until no edge longer than L_max can be split.
  Polyhedron grow(RandomStream& rng) {
    for (int step = 0; step < kMaxSteps; ++step) {
      make_room();
      const auto [a, b] = longest_edge();
      if (a < 0) break;
      if (!split(a, b, rng)) stuck_.emplace_back(a, b);
    }
    return std::move(p_);
  }

 private:
  // Face f's outward normal and offset, after it changed.
  void face_plane(int f) {
    const auto& t = p_.f[f];
    const Vec<3> n = (p_.v[t[1]] - p_.v[t[0]]).cross(p_.v[t[2]] - p_.v[t[0]]);
    if (f >= static_cast<int>(nrm_.size())) {
      nrm_.resize(f + 1);
      off_.resize(f + 1);
    }
    nrm_[f] = n;
    off_[f] = n.dot(p_.v[t[0]]);
  }

  // Face f entered in the edge table under its three directed edges.
  void mark(int f) {
    for (int k = 0; k < 3; ++k) face_[p_.f[f][k] * cap_ + p_.f[f][(k + 1) % 3]] = f;
  }

  // The edge table made larger when it has no room for one more vertex.
  void make_room() {
    if (static_cast<int>(p_.v.size()) + 1 <= cap_) return;
    cap_ = std::max(64, 2 * cap_);
    face_.assign(static_cast<std::size_t>(cap_) * cap_, -1);
    for (int f = 0; f < static_cast<int>(p_.f.size()); ++f) mark(f);
  }

  // The longest edge a–b (a < b) longer than L_max and not given up; a = −1 when there is none.
  std::pair<int, int> longest_edge() const {
    int a = -1, b = -1;
    double best = l_max_;
    for (const auto& t : p_.f)
      for (int k = 0; k < 3; ++k) {
        const int i = t[k], j = t[(k + 1) % 3];
        if (i > j) continue;
        const double len = (p_.v[j] - p_.v[i]).norm();
        if (len > best && std::find(stuck_.begin(), stuck_.end(), std::pair(i, j)) == stuck_.end()) {
          best = len;
          a = i;
          b = j;
        }
      }
    return {a, b};
  }

  // The edge a–b split at a random point A at least L_min from both ends, the new vertex P pushed out from A along
  // V = n_m + n_n (the two faces at the edge); up to kTriesPerEdge points A. False when none gives a P with both
  // new edges to the opposite vertices longer than L_min.
  bool split(int a, int b, RandomStream& rng) {
    const int fm = face_[a * cap_ + b], fn = face_[b * cap_ + a];
    const int c = opposite(fm, a, b), e = opposite(fn, a, b);
    const Vec<3> dir = (nrm_[fm].normalized() + nrm_[fn].normalized()).normalized();
    const Vec<3> va = p_.v[a], ab = p_.v[b] - p_.v[a];
    const double len = ab.norm();
    for (int t = 0; t < kTriesPerEdge; ++t) {
      const Vec<3> at = va + rng.uniform(l_min_ / len, 1 - l_min_ / len) * ab;
      const double push = max_push(at, dir, fm, fn);
      if (!(push > 0)) continue;
      const Vec<3> q = at + rng.uniform(kPushLo, kPushHi) * push * dir;
      if ((q - p_.v[c]).norm() <= l_min_ || (q - p_.v[e]).norm() <= l_min_) continue;
      if (!behind_other_faces(q, fm, fn)) continue;
      insert_vertex(q, a, b, c, e, fm, fn);
      return true;
    }
    return false;
  }

  int opposite(int f, int a, int b) const {
    for (int k = 0; k < 3; ++k)
      if (p_.f[f][k] != a && p_.f[f][k] != b) return p_.f[f][k];
    return -1;
  }

  // The farthest P may go from `at` along dir: inside the sphere and, (4.2), behind every face but fm and fn.
  double max_push(const Vec<3>& at, const Vec<3>& dir, int fm, int fn) const {
    double push = to_sphere(at, dir, r_);
    for (int f = 0; f < static_cast<int>(p_.f.size()); ++f) {
      if (f == fm || f == fn) continue;
      const double rate = nrm_[f].dot(dir);
      if (rate > 0) push = std::min(push, (off_[f] - nrm_[f].dot(at)) / rate);
    }
    return push;
  }

  // (4.2): 6 V_f = n_f · (q − a_f) < 0 for every face f but fm and fn, which keeps the polyhedron convex.
  bool behind_other_faces(const Vec<3>& q, int fm, int fn) const {
    for (int f = 0; f < static_cast<int>(p_.f.size()); ++f) {
      if (f == fm || f == fn) continue;
      if (!(nrm_[f].dot(q) < off_[f])) return false;
    }
    return true;
  }

  // q splits edge a–b: its faces fm = (a, b, c) and fn = (b, a, e) become four.
  void insert_vertex(const Vec<3>& q, int a, int b, int c, int e, int fm, int fn) {
    const int iq = static_cast<int>(p_.v.size());
    p_.v.push_back(q);
    face_[a * cap_ + b] = face_[b * cap_ + a] = -1;
    p_.f[fm] = {a, iq, c};
    p_.f[fn] = {b, iq, e};
    p_.f.push_back({iq, b, c});
    p_.f.push_back({iq, a, e});
    const int nf = static_cast<int>(p_.f.size());
    for (int f : {fm, fn, nf - 2, nf - 1}) {
      face_plane(f);
      mark(f);
    }
  }

  Polyhedron p_;
  double r_, l_max_, l_min_;
  std::vector<Vec<3>> nrm_;
  std::vector<double> off_;
  int cap_ = 0;
  std::vector<int> face_;
  std::vector<std::pair<int, int>> stuck_;
};

}  // namespace

Polyhedron random_polyhedron(double d, const ShapeParams& params, RandomStream& rng) {
  check_shape_params("random polyhedron", d, params);
  const double r = 0.5 * d, l_max = params.l_max * d, l_min = params.l_min * d;
  return PolyhedronGrowth(seed_octahedron(r, rng), r, l_max, l_min).grow(rng);
}

}  // namespace mc
