#include "preprocess/spatial_order.hpp"

#include <algorithm>
#include <cstdint>
#include <numeric>

namespace mc {

namespace {
// Spreads the low bits of v so that D interleaved coordinates form one key.
std::uint64_t spread(std::uint64_t v, int d) {
  std::uint64_t out = 0;
  const int bits = 63 / d;
  for (int b = 0; b < bits; ++b) out |= ((v >> b) & 1u) << (b * d);
  return out;
}
}  // namespace

template <int D>
std::vector<int> morton_order(const std::vector<Vec<D>>& x) {
  std::vector<int> order(x.size());
  std::iota(order.begin(), order.end(), 0);
  if (x.empty()) return order;
  Vec<D> lo = x[0], hi = x[0];
  for (const auto& p : x) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double cells = static_cast<double>((std::uint64_t(1) << (63 / D)) - 1);
  const double span = std::max((hi - lo).maxCoeff(), 1e-300);
  std::vector<std::uint64_t> key(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    std::uint64_t k = 0;
    for (int d = 0; d < D; ++d) k |= spread(static_cast<std::uint64_t>((x[i][d] - lo[d]) / span * cells), D) << d;
    key[i] = k;
  }
  // Stable, so equal keys keep their order: the numbering is reproducible.
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key[a] < key[b]; });
  return order;
}

template std::vector<int> morton_order<2>(const std::vector<Vec<2>>&);
template std::vector<int> morton_order<3>(const std::vector<Vec<3>>&);

}  // namespace mc
