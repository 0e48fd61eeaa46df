// Linked-cell contact detection: particles binned into cubic cells of edge ≥ 2 R_max + skin, so that every pair
// within reach lies in the same or an adjacent cell. O(N) per rebuild.
#pragma once
#include <array>
#include <vector>

#include "engine/dim.hpp"

namespace mc {

using Pair = std::array<int, 2>;

// All pairs i < j with |x_i − x_j| < R_i + R_j + skin, sorted by (i, j) whatever the thread count.
template <int D>
std::vector<Pair> candidate_pairs(const std::vector<Vec<D>>& x, const std::vector<double>& radius, double skin);

}  // namespace mc
