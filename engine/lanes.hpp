// Contacts side by side: each number of a contact law held as an array of kLanes lanes (Eigen's fixed-size
// arrays, which the compiler turns into SIMD instructions), so that a model can run several contacts through one
// sequence of instructions. The lanes repeat the scalar code's operations in the scalar code's order (Eigen's
// Vector3d sums x, y, z from the left), and IEEE arithmetic is the same in a lane as in a scalar register, so a
// law run in lanes gives the same bits as run one contact at a time (the build turns off fused multiply-add).
#pragma once
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "engine/cell_grid.hpp"
#include "engine/contact_geometry.hpp"
#include "engine/dim.hpp"

namespace mc {

// Two lanes per SSE register, four per AVX register. Wider lanes gained nothing on the parallel bond
// (AVX-512, 8 lanes: 3.7e6 particle-steps/s against 4.1e6 with 4): the kernel waits on gathering the particles and
// on spilled registers, not on arithmetic.
#if defined(__AVX__)
inline constexpr int kLanes = 4;
#else
inline constexpr int kLanes = 2;
#endif
using Lane = Eigen::Array<double, kLanes, 1>;
using LaneMask = Eigen::Array<bool, kLanes, 1>;
using LaneIndex = Eigen::Array<int, kLanes, 1>;

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
[[gnu::always_inline]] inline Lane pick(const LaneMask& m, const Lane& a, const Lane& b) { return m.select(a, b); }
[[gnu::always_inline]] inline Lane pick(const LaneMask& m, const Lane& a, double b) { return m.select(a, b); }
[[gnu::always_inline]] inline Lane3 pick(const LaneMask& m, const Lane3& a, const Lane3& b) {
  return {m.select(a.x, b.x), m.select(a.y, b.y), m.select(a.z, b.z)};
}
[[gnu::always_inline]] inline Lane3 pick(const LaneMask& m, const Lane3& a, double b) {
  return {m.select(a.x, b), m.select(a.y, b), m.select(a.z, b)};
}

// The two partners of kLanes consecutive pairs.
[[gnu::always_inline]] inline void lane_partners(const Pair* pairs, LaneIndex& a, LaneIndex& b) {
  for (int l = 0; l < kLanes; ++l) a[l] = pairs[l][0], b[l] = pairs[l][1];
}
// Per-particle values of the partners in `idx`.
[[gnu::always_inline]] inline Lane gather(const std::vector<double>& v, const LaneIndex& idx) {
  Lane g;
  for (int l = 0; l < kLanes; ++l) g[l] = v[idx[l]];
  return g;
}
[[gnu::always_inline]] inline Lane3 gather(const std::vector<Vec<3>>& v, const LaneIndex& idx) {
  Lane3 g;
  for (int l = 0; l < kLanes; ++l) {
    const Vec<3>& e = v[idx[l]];
    g.x[l] = e[0], g.y[l] = e[1], g.z[l] = e[2];
  }
  return g;
}

// A field of kLanes consecutive records of `Stride` doubles each (a contact state, a slot's vector): `at` points
// at the field in the first record.
template <int Stride>
using LaneField = Eigen::Map<Lane, 0, Eigen::InnerStride<Stride>>;

template <int Stride>
[[gnu::always_inline]] inline Lane load_lanes(const double* at) {
  return Eigen::Map<const Lane, 0, Eigen::InnerStride<Stride>>(at);
}
template <int Stride>
[[gnu::always_inline]] inline Lane3 load_lanes3(const double* at) {
  return {load_lanes<Stride>(at), load_lanes<Stride>(at + 1), load_lanes<Stride>(at + 2)};
}
template <int Stride>
[[gnu::always_inline]] inline void store_lanes(double* at, const Lane& v) {
  LaneField<Stride> field(at);
  field = v;
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

}  // namespace mc
