// The rigid-cell model's static solver (Květoň §3.2.3-3.2.4): prescribed displacements and forces, damage by
// secant-stiffness iteration, each linear solve by CHOLMOD's supernodal Cholesky (SuiteSparse, through Eigen) on
// the free degrees of freedom. The symbolic analysis is done once (the facets never change); the numeric
// factorisation is reused while no facet's damage changed.
#pragma once
#include <Eigen/CholmodSupport>
#include <memory>
#include <vector>

#include "rigid_cell/cell_assembly.hpp"

namespace mc::rigid_cell {

struct StaticOptions {
  double damage_tolerance = 1e-6;    // largest change of a facet's damage between iterations
  double force_tolerance = 1e-6;     // out-of-balance force over the largest of the internal and external forces
  int max_iterations = 500;
};

struct StaticResult {
  int iterations = 0;      // secant iterations of this step
  int factorisations = 0;  // numeric factorisations among them
  double residual = 0;     // the out-of-balance ratio reached
};

template <int D>
class StaticSolver {
 public:
  // `prescribed`: the degrees of freedom whose displacement is given (index cell × kDofs + component). Throws
  // InputError naming a cell that no chain of contact facets joins to a prescribed degree of freedom.
  StaticSolver(const CellAssembly<D>& model, std::vector<int> prescribed);

  // One load step: u holds the prescribed displacements on entry and the solution on return; f_ext the forces on
  // the free degrees of freedom. `damage` is the facets' damage (the last step's on entry); the facets' states
  // take the converged damage. Throws InstabilityError when the iteration does not converge or the stiffness is
  // singular.
  StaticResult solve(Eigen::VectorXd& u, const Eigen::VectorXd& f_ext, std::vector<double>& damage,
                     std::vector<FacetState>& states, const StaticOptions& options = {});

  // The forces the supports exert on the cells (at the prescribed degrees of freedom; zero elsewhere).
  Eigen::VectorXd reactions(const Eigen::VectorXd& u, const Eigen::VectorXd& f_ext,
                            const std::vector<double>& damage) const;

 private:
  const CellAssembly<D>& model_;
  std::vector<bool> is_prescribed_;
  SparseMatrix select_;  // free × all: picks the free degrees of freedom
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> cholesky_;
  SparseMatrix stiffness_;         // the secant stiffness of the damage below, factorised on the free part
  std::vector<double> factored_;  // that damage
  bool analysed_ = false;

  void check_support(const std::vector<int>& prescribed) const;
  void factorise(const std::vector<double>& damage);
};

extern template class StaticSolver<2>;
extern template class StaticSolver<3>;

}  // namespace mc::rigid_cell
