#include "engine/decomposition.hpp"

#include <algorithm>
#include <numeric>

namespace mc {

template <int D>
Decomposition<D> Decomposition<D>::bisect(const std::vector<Vec<D>>& x, int ranks) {
  Decomposition d;
  d.lo_.assign(ranks, Vec<D>::Constant(-kInf));
  d.hi_.assign(ranks, Vec<D>::Constant(kInf));
  std::vector<int> items(x.size());
  std::iota(items.begin(), items.end(), 0);
  d.split(items, x, 0, ranks, Vec<D>::Constant(-kInf), Vec<D>::Constant(kInf));
  return d;
}

// Splits the region [lo, hi) holding `items` among ranks [first_rank, first_rank + ranks); returns the code of
// what it made: the index of its cut, or −1 − rank for a single region.
template <int D>
int Decomposition<D>::split(std::vector<int>& items, const std::vector<Vec<D>>& x, int first_rank, int ranks,
                            const Vec<D>& lo, const Vec<D>& hi) {
  if (ranks == 1) {
    lo_[first_rank] = lo;
    hi_[first_rank] = hi;
    return -1 - first_rank;
  }
  int axis = 0;
  if (!items.empty()) {
    Vec<D> a = x[items[0]], b = a;
    for (int i : items) a = a.cwiseMin(x[i]), b = b.cwiseMax(x[i]);
    (b - a).maxCoeff(&axis);
  }
  const int below_ranks = ranks / 2;
  const std::size_t k = items.size() * below_ranks / ranks;
  auto key = [&](int i, int j) { return x[i][axis] < x[j][axis] || (x[i][axis] == x[j][axis] && i < j); };
  std::nth_element(items.begin(), items.begin() + k, items.end(), key);
  const double at = k < items.size() ? x[items[k]][axis] : (items.empty() ? 0.0 : x[items.back()][axis]);
  std::vector<int> below, above;
  for (int i : items) (x[i][axis] < at ? below : above).push_back(i);
  const int me = static_cast<int>(cuts_.size());
  cuts_.push_back({axis, at, 0, 0});
  Vec<D> mid_hi = hi, mid_lo = lo;
  mid_hi[axis] = at;
  mid_lo[axis] = at;
  const int b = split(below, x, first_rank, below_ranks, lo, mid_hi);
  const int c = split(above, x, first_rank + below_ranks, ranks - below_ranks, mid_lo, hi);
  cuts_[me].below = b;
  cuts_[me].above = c;
  return me;
}

template <int D>
int Decomposition<D>::owner(const Vec<D>& x) const {
  if (cuts_.empty()) return 0;
  int at = 0;
  while (true) {
    const Cut& c = cuts_[at];
    const int next = x[c.axis] < c.at ? c.below : c.above;
    if (next < 0) return -1 - next;
    at = next;
  }
}

template <int D>
bool Decomposition<D>::near(int r, const Vec<D>& x, double reach) const {
  double d2 = 0;
  for (int k = 0; k < D; ++k) {
    const double out = std::max({lo_[r][k] - x[k], 0.0, x[k] - hi_[r][k]});
    d2 += out * out;
  }
  return d2 <= reach * reach;
}

template <int D>
std::vector<int> Decomposition<D>::neighbours(int r, double reach) const {
  std::vector<int> out;
  for (int o = 0; o < size(); ++o) {
    if (o == r) continue;
    double d2 = 0;
    for (int k = 0; k < D; ++k) {
      const double gap = std::max({lo_[o][k] - hi_[r][k], lo_[r][k] - hi_[o][k], 0.0});
      d2 += gap * gap;
    }
    if (d2 <= reach * reach) out.push_back(o);
  }
  return out;
}

template class Decomposition<2>;
template class Decomposition<3>;

}  // namespace mc
