#include "preprocess/random_box.hpp"

#include <cmath>
#include <random>
#include <sstream>
#include <unordered_map>

#include "engine/errors.hpp"

namespace mc {

namespace {
// Uniform in [a, b) from the raw 64-bit stream: the same numbers on every platform and library.
double uniform(std::mt19937_64& g, double a, double b) {
  return a + (b - a) * (static_cast<double>(g() >> 11) * 0x1.0p-53);
}
}  // namespace

template <int D>
Packing<D> random_box_packing(const Vec<D>& lo, const Vec<D>& hi, std::int64_t count, double r_min, double r_max,
                              std::uint64_t seed) {
  std::mt19937_64 g(seed);
  Packing<D> out;
  const double h = 2.0 * r_max;  // hash cells: any overlapping pair lies in neighbouring cells
  std::unordered_map<std::int64_t, std::vector<int>> cells;
  auto key = [&](const std::array<std::int64_t, 3>& c) {
    return (c[0] * 73856093) ^ (c[1] * 19349663) ^ (c[2] * 83492791);
  };
  auto cell_of = [&](const Vec<D>& p) {
    std::array<std::int64_t, 3> c{0, 0, 0};
    for (int k = 0; k < D; ++k) c[k] = static_cast<std::int64_t>(std::floor((p[k] - lo[k]) / h));
    return c;
  };
  for (int k = 0; k < D; ++k)
    if (hi[k] - lo[k] <= 2 * r_max) throw InputError("the box is narrower than a particle (2 radius_max)");
  const int attempts = 2000;  // per particle, before giving up
  double volume = 0;
  for (std::int64_t n = 0; n < count; ++n) {
    const double r = uniform(g, r_min, r_max);
    bool placed = false;
    for (int a = 0; a < attempts && !placed; ++a) {
      Vec<D> p;
      for (int k = 0; k < D; ++k) p[k] = uniform(g, lo[k] + r, hi[k] - r);
      const auto c = cell_of(p);
      bool free = true;
      std::array<std::int64_t, 3> o{0, 0, 0};
      const int zr = D == 3 ? 1 : 0;
      for (o[0] = -1; o[0] <= 1 && free; ++o[0])
        for (o[1] = -1; o[1] <= 1 && free; ++o[1])
          for (o[2] = -zr; o[2] <= zr && free; ++o[2]) {
            const auto it = cells.find(key({c[0] + o[0], c[1] + o[1], c[2] + o[2]}));
            if (it == cells.end()) continue;
            for (int j : it->second)
              if ((out.x[j] - p).norm() < out.radius[j] + r) {
                free = false;
                break;
              }
          }
      if (!free) continue;
      cells[key(c)].push_back(static_cast<int>(out.x.size()));
      out.x.push_back(p);
      out.radius.push_back(r);
      volume += Dim<D>::volume(r);
      placed = true;
    }
    if (!placed) {
      double box = 1;
      for (int k = 0; k < D; ++k) box *= hi[k] - lo[k];
      std::ostringstream m;
      m << "could not place particle " << n + 1 << " of " << count << " without overlap after " << attempts
        << " attempts (packing fraction reached " << volume / box
        << "); random placement fills at most about 0.5 (2D) / 0.35 (3D): lower 'count' or enlarge the box";
      throw InputError(m.str());
    }
  }
  return out;
}

template Packing<2> random_box_packing<2>(const Vec<2>&, const Vec<2>&, std::int64_t, double, double, std::uint64_t);
template Packing<3> random_box_packing<3>(const Vec<3>&, const Vec<3>&, std::int64_t, double, double, std::uint64_t);

}  // namespace mc
