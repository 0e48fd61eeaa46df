#include "rigid_cell/plate_constraints.hpp"

namespace mc::rigid_cell {

template <int D>
PlateConstraints<D>::PlateConstraints(int cells) : first_plate_dof_(cells * kDofs) {
  map_.resize(cells * kDofs, cells * kDofs);
  map_.setIdentity();
}

template <int D>
PlateConstraints<D>::PlateConstraints(const std::vector<Vec<D>>& nodes, const std::vector<int>& plate_of,
                                      const std::vector<Vec<D>>& references)
    : plates_(static_cast<int>(references.size())) {
  const int n = static_cast<int>(nodes.size());
  std::vector<int> owner(n);  // the reduced block each cell moves with: its own, or its plate's
  int free = 0;
  for (int c = 0; c < n; ++c)
    if (plate_of[c] < 0) owner[c] = free++;
  first_plate_dof_ = free * kDofs;
  for (int c = 0; c < n; ++c)
    if (plate_of[c] >= 0) owner[c] = free + plate_of[c];

  std::vector<Eigen::Triplet<double>> t;
  for (int c = 0; c < n; ++c) {
    const int row = c * kDofs, col = owner[c] * kDofs;
    for (int k = 0; k < kDofs; ++k) t.emplace_back(row + k, col + k, 1.0);
    if (plate_of[c] < 0) continue;
    // u = U + Θ × r: the translation rows take −[r]× Θ (2D: Θ about z, ẑ × r = (−r_y, r_x)).
    const Vec<D> r = nodes[c] - references[plate_of[c]];
    if constexpr (D == 2) {
      t.emplace_back(row, col + 2, -r[1]);
      t.emplace_back(row + 1, col + 2, r[0]);
    } else {
      t.emplace_back(row, col + 4, r[2]), t.emplace_back(row, col + 5, -r[1]);
      t.emplace_back(row + 1, col + 3, -r[2]), t.emplace_back(row + 1, col + 5, r[0]);
      t.emplace_back(row + 2, col + 3, r[1]), t.emplace_back(row + 2, col + 4, -r[0]);
    }
  }
  map_.resize(n * kDofs, (free + plates_) * kDofs);
  map_.setFromTriplets(t.begin(), t.end());
}

template class PlateConstraints<2>;
template class PlateConstraints<3>;

}  // namespace mc::rigid_cell
