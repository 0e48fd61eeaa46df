#include "rigid_cell/fibre_placement.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/errors.hpp"

namespace mc::rigid_cell {

long fibre_count(const FibrePlacement& p, double volume) {
  if (p.count > 0) return p.count;
  return std::lround(p.volume_fraction * volume / (0.25 * M_PI * p.diameter * p.diameter * p.length));
}

namespace {

// A unit vector with cosine w to the z axis and azimuth φ, turned so that z goes to `axis` (unit).
Vec<3> about(const Vec<3>& axis, double w, double phi) {
  const double s = std::sqrt(std::max(0.0, 1.0 - w * w));
  const Vec<3> local(s * std::cos(phi), s * std::sin(phi), w);
  return Eigen::Quaterniond::FromTwoVectors(Vec<3>::UnitZ(), axis) * local;
}

}  // namespace

Vec<3> draw_direction(const FibrePlacement& p, RandomStream& rng) {
  switch (p.orientation) {
    case FibreOrientation::Aligned:
      return p.direction;
    case FibreOrientation::Isotropic: {
      const double w = rng.uniform(-1.0, 1.0), phi = rng.uniform(0.0, 2 * M_PI);
      return about(Vec<3>::UnitZ(), w, phi);
    }
    case FibreOrientation::Preferential: {
      // The cosine by inverting its distribution, F(w) = (e^{κw} − e^{−κ})/(e^{κ} − e^{−κ}), written so that large κ
      // does not overflow: w = 1 + ln(ξ + (1 − ξ) e^{−2κ})/κ (κ = 0: isotropic).
      const double k = p.concentration, xi = rng.uniform(), phi = rng.uniform(0.0, 2 * M_PI);
      const double w = k > 0 ? 1.0 + std::log(xi + (1.0 - xi) * std::exp(-2.0 * k)) / k : 2.0 * xi - 1.0;
      return about(p.direction, std::clamp(w, -1.0, 1.0), phi);
    }
  }
  return p.direction;
}

std::vector<Fibre> place_fibres(const SpecimenShape<3>& shape, const FibrePlacement& p, RandomStream& rng) {
  const long n = fibre_count(p, shape.volume());
  const Vec<3> lo = shape.lo(), hi = shape.hi();
  const double half = 0.5 * p.length;
  std::vector<Fibre> out;
  out.reserve(static_cast<std::size_t>(n));
  for (long i = 0; i < n; ++i) {
    for (int draw = 0;; ++draw) {
      if (draw == 10000)
        throw InputError("[rigid_cell.fibres]: no fibre of length " + std::to_string(p.length) +
                         " m fits wholly inside the specimen in 10000 draws: shorten the fibres, or let them be cut "
                         "at the surface (boundary = \"cut\")");
      Vec<3> c;
      for (int k = 0; k < 3; ++k) c[k] = rng.uniform(lo[k], hi[k]);
      const Vec<3> u = draw_direction(p, rng);
      if (!shape.inside(c)) continue;
      const double ahead = shape.exit_distance(c, u), behind = shape.exit_distance(c, -u);
      if (p.boundary == FibreBoundary::Redraw) {
        if (ahead < half || behind < half) continue;
        out.push_back({c - half * u, c + half * u});
      } else {
        out.push_back({c - std::min(half, behind) * u, c + std::min(half, ahead) * u});
      }
      break;
    }
  }
  return out;
}

}  // namespace mc::rigid_cell
