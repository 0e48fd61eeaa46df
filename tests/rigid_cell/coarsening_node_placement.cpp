// Cells that coarsen away from a fine box: the spacing rule holds between every pair of nodes, the box is as dense
// as a uniform placement at l_min, far away as dense as one at l_max, and the cells still tile the specimen.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "rigid_cell/node_placement.hpp"
#include "rigid_cell/tessellation.hpp"
#include "tests/common/relative.hpp"

using namespace mc;
using namespace mc::rigid_cell;

namespace {

template <class Inside>
double count_in(const std::vector<Vec<2>>& nodes, Inside inside) {
  double n = 0;
  for (const auto& x : nodes) n += inside(x) ? 1 : 0;
  return n;
}

}  // namespace

TEST_CASE("coarsening cells keep the mean spacing of every pair and the density of uniform placements") {
  const auto shape = SpecimenShape<2>::box(Vec<2>(0.2, 0.05));
  NodeSpacing<2> s{.l_min = 2e-3, .l_max = 6e-3, .grading = 0.25};
  s.fine_lo = Vec<2>(0.08, 0), s.fine_hi = Vec<2>(0.12, 0.05);
  const auto nodes = place_nodes(shape, s, 7, 2000);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    CHECK(shape.depth(nodes[i]) >= 0.5 * s.at(nodes[i]));
    for (std::size_t j = 0; j < i; ++j)
      if ((nodes[i] - nodes[j]).norm() < 0.5 * (s.at(nodes[i]) + s.at(nodes[j]))) FAIL("nodes ", i, ", ", j);
  }
  // Saturated random sequential addition holds 0.62 nodes per l² (measured on uniform boxes): the fine box within
  // 5 % of a uniform placement at l_min on the same box (both random, about 500 nodes: ±4.5 % is 1 σ of neither).
  const auto uniform_fine = place_nodes(SpecimenShape<2>::box(Vec<2>(0.04, 0.05)), s.l_min, 7, 2000);
  const double in_box = count_in(nodes, [&](const Vec<2>& x) { return x[0] > 0.08 && x[0] < 0.12; });
  CHECK(in_box == mc::test::relative(static_cast<double>(uniform_fine.size()), 0.05));
  // Beyond (l_max − l_min)/grading = 16 mm from the box the spacing is l_max: the ends as a uniform placement at
  // l_max, within 15 % (about 60 nodes each, and the transition's finer nodes reach into the first row).
  const double ends = count_in(nodes, [](const Vec<2>& x) { return x[0] < 0.05 || x[0] > 0.15; });
  const double uniform_coarse = 0.62 * 2 * (0.05 - s.l_max) * (0.05 - s.l_max / 2) / (s.l_max * s.l_max);
  CHECK(ends == mc::test::relative(uniform_coarse, 0.15));
  CHECK(nodes.size() < 0.5 * 0.62 * 0.2 * 0.05 / (s.l_min * s.l_min));  // fewer than half the uniform l_min cells
  const auto t = tessellate(nodes, shape, 3 * s.l_max);
  CHECK(t.volume() == mc::test::relative(shape.volume(), 1e-10));
}
