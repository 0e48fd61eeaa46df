// The rigid-cell model's static solver (Květoň §3.2.3-3.2.4): prescribed displacements and forces, damage by
// secant-stiffness iteration, each linear solve by CHOLMOD's Cholesky (SuiteSparse, through Eigen) on
// the free degrees of freedom. It works on the reduced degrees of freedom q of the plate constraints (u = T q,
// stiffness Tᵀ K T, forces Tᵀ f); without plates q = u. The symbolic analysis is done once (the facets never
// change); the numeric factorisation is reused while no facet's damage changed.
#pragma once
#include <Eigen/CholmodSupport>
#include <Eigen/IterativeLinearSolvers>
#include <memory>
#include <vector>

#include "rigid_cell/cell_assembly.hpp"
#include "rigid_cell/free_stiffness.hpp"
#include "rigid_cell/plate_constraints.hpp"

namespace mc::rigid_cell {

struct StaticOptions {
  double damage_tolerance = 1e-6;  // largest change of a facet's damage between iterations
  double force_tolerance = 1e-6;   // out-of-balance force over the largest of the internal and external forces
  int max_iterations = 500;
  // Damage never decreases from one iteration to the next: the iteration then always converges (a bounded
  // monotone sequence), to a state past a snap-back of the load path that displacement control cannot follow,
  // with the damage the jump left behind (as the crack running dynamically would).
  bool monotone = false;
  // Rate dependence (8.16)-(8.17): each facet's equivalent strain rate, held through the step's iteration (taken
  // from the velocities the step starts with: a rate that followed the iterate would raise the limit as the damage
  // grows, and the iteration would swing). Null: none.
  const std::vector<double>* strain_rates = nullptr;
};

// Indirect displacement control (CMOD-type): the prescribed displacements are u_p + λ·drive with λ unknown, found
// in each secant iteration so that a gauge reading gᵀu equals its target. The stiffness is linear in the prescribed
// displacements for a given damage, so u = u₀ + λ u₁ (u₀ with λ = 0, u₁ the response to a unit drive) and
// λ = (target − gᵀu₀) / gᵀu₁: two solves on one factor. A load path that snaps back in the driven displacement
// then stays in equilibrium as long as the gauge (a crack's opening) grows.
struct GaugeControl {
  Eigen::VectorXd drive;  // reduced; non-zero on prescribed degrees of freedom only
  Eigen::VectorXd gauge;  // reduced: the reading is gauge · u
  double target = 0;
  double lambda = 0;  // λ of the last solve, where the iteration starts
};

struct StaticResult {
  int iterations = 0;      // secant iterations of this step
  int factorisations = 0;  // numeric factorisations among them
  int cg_iterations = 0;   // conjugate-gradient iterations of the solves done without one
  double residual = 0;     // the out-of-balance ratio reached
  double lambda = 0;       // λ of a gauge control
};

template <int D>
class StaticSolver {
 public:
  // `prescribed`: the reduced degrees of freedom whose displacement is given. Throws InputError naming a cell that
  // no chain of contact facets and plates joins to a prescribed degree of freedom, unless `inertia` says every
  // solve will carry a mass (set_inertia): a free body then moves as its load and inertia say.
  // `bridges` (may be null): the fibres across the facets, evaluated at each iterate and kept with its convergence.
  StaticSolver(const CellAssembly<D>& model, const PlateConstraints<D>& plates, const std::vector<int>& prescribed,
               bool inertia = false, FibreBridges<D>* bridges = nullptr);
  // Without plates: `prescribed` indexes cell × kDofs + component.
  StaticSolver(const CellAssembly<D>& model, const std::vector<int>& prescribed);

  // One load step: u (reduced) holds the prescribed displacements on entry and the solution on return; f_ext the
  // forces on the free reduced degrees of freedom. `damage` is the facets' damage (the last step's on entry); the
  // facets' states take the converged damage. Throws InstabilityError when the iteration does not converge or the
  // stiffness is singular. With `control`, u's prescribed degrees of freedom hold the part without the drive on
  // entry and the part with it on return.
  StaticResult solve(Eigen::VectorXd& u, const Eigen::VectorXd& f_ext, std::vector<double>& damage,
                     std::vector<FacetState>& states, const StaticOptions& options = {},
                     const GaugeControl* control = nullptr);

  // gᵀu₁ of a gauge control at `damage`: how far the gauge moves per unit drive (zero: the drive does not reach it).
  double gauge_sensitivity(const GaugeControl& control, const std::vector<double>& damage);

  // Every cell's displacements and rotations for the reduced u.
  Eigen::VectorXd cell_displacements(const Eigen::VectorXd& u) const { return map_ * u; }
  // The forces the supports exert (at the prescribed reduced degrees of freedom; zero elsewhere): on a plate, its
  // resultant force and moment about its reference point.
  Eigen::VectorXd reactions(const Eigen::VectorXd& u, const Eigen::VectorXd& f_ext,
                            const std::vector<double>& damage) const;

  // Implicit dynamics (Newmark (8.4)): from now on every solve is of (K(D) + c_M M + c_K K₀) u = f, with M the
  // reduced mass matrix and K₀ the undamaged stiffness (the effective stiffness of a step with Rayleigh damping
  // C = a_M M + a_K K₀). The caller puts the step's inertial and damping loads into f. Drops any factor.
  void set_inertia(const SparseMatrix& mass, double c_M, double c_K);
  // K₀ u: the undamaged stiffness's forces, over every reduced degree of freedom.
  Eigen::VectorXd intact_forces(const Eigen::VectorXd& u) const;

  // The state whose stiffness is factorised (empty before the first solve): the damage, then the bridges' secants;
  // and a factorisation at a given one: a checkpoint keeps it, since the solves that use it as a preconditioner
  // depend on it in their last bits.
  const std::vector<double>& factored_state() const { return factored_; }
  void factorise_at(const std::vector<double>& state);

 private:
  // CHOLMOD's factor, and the number of values its analysis gave it room for (Eigen keeps the factor to itself): a
  // supernodal factor holds the zeros inside its supernodes too (xsize, CHOLMOD's int), more than Common->lnz.
  class Cholesky : public Eigen::CholmodDecomposition<SparseMatrix, Eigen::Lower> {
   public:
    double values() {
      const cholmod_factor* f = m_cholmodFactor;
      return f && f->is_super ? static_cast<double>(f->xsize) : cholmod().lnz;
    }
  };
  // The factor of an earlier stiffness as a preconditioner (Eigen's preconditioner interface).
  class FactorPreconditioner {
   public:
    void use(const Cholesky* factor) { factor_ = factor; }
    template <typename M>
    FactorPreconditioner& analyzePattern(const M&) {
      return *this;
    }
    template <typename M>
    FactorPreconditioner& factorize(const M&) {
      return *this;
    }
    template <typename M>
    FactorPreconditioner& compute(const M&) {
      return *this;
    }
    Eigen::VectorXd solve(const Eigen::VectorXd& b) const { return factor_->solve(b); }
    Eigen::ComputationInfo info() const { return Eigen::Success; }

   private:
    const Cholesky* factor_ = nullptr;
  };

  const CellAssembly<D>& model_;
  FibreBridges<D>* bridges_;
  SparseMatrix map_;  // u_cells = map_ · u
  // Newmark's constant part c_M M + c_K K₀ (set_inertia): c_M = 0 and c_K = 0 for a static solve.
  SparseMatrix mass_;        // reduced
  SparseMatrix shift_free_;  // its free × free lower triangle
  SparseMatrix shifted_;     // K_ff(D) plus it
  double c_M_ = 0, c_K_ = 0;
  std::vector<bool> is_prescribed_;
  SparseMatrix select_;  // free × all: picks the free degrees of freedom
  FreeStiffness<D> free_stiffness_;
  // CHOLMOD chooses simplicial or supernodal from the fill of the factor; both run on this thread alone (one
  // BLAS thread, no OpenMP level), so the bits do not depend on the thread count. On a 3D disc of 786 DOFs the
  // supernodal one takes 1.3 s for 120 steps where simplicial took 4.0 s.
  Cholesky cholesky_;
  std::vector<double> factored_;  // the state (stiffness_state) of the factorised stiffness; empty: no usable factor
  bool analysed_ = false;
  Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower, FactorPreconditioner> cg_;

  static void refuse_unaffordable_factor(double values, Eigen::Index dofs);
  static void check_support(const CellAssembly<D>& model, const SparseMatrix& map, const std::vector<int>& prescribed,
                            bool inertia);
  void factorise(const SparseMatrix& Kff, const std::vector<double>& damage);
  [[noreturn]] void discard_and_throw(const std::string& message);
  // The lower triangle of the free stiffness for a damage, with the constant shift of a dynamic solve.
  const SparseMatrix& stiffness(const std::vector<double>& damage);
  // What the stiffness is built from: the damage, then the bridges' secants of their last evaluation.
  std::vector<double> stiffness_state(const std::vector<double>& damage) const;
  // (K(D) + shift) u over every reduced degree of freedom, the bridges' secants included: linear in u.
  Eigen::VectorXd secant_forces(const Eigen::VectorXd& u, const std::vector<double>& damage) const;
  // The internal forces at u: the facets' secant ones, the bridges' of their last evaluation (at u), and the shift.
  Eigen::VectorXd forces(const Eigen::VectorXd& u, const std::vector<double>& damage) const;
  Eigen::VectorXd free_solution(const std::vector<double>& damage, const Eigen::VectorXd& rhs,
                                const Eigen::VectorXd& guess, StaticResult& r);
  // The reduced displacements for prescribed ones `prescribed` (zero on the free degrees of freedom) and forces f.
  Eigen::VectorXd equilibrium(const std::vector<double>& damage, const Eigen::VectorXd& prescribed,
                              const Eigen::VectorXd& f, const Eigen::VectorXd& guess, StaticResult& r);
};

extern template class StaticSolver<2>;
extern template class StaticSolver<3>;

}  // namespace mc::rigid_cell
