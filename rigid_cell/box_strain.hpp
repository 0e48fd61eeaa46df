// The mean strain of the cells whose nodes lie in a box ([rigid_cell.strain]): the symmetric part of the least-
// squares gradient G of the nodes' displacements, u_i − ū = G (x_i − x̄). G = (Σ u_i dx_iᵀ) M⁻¹ with dx_i = x_i − x̄
// and M = Σ dx_i dx_iᵀ is linear in u: G_ab = Σ_i u_i,a w_i,b with w_i = M⁻¹ dx_i, so each strain component is a
// fixed row over the cells' degrees of freedom, read at any step as row · u.
#pragma once
#include <vector>

#include <Eigen/Core>

#include "engine/dim.hpp"

namespace mc::rigid_cell {

// The rows of ε_xx, ε_yy, ε_xy (2D) or ε_xx, ε_yy, ε_zz, ε_yz, ε_zx, ε_xy (3D) over u (cells × dofs_per_cell, the
// translations first). Throws InputError when the box holds fewer than D + 1 nodes or they lie on one line (plane).
template <int D>
std::vector<Eigen::VectorXd> box_strain_rows(const std::vector<Vec<D>>& nodes, const Vec<D>& lo, const Vec<D>& hi,
                                             int dofs_per_cell);

}  // namespace mc::rigid_cell
