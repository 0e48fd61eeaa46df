// The background grid and status matrix of the aggregate placement (StatusGrid, aggregate_placement.hpp), and
// Tang's detailed determination on it (§4.2): which cells a convex body covers.
#pragma once
#include <cstdint>
#include <vector>

#include "preprocess/aggregate_placement.hpp"
#include "preprocess/convex_body.hpp"

namespace mc {

// The cells whose centres the body covers, row by row along x (each row clipped by every half-space), into
// `covered`; false at the first taken cell (status ≠ 0), whose status goes to `hit`.
template <int D>
bool rasterise(const StatusGrid<D>& grid, const Body<D>& b, std::vector<std::int32_t>& covered, std::int32_t& hit);

}  // namespace mc
