// Rigid plates (Květoň §9.2-9.3): the loading and support plates are groups of cells tied into one rigid body,
// free to rotate or not. Their cells' degrees of freedom are replaced by the plate's: a cell at r from the plate's
// reference point moves by u = U + Θ × r and turns by Θ (small rotations, as the facet kinematics (3.1)). The
// map u = T q takes the reduced degrees of freedom q (the free cells', then the plates') to every cell's.
#pragma once
#include <Eigen/SparseCore>
#include <vector>

#include "engine/dim.hpp"

namespace mc::rigid_cell {

template <int D>
class PlateConstraints {
 public:
  static constexpr int kDofs = D + Dim<D>::rot;  // per cell and per plate: translations, then rotations

  // `plate_of`: each cell's plate, or −1 for a free cell; `references`: each plate's reference point, about which
  // it turns (one per plate; a plate without cells leaves its free degrees of freedom without stiffness).
  PlateConstraints(const std::vector<Vec<D>>& nodes, const std::vector<int>& plate_of,
                   const std::vector<Vec<D>>& references);
  // No plates: q = u.
  explicit PlateConstraints(int cells);

  const Eigen::SparseMatrix<double>& map() const { return map_; }  // cells·kDofs × reduced()
  int reduced() const { return static_cast<int>(map_.cols()); }
  int plates() const { return plates_; }
  // The reduced index of component k of a plate.
  int plate_dof(int plate, int k) const { return first_plate_dof_ + plate * kDofs + k; }
  const Vec<D>& reference(int plate) const { return references_[plate]; }

 private:
  int plates_ = 0, first_plate_dof_ = 0;
  std::vector<Vec<D>> references_;
  Eigen::SparseMatrix<double> map_;
};

extern template class PlateConstraints<2>;
extern template class PlateConstraints<3>;

}  // namespace mc::rigid_cell
