// Random loose packing: particles with radii uniform in [R_min, R_max] placed one by one at random points of a
// box, each without overlapping those placed before (random sequential addition). The start of a deposition or
// of a compaction by walls.
#pragma once
#include <cstdint>
#include <vector>

#include "engine/dim.hpp"

namespace mc {

template <int D>
struct Packing {
  std::vector<Vec<D>> x;
  std::vector<double> radius;
};

// Throws InputError when `count` particles do not fit (the message gives the packing fraction reached).
template <int D>
Packing<D> random_box_packing(const Vec<D>& lo, const Vec<D>& hi, std::int64_t count, double r_min, double r_max,
                              std::uint64_t seed);

}  // namespace mc
