// The static solver's secant stiffness on the free degrees of freedom (Květoň (3.10)-(3.11)):
// K_ff = Σ_c (1 − D_c) Mᵀ K_c M, with K_c contact c's undamaged stiffness on its two cells and M the map from the free
// reduced degrees of freedom to the cells' (the plates' u = T q with the prescribed degrees of freedom left out).
// The facets never change, so the pattern of K_ff and each contact's share of each of its entries are found once;
// a new damage refills the values in one pass over the shares, with no triplets, sorting or sparse products. The
// fibres' bridges (fibre_bridges.hpp) join the same two cells as the facet they cross, so they add no entry to the
// pattern but the ones a facet's stiffness happens to have zero: each bridged contact keeps a share per entry of its
// cells' element, by which the bridges' element of each iterate is spread.
#pragma once
#include <Eigen/SparseCore>
#include <cstddef>
#include <vector>

#include "rigid_cell/cell_assembly.hpp"
#include "rigid_cell/fibre_bridges.hpp"

namespace mc::rigid_cell {

using SparseMatrix = Eigen::SparseMatrix<double>;

// free × all: the rows of the identity at the degrees of freedom not prescribed.
SparseMatrix free_rows(const std::vector<bool>& is_prescribed);

template <int D>
class FreeStiffness {
 public:
  // `to_cells` (cells·kDofs × free): u_cells = to_cells · q_free. `bridges` may be null: no fibres.
  FreeStiffness(const CellAssembly<D>& model, const SparseMatrix& to_cells, const FibreBridges<D>* bridges = nullptr);

  // The lower triangle of K_ff for the damage of each contact, with the bridges' secant stiffness of their last
  // evaluation.
  const SparseMatrix& operator()(const std::vector<double>& damage);

 private:
  SparseMatrix K_;
  std::vector<std::size_t> first_;  // contact c's shares are [first_[c], first_[c + 1])
  std::vector<int> entry_;          // a share's index into K_'s values
  std::vector<double> share_;       // its undamaged value
  const FibreBridges<D>* bridges_;
  // Bridged contact j's shares: [bridge_first_[j], bridge_first_[j + 1]), each an entry of K_, the element's entry
  // it takes (row · 2 kDofs + column) and the weight the map gives it.
  std::vector<std::size_t> bridge_first_;
  std::vector<int> bridge_entry_, bridge_local_;
  std::vector<double> bridge_weight_;
};

extern template class FreeStiffness<2>;
extern template class FreeStiffness<3>;

}  // namespace mc::rigid_cell
