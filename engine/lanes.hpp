// Contacts side by side: each number of a contact law held as kLanes lanes of one SIMD register, so that a model
// can run several contacts through one sequence of instructions. The lanes repeat the scalar code's operations in the
// scalar code's order (Eigen's Vector3d sums x, y, z from the left), and IEEE arithmetic is the same in a lane as in a
// scalar register, so a law run in lanes gives the same bits as run one contact at a time (the build turns off fused
// multiply-add).
#pragma once
#include <immintrin.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/cell_grid.hpp"
#include "engine/dim.hpp"
#include "engine/particles.hpp"
#include "engine/slots.hpp"

namespace mc {

// Two lanes per SSE register, four per AVX register, eight per AVX-512 register: the wider, the faster (n10k, one core,
// 2026-11-27, CPM: 5.8–6.6e6 particle-steps/s with 2 lanes, 7.0–7.8e6 with 4, 8.5–9.5e6 with 8). The build takes the
// widest the build machine runs (CMakeLists.txt, MESOCRACK_ARCH).
#if defined(__AVX512F__)
inline constexpr int kLanes = 8;
#elif defined(__AVX__)
inline constexpr int kLanes = 4;
#else
inline constexpr int kLanes = 2;
#endif

// A lane value is a GCC vector, not an Eigen array: the compiler keeps it in a register and builds a gathered one
// there, where Eigen 3.4 writes an array lane by lane to the stack and reads it back whole (a stalled store
// forward per gather, per mask and per select).
using LaneV = double __attribute__((vector_size(8 * kLanes)));
using LaneM = decltype(LaneV{} < LaneV{});  // −1 (all bits set) where true, 0 where false

struct LaneMask {
  LaneM m;
  static LaneMask Constant(bool b) { return {b ? ~LaneM{} : LaneM{}}; }
  bool operator[](int l) const { return m[l] != 0; }
  bool any() const {
    for (int l = 0; l < kLanes; ++l)
      if (m[l]) return true;
    return false;
  }
};
[[gnu::always_inline]] inline LaneMask operator&&(const LaneMask& a, const LaneMask& b) { return {a.m & b.m}; }
[[gnu::always_inline]] inline LaneMask operator||(const LaneMask& a, const LaneMask& b) { return {a.m | b.m}; }
[[gnu::always_inline]] inline LaneMask operator!(const LaneMask& a) { return {~a.m}; }

struct Lane {
  LaneV v;
  Lane() = default;
  Lane(LaneV x) : v(x) {}
  Lane(double s) : v(s - LaneV{}) {}  // every lane s (s − 0 is s, even for s = −0)
  double operator[](int l) const { return v[l]; }
  void set(int l, double x) { v[l] = x; }
  Lane sqrt() const {
#if defined(__AVX512F__)
    return Lane(LaneV(_mm512_sqrt_pd(v)));
#elif defined(__AVX__)
    return Lane(LaneV(_mm256_sqrt_pd(v)));
#else
    return Lane(LaneV(_mm_sqrt_pd(v)));
#endif
  }
  Lane min(const Lane& o) const { return Lane(o.v < v ? o.v : v); }  // std::min(*this, o)
  Lane abs() const {                                                 // std::abs: the sign bit cleared
    const LaneV sign = -0.0 - LaneV{};
    return Lane(LaneV(LaneM(v) & ~LaneM(sign)));
  }
};
[[gnu::always_inline]] inline Lane operator+(const Lane& a, const Lane& b) { return a.v + b.v; }
[[gnu::always_inline]] inline Lane operator-(const Lane& a, const Lane& b) { return a.v - b.v; }
[[gnu::always_inline]] inline Lane operator*(const Lane& a, const Lane& b) { return a.v * b.v; }
[[gnu::always_inline]] inline Lane operator/(const Lane& a, const Lane& b) { return a.v / b.v; }
[[gnu::always_inline]] inline Lane operator-(const Lane& a) { return -a.v; }
[[gnu::always_inline]] inline LaneMask operator<(const Lane& a, const Lane& b) { return {a.v < b.v}; }
[[gnu::always_inline]] inline LaneMask operator<=(const Lane& a, const Lane& b) { return {a.v <= b.v}; }
[[gnu::always_inline]] inline LaneMask operator>(const Lane& a, const Lane& b) { return {a.v > b.v}; }
[[gnu::always_inline]] inline LaneMask operator>=(const Lane& a, const Lane& b) { return {a.v >= b.v}; }
[[gnu::always_inline]] inline LaneMask operator==(const Lane& a, const Lane& b) { return {a.v == b.v}; }
[[gnu::always_inline]] inline LaneMask operator!=(const Lane& a, const Lane& b) { return {a.v != b.v}; }
[[gnu::always_inline]] inline Lane min_of(const Lane& a, const Lane& b) { return a.min(b); }
[[gnu::always_inline]] inline Lane abs_of(const Lane& a) { return a.abs(); }
using LaneIndex = std::array<int, kLanes>;

struct Lane3 {
  Lane x, y, z;
};

[[gnu::always_inline]] inline Lane3 operator+(const Lane3& a, const Lane3& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
[[gnu::always_inline]] inline Lane3 operator-(const Lane3& a, const Lane3& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
[[gnu::always_inline]] inline Lane3 operator+(double s, const Lane3& a) { return {s + a.x, s + a.y, s + a.z}; }
[[gnu::always_inline]] inline Lane3 operator*(const Lane& s, const Lane3& a) { return {s * a.x, s * a.y, s * a.z}; }
[[gnu::always_inline]] inline Lane3 operator*(const Lane3& a, const Lane& s) { return {a.x * s, a.y * s, a.z * s}; }
[[gnu::always_inline]] inline Lane3 operator*(const Lane3& a, double s) { return {a.x * s, a.y * s, a.z * s}; }
// (a_x b_x + a_y b_y) + a_z b_z: Eigen's order for Vector3d.
[[gnu::always_inline]] inline Lane dot(const Lane3& a, const Lane3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
[[gnu::always_inline]] inline Lane3 cross(const Lane3& a, const Lane3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
// Per lane: a where m, else b.
[[gnu::always_inline]] inline Lane pick(const LaneMask& m, const Lane& a, const Lane& b) {
  return Lane(m.m ? a.v : b.v);
}
[[gnu::always_inline]] inline Lane3 pick(const LaneMask& m, const Lane3& a, const Lane3& b) {
  return {pick(m, a.x, b.x), pick(m, a.y, b.y), pick(m, a.z, b.z)};
}
[[gnu::always_inline]] inline Lane3 pick(const LaneMask& m, const Lane3& a, double b) {
  return {pick(m, a.x, b), pick(m, a.y, b), pick(m, a.z, b)};
}

// The two partners of kLanes consecutive pairs.
[[gnu::always_inline]] inline void lane_partners(const Pair* pairs, LaneIndex& a, LaneIndex& b) {
  for (int l = 0; l < kLanes; ++l) a[l] = pairs[l][0], b[l] = pairs[l][1];
}
// Per-particle values of the partners in `idx`.
[[gnu::always_inline]] inline Lane gather(const std::vector<double>& v, const LaneIndex& idx) {
  LaneV g;
  for (int l = 0; l < kLanes; ++l) g[l] = v[idx[l]];
  return g;
}
[[gnu::always_inline]] inline Lane3 gather(const std::vector<Vec<3>>& v, const LaneIndex& idx) {
  LaneV x, y, z;
  for (int l = 0; l < kLanes; ++l) {
    const Vec<3>& e = v[idx[l]];
    x[l] = e[0], y[l] = e[1], z[l] = e[2];
  }
  return {x, y, z};
}

// A field of kLanes consecutive records of `Stride` numbers each (a contact state, a slot's vector): `at` points
// at the field in the first record. A single-precision field is widened exactly, and stored back rounded.
template <int Stride, class T>
[[gnu::always_inline]] inline Lane load_lanes(const T* at) {
  LaneV v;
  for (int l = 0; l < kLanes; ++l) v[l] = at[l * Stride];
  return v;
}
template <int Stride>
[[gnu::always_inline]] inline Lane3 load_lanes3(const double* at) {
  return {load_lanes<Stride>(at), load_lanes<Stride>(at + 1), load_lanes<Stride>(at + 2)};
}
template <int Stride, class T>
[[gnu::always_inline]] inline void store_lanes(T* at, const Lane& v) {
  for (int l = 0; l < kLanes; ++l) at[l * Stride] = static_cast<T>(v.v[l]);
}
template <int Stride>
[[gnu::always_inline]] inline void store_lanes3(double* at, const Lane3& v) {
  store_lanes<Stride>(at, v.x), store_lanes<Stride>(at + 1, v.y), store_lanes<Stride>(at + 2, v.z);
}

// carry_shear (contact_geometry.hpp) in lanes, `a` the spin angle and c = 1 − a²/2. The exact restore of a
// plane tilted by more than 1e-4 rad is left to the one-contact law: such lanes, among the `active` ones, are
// added to `tilted`.
[[gnu::always_inline]] inline Lane3 carry_shear(const Lane3& fs, const Lane3& n, const Lane& a, const Lane& c,
                                                const LaneMask& active, LaneMask& tilted) {
  const Lane mag2 = dot(fs, fs), p = dot(fs, n);
  const Lane3 t = fs - p * n;
  tilted = tilted || (active && !(p * p <= 1e-8 * mag2));
  return c * t + a * cross(n, t);
}

// ball_geometry (contact_points.hpp, Tang 3.1–3.6) of kLanes consecutive pairs.
struct LaneGeometry {
  LaneIndex ia, ib;
  Lane ra, rb, reach;  // radii, r_a + r_b
  Lane3 d, n;          // x_b − x_a, the unit normal
  Lane overlap;
  Lane3 ca, cb;      // the partners' centres to the contact point
  Lane3 wa, wb;      // spins
  Lane3 v_rel;       // velocity of B relative to A at the contact point
  Lane angle, turn;  // the plane's spin about n in this step, ½(ω_a + ω_b)·n Δt, and 1 − angle²/2 (carry_shear)
  LaneMask apart;    // not `held` and at least the touching reach apart: no force, and the state of a pair
                     // never touched
};

// False when a pair that is not apart overlaps by more than half its smaller radius: it is passing through, and
// the one-contact pass gives the guard its message.
[[gnu::always_inline]] inline bool lane_geometry(const Particles<3>& p, const Pair* pairs, const LaneMask& held,
                                                 double dt, LaneGeometry& g) {
  lane_partners(pairs, g.ia, g.ib);
  const Lane3 xa = gather(p.x, g.ia), xb = gather(p.x, g.ib);
  g.ra = gather(p.radius, g.ia), g.rb = gather(p.radius, g.ib);
  g.d = xb - xa;
  g.reach = g.ra + g.rb;
  g.apart = dot(g.d, g.d) >= g.reach * g.reach && !held;
  const Lane dist = dot(g.d, g.d).sqrt();
  g.n = g.d * (1.0 / dist);
  g.overlap = g.reach - dist;
  if ((!g.apart && g.overlap > 0.5 * g.ra.min(g.rb)).any()) return false;
  g.ca = (g.ra - 0.5 * g.overlap) * g.n;
  g.cb = g.ca - g.d;
  g.wa = gather(p.w, g.ia), g.wb = gather(p.w, g.ib);
  g.v_rel = (gather(p.v, g.ib) + cross(g.wb, g.cb)) - (gather(p.v, g.ia) + cross(g.wa, g.ca));
  g.angle = 0.5 * dot(g.wa + g.wb, g.n) * dt;
  g.turn = 1.0 - 0.5 * g.angle * g.angle;
  return true;
}

// The results of kLanes contacts, as the one-contact pass stores them (ContactSet::forces_impl), lane by lane in pair
// order: nothing for an apart pair but the zeroing of its far slot; else the force on A and its moment about A's
// centre less the model's moment added to A's sums, and the force on B with its moment about B's centre plus the
// model's moment added to B's sums (a near pair) or written to its far slot (`moment` = nullptr: x − 0 is x, but
// −0 + 0 is +0, so the sum is kept even then). The force on B also goes to `record` on when the forces are kept.
template <class Slots>
[[gnu::always_inline]] inline void store_slots(Slots& s, BlockTarget& t, std::size_t record, const Particles<3>& p,
                                               const LaneGeometry& g, const Lane3& force, const Lane3* moment) {
  constexpr int kVec = 3;
  const LaneMask written = !g.apart;
  const Lane3 neg = Lane3{-force.x, -force.y, -force.z};
  const Lane3 ma = moment ? cross(g.ca, neg) - *moment : cross(g.ca, neg);
  const Lane3 mb = moment ? cross(g.cb, force) + *moment : 0.0 + cross(g.cb, force);
  const Lane f2 = dot(force, force);
  if (!s.pair_force.empty()) store_lanes3<kVec>(s.pair_force[record].data(), pick(written, force, 0.0));
  // Locals: the live bytes' stores could alias anything the loop reads through `s` and `t`.
  Vec<3>* sum_f = s.sum_force;
  Rot<3>* sum_m = s.sum_moment.data();
  Vec<3>* slot_f = s.f.data();
  Rot<3>* slot_m = s.mb.data();
  std::uint8_t* live = s.live.data();
  const int near_end = t.near_end;
  const bool ghosts = !p.ghost.empty();
  std::size_t far = t.far, touching = t.touching;
  for (int l = 0; l < kLanes; ++l) {
    const int a = g.ia[l], b = g.ib[l];
    const bool is_far = b >= near_end;
    const std::size_t slot = is_far ? far++ : 0;
    if (!written[l]) [[unlikely]] {
      if (is_far && live[slot]) slot_f[slot].setZero(), slot_m[slot].setZero(), live[slot] = 0;
      continue;
    }
    touching += f2[l] > 0 && !(ghosts && p.ghost[a]);
    double* fa = sum_f[a].data();
    fa[0] -= force.x[l], fa[1] -= force.y[l], fa[2] -= force.z[l];
    double* mo = sum_m[a].data();
    mo[0] += ma.x[l], mo[1] += ma.y[l], mo[2] += ma.z[l];
    double* fb = is_far ? slot_f[slot].data() : sum_f[b].data();
    double* mob = is_far ? slot_m[slot].data() : sum_m[b].data();
    if (is_far) {
      fb[0] = force.x[l], fb[1] = force.y[l], fb[2] = force.z[l];
      mob[0] = mb.x[l], mob[1] = mb.y[l], mob[2] = mb.z[l];
      live[slot] = 1;
    } else {
      fb[0] += force.x[l], fb[1] += force.y[l], fb[2] += force.z[l];
      mob[0] += mb.x[l], mob[1] += mb.y[l], mob[2] += mb.z[l];
    }
  }
  t.far = far, t.touching = touching;
}

}  // namespace mc
