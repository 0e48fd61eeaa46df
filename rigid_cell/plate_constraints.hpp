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

  // `members`: the cells of each plate (a cell in one plate at most); `references`: each plate's reference point,
  // about which it turns. Throws InputError naming a cell given to two plates or a plate without cells.
  PlateConstraints(const std::vector<Vec<D>>& nodes, std::vector<std::vector<int>> members,
                   const std::vector<Vec<D>>& references);
  // No plates: q = u.
  explicit PlateConstraints(int cells);

  const Eigen::SparseMatrix<double>& map() const { return map_; }  // cells·kDofs × reduced()
  int reduced() const { return static_cast<int>(map_.cols()); }
  // The reduced index of component k of a plate.
  int plate_dof(int plate, int k) const { return first_plate_dof_ + plate * kDofs + k; }
  // The reduced index of component k of a cell: its own, or its plate's.
  int cell_dof(int cell, int k) const { return owner_[cell] * kDofs + k; }
  int plates() const { return static_cast<int>(plates_.size()); }
  const std::vector<int>& plate_cells(int p) const { return plates_[p]; }

 private:
  std::vector<std::vector<int>> plates_;
  std::vector<int> owner_;  // per cell: the reduced block it moves with (its own, or its plate's)
  int first_plate_dof_ = 0;
  Eigen::SparseMatrix<double> map_;
};

extern template class PlateConstraints<2>;
extern template class PlateConstraints<3>;

}  // namespace mc::rigid_cell
