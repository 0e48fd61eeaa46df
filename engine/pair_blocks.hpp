// The blocks of a contact set's force pass: one per group of kGroup particles (parallel.hpp), holding the pairs whose
// A is of the group (the pairs are sorted by A). A pair whose B is of the group too is near: its thread sums it on
// both sides. The others are far and write slots, numbered in pair order (engine/slots.hpp).
#pragma once
#include <cstddef>
#include <vector>

#include "engine/cell_grid.hpp"

namespace mc {

struct PairBlocks {
  std::vector<std::size_t> first;  // per block its first pair, then the pair count
  std::vector<std::size_t> far;    // per block the far pairs before it, then their count
  std::vector<int> near_end;       // per block the first particle of the next group: B below it is near

  // `group_begin`: the first particle of each group in this process's numbering, then the particle count.
  void build(const std::vector<Pair>& pairs, const std::vector<int>& group_begin) {
    const std::size_t groups = group_begin.size() - 1;
    first.assign(groups + 1, pairs.size());
    near_end.resize(groups);
    far.assign(groups + 1, 0);
    std::size_t c = 0, n_far = 0;
    for (std::size_t k = 0; k < groups; ++k) {
      first[k] = c;
      far[k] = n_far;
      near_end[k] = group_begin[k + 1];
      for (; c < pairs.size() && pairs[c][0] < near_end[k]; ++c) n_far += pairs[c][1] >= near_end[k];
    }
    far[groups] = n_far;
  }
  int count() const { return static_cast<int>(near_end.size()); }
  int group_first(int k) const { return k == 0 ? 0 : near_end[k - 1]; }  // block k's group starts where k − 1's ends
  std::size_t far_count() const { return far.empty() ? 0 : far.back(); }
  // The far pairs' indices, in the order of their slots.
  std::vector<std::size_t> far_pairs(const std::vector<Pair>& pairs) const {
    std::vector<std::size_t> out;
    out.reserve(far_count());
    for (int k = 0; k < count(); ++k)
      for (std::size_t c = first[k]; c < first[k + 1]; ++c)
        if (pairs[c][1] >= near_end[k]) out.push_back(c);
    return out;
  }
};

}  // namespace mc
