#include "rigid_cell/facet_law.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "engine/errors.hpp"

namespace mc::rigid_cell {

namespace {

// The tensile-shear boundary of (3.16) in stresses, units of f_t: 0.02 s_N² − 0.5 s_T² − 4.52 s_N + 4.5 = 0, which
// holds pure tension at s_N = f_t and pure shear at s_T = 3 f_t. Solved along s_N = f sin ω, s_T = √α f cos ω its
// discriminant is 20.0704 sin²ω + 9α cos²ω; the thesis prints 20, which would put pure tension at 1.2 f_t.
constexpr double kA = 0.02, kB = 4.52, kC = 4.5, kShear = 0.5;
constexpr double kCompression = 16;  // the compressive boundary: a circle of radius 16 f_t, (3.16)

}  // namespace

double omega_0(double alpha) {
  // s_T² = 256 − s_N² into the hyperbola: (kA + kShear) s_N² − kB s_N + kC − kShear·256 = 0, its negative root.
  const double a = kA + kShear, b = -kB, c = kC - kShear * kCompression * kCompression;
  const double sN = (-b - std::sqrt(b * b - 4 * a * c)) / (2 * a);
  const double sT = std::sqrt(kCompression * kCompression - sN * sN);
  return std::atan(std::sqrt(alpha) * sN / sT);
}

double elastic_limit(double omega, const FacetParams& p) {
  const double s = std::sin(omega), c = std::cos(omega);
  if (omega < omega_0(p.alpha)) return kCompression * p.tensile_strength / std::sqrt(s * s + p.alpha * c * c);
  // The smaller positive root of (kA s² − kShear α c²) f² − kB s f + kC = 0.
  const double a = kA * s * s - kShear * p.alpha * c * c, b = -kB * s;
  const double disc = std::sqrt(b * b - 4 * a * kC);
  return p.tensile_strength * (2 * kC) / (-b + disc);  // the same root, written without the cancellation near ω = π/2
}

Slopes crack_band_slopes(const FacetParams& p, double L) {
  const double ft2L = p.tensile_strength * p.tensile_strength * L;
  if (!(2 * p.E0 * p.fracture_energy > ft2L) || !(32 * p.alpha * p.E0 * p.fracture_energy > 9 * ft2L)) {
    std::ostringstream m;
    m << "a facet " << L << " m long with f_t " << p.tensile_strength << " Pa, G_t " << p.fracture_energy << " N/m and E0 " << p.E0
      << " Pa snaps back: the crack band needs 2 E0 G_t > f_t^2 L and 32 alpha E0 G_t > 9 f_t^2 L (Kveton (3.20)); "
      << "use smaller cells or a larger G_t";
    throw InputError(m.str());
  }
  return {2 * p.E0 * ft2L / (2 * p.E0 * p.fracture_energy - ft2L),
          18 * p.alpha * p.E0 * ft2L / (32 * p.alpha * p.E0 * p.fracture_energy - 9 * ft2L)};
}

double rate_increase(const FacetParams& p, double strain_rate) {
  return p.rate_c1 > 0 ? 1 + p.rate_c1 * std::asinh(strain_rate / p.rate_c0) : 1.0;
}

double strain_rate(const Eigen::Vector3d& e_rate, const FacetParams& p) {
  const Eigen::Vector3d& r = e_rate;
  return std::sqrt(r[0] * r[0] + p.alpha * (r[1] * r[1] + r[2] * r[2]));
}

double damage(const Eigen::Vector3d& e, const FacetParams& p, double L, const FacetState& s, double strain_rate) {
  if (!(p.tensile_strength > 0)) return 0;
  const double eT = std::hypot(e[1], e[2]);
  const double e_eq = std::sqrt(e[0] * e[0] + p.alpha * eT * eT);  // (3.12)
  if (e_eq == 0) return s.D_max;
  const double omega = std::atan2(e[0], std::sqrt(p.alpha) * eT);  // (3.15), in [−π/2, π/2] since eT ≥ 0
  const double f_eq = elastic_limit(omega, p);
  const double w0 = omega_0(p.alpha);
  double K;  // (3.18)-(3.19): hardening below ω₀, softening above
  if (omega < w0) {
    const double x = (omega + M_PI / 2) / (w0 + M_PI / 2);
    K = 0.26 * p.E0 * (1 - x * x);
  } else {
    const Slopes k = crack_band_slopes(p, L);
    const double n_t = std::log(k.Kt / (k.Kt - k.Ks)) / std::log(1 - 2 * w0 / M_PI);
    K = -k.Kt * (1 - std::pow((omega - M_PI / 2) / (w0 - M_PI / 2), n_t));
  }
  // (3.17), and (8.16): the limit raised by F(ẇ), the softening's initial slope K unchanged.
  const double limit = rate_increase(p, strain_rate) * f_eq;
  const double beyond = std::max(0.0, e_eq - limit / p.E0);
  const double s_eq = std::min((1 - s.D_max) * p.E0 * e_eq, limit * std::exp(K / f_eq * beyond));
  return std::max(s.D_max, 1 - s_eq / (p.E0 * e_eq));  // (3.14)
}

}  // namespace mc::rigid_cell
