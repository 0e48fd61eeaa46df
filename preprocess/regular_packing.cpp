#include "preprocess/regular_packing.hpp"

#include <cmath>
#include <sstream>
#include <string>

#include "engine/errors.hpp"

namespace mc {

namespace {

// Slack for sites that sit exactly on the far limit (a box sized to n spacings): round-off must not drop them.
constexpr double kSlack = 1e-9;

void check_radius(double radius) {
  if (!(radius > 0) || !std::isfinite(radius))
    throw InputError("regular packing: radius = " + std::to_string(radius) + ": must be positive and finite");
}

// Number of sites first, first + step, … that stay ≤ last (0 if first > last), with kSlack·radius of room.
int sites(double first, double last, double step, double radius) {
  const double room = last - first + kSlack * radius;
  return room < 0 ? 0 : static_cast<int>(std::floor(room / step)) + 1;
}

void check_dimension(double a, double b) {
  if (!std::isfinite(a) || !std::isfinite(b)) throw InputError("regular packing: the box must be finite");
}

void check_young_poisson(const char* what, double young, double poisson, double limit, const char* reason) {
  std::ostringstream m;
  if (!(young > 0) || !std::isfinite(young)) {
    m << what << ": Young's modulus E = " << young << " Pa must be positive";
    throw InputError(m.str());
  }
  if (!(poisson > -1 && poisson < limit)) {
    m << what << ": Poisson's ratio nu = " << poisson << " is outside what a bonded hexagonal lattice can have, "
      << "-1 < nu < " << reason;
    throw InputError(m.str());
  }
}

}  // namespace

Packing<2> hexagonal_packing(const Vec<2>& lo, const Vec<2>& hi, double radius) {
  check_radius(radius);
  for (int k = 0; k < 2; ++k) check_dimension(lo[k], hi[k]);
  const double R = radius, row_step = std::sqrt(3.0) * R;
  const int rows = sites(lo[1] + R, hi[1] - R, row_step, R);
  Packing<2> out;
  for (int j = 0; j < rows; ++j) {
    const double y = lo[1] + R + j * row_step;
    const double x_first = lo[0] + R + (j % 2) * R;  // odd rows offset by R
    const int n = sites(x_first, hi[0] - R, 2 * R, R);
    for (int i = 0; i < n; ++i) {
      out.x.emplace_back(x_first + 2 * R * i, y);
      out.radius.push_back(R);
    }
  }
  if (out.x.empty())
    throw InputError("hexagonal packing: the box holds no disc of radius " + std::to_string(R) +
                     " (it must be at least 2 R wide and high)");
  return out;
}

Packing<3> fcc_packing(const Vec<3>& lo, const Vec<3>& hi, double radius) {
  check_radius(radius);
  for (int k = 0; k < 3; ++k) check_dimension(lo[k], hi[k]);
  const double R = radius, half = std::sqrt(2.0) * R;  // a/2, a = 2√2 R
  int n[3];
  for (int k = 0; k < 3; ++k) n[k] = sites(lo[k] + R, hi[k] - R, half, R);
  Packing<3> out;
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = (j + k) % 2; i < n[0]; i += 2) {  // i + j + k even
        out.x.emplace_back(lo[0] + R + half * i, lo[1] + R + half * j, lo[2] + R + half * k);
        out.radius.push_back(R);
      }
  if (out.x.empty())
    throw InputError("fcc packing: the box holds no sphere of radius " + std::to_string(R) +
                     " (it must be at least 2 R wide in every direction)");
  return out;
}

LatticeStiffness hex_lattice_stiffness_plane_strain(double young, double poisson) {
  check_young_poisson("hexagonal lattice stiffness (plane strain, Tang 8.2)", young, poisson, 0.25,
                      "1/4 (nu >= 1/4 needs a zero or negative shear spring K^s)");
  const double nu = poisson, c = young / (std::sqrt(3.0) * (1 + nu) * (1 - 2 * nu));
  return {c, c * (1 - 4 * nu)};  // Tang (8.2)
}

LatticeStiffness hex_lattice_stiffness_plane_stress(double young, double poisson) {
  check_young_poisson("hexagonal lattice stiffness (plane stress, Tang 8.3)", young, poisson, 1.0 / 3.0,
                      "1/3 (nu >= 1/3 needs a zero or negative shear spring K^s)");
  const double nu = poisson, s3 = std::sqrt(3.0);
  return {young / (s3 * (1 - nu)), young * (1 - 3 * nu) / (s3 * (1 - nu * nu))};  // Tang (8.3)
}

}  // namespace mc
