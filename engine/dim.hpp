// Types that differ between 2D (discs of unit thickness, PFC2D conventions) and 3D (spheres).
// In 2D a rotation is a scalar about the out-of-plane axis; in 3D it is a vector.
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <limits>

namespace mc {

template <int D>
using Vec = Eigen::Matrix<double, D, 1>;

template <int D>
struct Dim;

template <>
struct Dim<2> {
  static constexpr int rot = 1;                            // rotational degrees of freedom
  using Rot = Eigen::Matrix<double, 1, 1>;                 // angular velocity, moment
  using Orientation = double;                              // angle [rad]
  static constexpr double inertia_factor = 0.5;            // I = ½ m R² for a disc, Tang (3.15)
  static double volume(double r) { return M_PI * r * r; }  // per unit thickness t = 1 m
  // ω × r for ω along z
  static Vec<2> cross(const Rot& w, const Vec<2>& r) { return {-w[0] * r[1], w[0] * r[0]}; }
  // r × F, the z component
  static Rot cross(const Vec<2>& r, const Vec<2>& f) { return Rot(r[0] * f[1] - r[1] * f[0]); }
  static Orientation identity() { return 0.0; }
  static void rotate(Orientation& q, const Rot& w, double dt) { q += w[0] * dt; }
};

template <>
struct Dim<3> {
  static constexpr int rot = 3;
  using Rot = Eigen::Vector3d;
  using Orientation = Eigen::Quaterniond;
  static constexpr double inertia_factor = 0.4;  // I = ⅖ m R² for a sphere, Tang (3.15)
  static double volume(double r) { return 4.0 / 3.0 * M_PI * r * r * r; }
  static Vec<3> cross(const Rot& w, const Vec<3>& r) { return w.cross(r); }
  static Orientation identity() { return Eigen::Quaterniond::Identity(); }
  // Rotation by the increment ω·Δt: the unit quaternion (cos a/2, sin(a/2) ω/|ω|) with the cosine and sine
  // from their series, exact to O(a⁵) for the a ≲ 1e-3 rad of a stable step, then renormalised. No trig per particle.
  static void rotate(Orientation& q, const Rot& w, double dt) {
    const Rot h = 0.5 * dt * w;  // (a/2)·axis
    const double h2 = h.squaredNorm();
    if (h2 == 0) return;
    const double c = 1.0 - 0.5 * h2 + h2 * h2 / 24.0, s = 1.0 - h2 / 6.0 + h2 * h2 / 120.0;
    q = (Eigen::Quaterniond(c, s * h[0], s * h[1], s * h[2]) * q).normalized();
  }
};

template <int D>
using Rot = typename Dim<D>::Rot;

inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace mc
