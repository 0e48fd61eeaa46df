// Nodes at the centres of an nx × ny × nz grid of cubes of side h: their Voronoi cells are those cubes.
#pragma once
#include <vector>

#include "engine/dim.hpp"

namespace mc::test {

inline std::vector<Vec<3>> cubic_grid_nodes(double h, int nx, int ny, int nz) {
  std::vector<Vec<3>> nodes;
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int k = 0; k < nz; ++k) nodes.push_back(h * Vec<3>(i + 0.5, j + 0.5, k + 0.5));
  return nodes;
}

}  // namespace mc::test
