// Explicit time integration of the rigid-cell model: the central-difference scheme in its velocity form (velocity
// Verlet; Bathe 1996 §9.2.1), the explicit counterpart of Newmark's implicit steps (Květoň ch. 8), so that one
// specimen can be run both ways. Each cell's mass matrix (8.6)-(8.8) is its own block, so the mass matrix is
// block-diagonal per body (a cell, or a plate's cells as one body): it is factorised once, and a step is a strain
// evaluation, the facet law, the forces and one block-diagonal solve, with no stiffness matrix and no iteration.
// The damage of each facet follows its strain directly (the secant law of (3.11)-(3.19) needs no iteration when
// the strain is given). Stable for Δt < (2/ω_max)(√(1 + ξ²) − ξ), ω_max the highest frequency of the undamaged
// specimen (damage only lowers it) and ξ its Rayleigh damping ratio.
#pragma once
#include <Eigen/SparseCholesky>
#include <vector>

#include "rigid_cell/cell_assembly.hpp"
#include "rigid_cell/fibre_bridges.hpp"
#include "rigid_cell/free_stiffness.hpp"

namespace mc::rigid_cell {

// The state of a step, on the reduced degrees of freedom: displacements, velocities, accelerations at t.
struct KinematicState {
  Eigen::VectorXd u, v, a;
};

template <int D>
class CentralDifference {
 public:
  // `map`: cell degrees of freedom = map · reduced ones; `mass`: the reduced mass matrix; `is_prescribed`: the
  // reduced degrees of freedom whose motion is given; `bridges` (may be null) the fibres across the facets, whose
  // forces follow the new displacements each step. Throws InputError when a free body has no mass.
  CentralDifference(const CellAssembly<D>& model, const SparseMatrix& map, const SparseMatrix& mass,
                    std::vector<bool> is_prescribed, double mass_damping, double stiffness_damping,
                    FibreBridges<D>* bridges = nullptr);

  // The highest circular frequency of the undamaged specimen on its free degrees of freedom [rad/s], by power
  // iteration on M⁻¹K₀ (its Rayleigh quotient, a lower bound that converges to it from below). With fibres, K₀
  // holds every crossing at its stiffest as well (FibreBridges::add_stiffest_forces): damage lowers the facets'
  // stiffness and the fibres' is never above that, so the step stays stable as the specimen cracks.
  double highest_frequency() const { return omega_max_; }
  // The largest stable step: (2/ω_max)(√(1 + ξ²) − ξ), ξ = ½(a_M/ω_max + a_K ω_max).
  double critical_timestep() const;

  // One step from t to t + dt. `held` holds the prescribed displacements, velocities and accelerations at t + dt on
  // the prescribed degrees of freedom (what it holds elsewhere is not read); f_ext the loads at t + dt. The damage
  // and the facets' D_max follow the new strain; `strain_rates` (per facet, may be null) is filled from the
  // mid-step velocities when the laws are rate dependent. Returns the reactions at t + dt (the prescribed degrees
  // of freedom's K u + M ü + C u̇ − f; zero elsewhere).
  Eigen::VectorXd step(double dt, KinematicState& s, const KinematicState& held, const Eigen::VectorXd& f_ext,
                       std::vector<double>& damage, std::vector<FacetState>& states,
                       std::vector<double>* strain_rates) const;

 private:
  const CellAssembly<D>& model_;
  FibreBridges<D>* bridges_;
  const SparseMatrix& map_;
  const SparseMatrix& mass_;
  std::vector<bool> is_prescribed_;
  SparseMatrix select_;  // free × all
  Eigen::SimplicialLDLT<SparseMatrix> mass_free_;
  double mass_damping_, stiffness_damping_;
  double omega_max_ = 0;

  Eigen::VectorXd intact_forces(const Eigen::VectorXd& u) const;  // K₀ u, reduced (with the fibres at their stiffest)
  double power_iteration() const;
};

extern template class CentralDifference<2>;
extern template class CentralDifference<3>;

}  // namespace mc::rigid_cell
