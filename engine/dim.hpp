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
  static constexpr double inertia_factor = 0.5;            // I = ½ m R² for a disc, Tang (3.15)
  static double volume(double r) { return M_PI * r * r; }  // per unit thickness t = 1 m
  // ω × r for ω along z
  static Vec<2> cross(const Rot& w, const Vec<2>& r) { return {-w[0] * r[1], w[0] * r[0]}; }
  // r × F, the z component
  static Rot cross(const Vec<2>& r, const Vec<2>& f) { return Rot(r[0] * f[1] - r[1] * f[0]); }
};

template <>
struct Dim<3> {
  static constexpr int rot = 3;
  using Rot = Eigen::Vector3d;
  static constexpr double inertia_factor = 0.4;  // I = ⅖ m R² for a sphere, Tang (3.15)
  static double volume(double r) { return 4.0 / 3.0 * M_PI * r * r * r; }
  static Vec<3> cross(const Rot& w, const Vec<3>& r) { return w.cross(r); }
};

template <int D>
using Rot = typename Dim<D>::Rot;

inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace mc
