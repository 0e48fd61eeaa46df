#include "engine/cell_grid.hpp"

#include "engine/parallel.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace mc {

namespace {

template <int D>
struct Grid {
  Vec<D> lo;
  double h;
  std::array<std::int64_t, D> n;
  std::vector<int> start, items;  // counting-sort layout: items of cell c are items[start[c] .. start[c+1])

  std::array<std::int64_t, D> cell_of(const Vec<D>& p) const {
    std::array<std::int64_t, D> c;
    for (int k = 0; k < D; ++k)
      c[k] = std::clamp<std::int64_t>(static_cast<std::int64_t>((p[k] - lo[k]) / h), 0, n[k] - 1);
    return c;
  }
  std::int64_t index(const std::array<std::int64_t, D>& c) const {
    std::int64_t id = 0;
    for (int k = D - 1; k >= 0; --k) id = id * n[k] + c[k];
    return id;
  }
};

template <int D>
Grid<D> bin(const std::vector<Vec<D>>& x, double h) {
  Grid<D> g;
  Vec<D> lo = x[0], hi = x[0];
  for (const auto& p : x) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  g.lo = lo;
  g.h = h;
  // Cap the cell count so a few far-flung particles cannot make the grid huge (cells just get more crowded).
  const double cap = std::pow(8.0 * static_cast<double>(x.size()) + 64.0, 1.0 / D);
  for (int k = 0; k < D; ++k) {
    const double ext = hi[k] - lo[k];
    g.n[k] = std::max<std::int64_t>(
        1, std::min<std::int64_t>(static_cast<std::int64_t>(ext / h) + 1, static_cast<std::int64_t>(cap)));
    if (static_cast<double>(g.n[k]) * h <= ext) g.h = std::max(g.h, ext / static_cast<double>(g.n[k]) * 1.000001);
  }
  std::int64_t cells = 1;
  for (int k = 0; k < D; ++k) cells *= g.n[k];
  std::vector<std::int64_t> cell(x.size());
  g.start.assign(cells + 1, 0);
  for (std::size_t i = 0; i < x.size(); ++i) {
    cell[i] = g.index(g.cell_of(x[i]));
    ++g.start[cell[i] + 1];
  }
  for (std::int64_t c = 0; c < cells; ++c) g.start[c + 1] += g.start[c];
  g.items.resize(x.size());
  std::vector<int> fill(g.start.begin(), g.start.end() - 1);
  for (std::size_t i = 0; i < x.size(); ++i) g.items[fill[cell[i]]++] = static_cast<int>(i);
  return g;
}

}  // namespace

template <int D>
std::vector<Pair> candidate_pairs(const std::vector<Vec<D>>& x, const std::vector<double>& radius, double skin) {
  const int n = static_cast<int>(x.size());
  if (n < 2) return {};
  double rmax = 0;
  for (double r : radius) rmax = std::max(rmax, r);
  const Grid<D> g = bin<D>(x, 2.0 * rmax + skin);

  // Each thread takes a contiguous block of i (static schedule) and keeps its pairs in i order;
  // the blocks are joined in thread order, so the result is the same for any thread count.
  std::vector<std::vector<Pair>> parts(omp_get_max_threads());
#pragma omp parallel if (n > kParallelMin)
  {
    auto& out = parts[omp_get_thread_num()];
    std::vector<int> near;
#pragma omp for schedule(static)
    for (int i = 0; i < n; ++i) {
      near.clear();
      const auto c = g.cell_of(x[i]);
      std::array<std::int64_t, D> lo, hi, k;
      for (int d = 0; d < D; ++d) {
        lo[d] = std::max<std::int64_t>(c[d] - 1, 0);
        hi[d] = std::min<std::int64_t>(c[d] + 1, g.n[d] - 1);
        k[d] = lo[d];
      }
      while (true) {
        const std::int64_t id = g.index(k);
        for (int s = g.start[id]; s < g.start[id + 1]; ++s) {
          const int j = g.items[s];
          if (j <= i) continue;
          const double reach = radius[i] + radius[j] + skin;
          if ((x[j] - x[i]).squaredNorm() < reach * reach) near.push_back(j);
        }
        int d = 0;
        while (d < D && ++k[d] > hi[d]) k[d] = lo[d], ++d;
        if (d == D) break;
      }
      std::sort(near.begin(), near.end());
      for (int j : near) out.push_back({i, j});
    }
  }
  std::size_t total = 0;
  for (const auto& p : parts) total += p.size();
  std::vector<Pair> pairs;
  pairs.reserve(total);
  for (const auto& p : parts) pairs.insert(pairs.end(), p.begin(), p.end());
  return pairs;
}

template std::vector<Pair> candidate_pairs<2>(const std::vector<Vec<2>>&, const std::vector<double>&, double);
template std::vector<Pair> candidate_pairs<3>(const std::vector<Vec<3>>&, const std::vector<double>&, double);

}  // namespace mc
