#include "rigid_cell/plate_constraints.hpp"

#include "rigid_cell/point_motion.hpp"

namespace mc::rigid_cell {

template <int D>
PlateConstraints<D>::PlateConstraints(int cells) : first_plate_dof_(cells * kDofs) {
  map_.resize(cells * kDofs, cells * kDofs);
  map_.setIdentity();
}

template <int D>
PlateConstraints<D>::PlateConstraints(const std::vector<Vec<D>>& nodes, const std::vector<int>& plate_of,
                                      const std::vector<Vec<D>>& references)
    : plates_(static_cast<int>(references.size())), references_(references) {
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
    // The cell's node moves with the plate (3.2): its translation rows take the plate's rotation through
    // A_reference^node (every entry but the skew matrix's zero diagonal, so the pattern does not hang on r); its
    // own rotation is the plate's (the identity above).
    const auto A = point_motion<D>(references[plate_of[c]], nodes[c]);
    for (int i = 0; i < D; ++i)
      for (int k = D; k < kDofs; ++k)
        if (D == 2 || k - D != i) t.emplace_back(row + i, col + k, A(i, k));
  }
  map_.resize(n * kDofs, (free + plates_) * kDofs);
  map_.setFromTriplets(t.begin(), t.end());
}

template class PlateConstraints<2>;
template class PlateConstraints<3>;

}  // namespace mc::rigid_cell
