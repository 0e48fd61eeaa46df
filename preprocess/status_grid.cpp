#include "preprocess/status_grid.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace mc {

namespace {

// The cells c0–c1 whose centres lie in the body's bounding box; false when there are none.
template <int D>
bool cells_under_box(const StatusGrid<D>& grid, const Body<D>& b, std::array<int, D>& c0, std::array<int, D>& c1) {
  for (int k = 0; k < D; ++k) {
    c0[k] = std::max(0, static_cast<int>(std::ceil((b.lo[k] - grid.lo[k]) / grid.h[k] - 0.5)));
    c1[k] = std::min(grid.n[k] - 1, static_cast<int>(std::floor((b.hi[k] - grid.lo[k]) / grid.h[k] - 0.5)));
    if (c1[k] < c0[k]) return false;
  }
  return true;
}

// The stretch xl ≤ x ≤ xu of the grid row through y (y[1], y[2] given) inside the body, clipped by every
// half-space; empty when xl > xu.
template <int D>
std::pair<double, double> row_span(const Body<D>& b, const Vec<D>& y) {
  double xl = -kInf, xu = kInf;
  for (std::size_t f = 0; f < b.n.size(); ++f) {
    double rhs = b.off[f];
    for (int k = 1; k < D; ++k) rhs -= b.n[f][k] * y[k];
    const double a = b.n[f][0];
    if (a > 1e-14)
      xu = std::min(xu, rhs / a);
    else if (a < -1e-14)
      xl = std::max(xl, rhs / a);
    else if (rhs < 0)
      xu = -kInf;
  }
  return {xl, xu};
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
bool rasterise(const StatusGrid<D>& grid, const Body<D>& b, std::vector<std::int32_t>& covered, std::int32_t& hit) {
  covered.clear();
  std::array<int, D> c0, c1;
  if (!cells_under_box<D>(grid, b, c0, c1)) return true;
  std::array<int, 3> j{0, 0, 0};
  const int z0 = D == 3 ? c0[D - 1] : 0, z1 = D == 3 ? c1[D - 1] : 0;
  for (j[2] = z0; j[2] <= z1; ++j[2])
    for (j[1] = c0[1]; j[1] <= c1[1]; ++j[1]) {
      Vec<D> y;
      for (int k = 1; k < D; ++k) y[k] = grid.lo[k] + (j[k] + 0.5) * grid.h[k];
      const auto [xl, xu] = row_span(b, y);
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
}

template struct StatusGrid<2>;
template struct StatusGrid<3>;
template bool rasterise<2>(const StatusGrid<2>&, const Body<2>&, std::vector<std::int32_t>&, std::int32_t&);
template bool rasterise<3>(const StatusGrid<3>&, const Body<3>&, std::vector<std::int32_t>&, std::int32_t&);

}  // namespace mc
