#include "rigid_cell/static_solver.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <queue>
#include <sstream>
#include <string>

#include "engine/errors.hpp"
#include "engine/machine_memory.hpp"
#include "rigid_cell/factor_size.hpp"

extern "C" void openblas_set_num_threads(int) __attribute__((weak));

namespace mc::rigid_cell {

namespace {

constexpr double kSteadyRatio = 0.5;              // successive damage changes shrinking slower: extrapolate
constexpr double kMaxBoost = 20;                  // at most 20 times the last change
constexpr double kMaxExtrapolatedDamage = 0.999;  // an extrapolation leaves every facet some stiffness
// Where a crack runs within a step there is no equilibrium near the last one: the changes then wander between 1e-4
// and 1e-2 for hundreds of iterations (a 3D disc after its peak) instead of shrinking. With no new smallest change
// in this many iterations the step is given up at once, to be halved by the caller.
constexpr int kStallIterations = 50;
// A secant iteration changes the stiffness of a few facets: conjugate gradients preconditioned with the factor of
// an earlier stiffness then converge in a few iterations (3 on average), each a pair of triangular solves where a
// factorisation costs 0.87 s (a 3D mortar disc of 27 228 DOFs: 110 steps, 369 secant iterations in 35 s instead of
// 215 s). Past this many the stiffness has drifted from the factor's: it is factorised anew.
constexpr int kMaxCgIterations = 50;
constexpr double kCgTolerance = 1e-10;  // relative residual, far below the secant iteration's tolerances

// The largest magnitude of v's entries; 0 for none (a specimen whose every degree of freedom is prescribed).
double largest(const Eigen::VectorXd& v) { return v.size() == 0 ? 0.0 : v.cwiseAbs().maxCoeff(); }

std::vector<bool> mask(int size, const std::vector<int>& prescribed) {
  std::vector<bool> is_prescribed(size, false);
  for (int d : prescribed) is_prescribed.at(d) = true;
  return is_prescribed;
}

}  // namespace

template <int D>
StaticSolver<D>::StaticSolver(const CellAssembly<D>& model, const PlateConstraints<D>& plates,
                              const std::vector<int>& prescribed, bool inertia, FibreBridges<D>* bridges)
    : model_(model),
      bridges_(bridges),
      // Checked first: an unsupported specimen is refused before its stiffness pattern is built.
      map_((check_support(model, plates.map(), prescribed, inertia), plates.map())),
      is_prescribed_(mask(plates.reduced(), prescribed)),
      select_(free_rows(is_prescribed_)),
      free_stiffness_(model, map_ * select_.transpose(), bridges) {
  cholesky_.setMode(Eigen::CholmodAuto);
  cg_.setMaxIterations(kMaxCgIterations);
  cg_.setTolerance(kCgTolerance);
  cholesky_.cholmod().print = 0;  // a singular stiffness is reported by factorise's InstabilityError, not on stdout
  // OpenBLAS (Debian's default BLAS) threads its dense kernels on every core; other BLAS leave the symbol unset.
  if (openblas_set_num_threads) openblas_set_num_threads(1);
  // The pattern is the same for every damage: analysed once, here, so that a factor this machine cannot hold is
  // refused before the run rather than ending it in CHOLMOD (a 3D disc of 5·10⁵ cells died of SIGSEGV there).
  if (select_.rows() > 0) {
    cholesky_.analyzePattern(free_stiffness_(std::vector<double>(model.contacts(), 0.0)));
    analysed_ = true;
    refuse_unaffordable_factor(cholesky_.values(), select_.rows());
  }
}

// CHOLMOD's analysis sizes the factor: 8 bytes a value, beside what the process holds already (the tessellation, the
// stiffness), and at most kMostFactorValues.
template <int D>
void StaticSolver<D>::refuse_unaffordable_factor(double values, Eigen::Index dofs) {
  const double have = physical_memory(), held = resident_memory(), need = 8 * values;
  if (held + need <= have && values <= kMostFactorValues) return;
  std::ostringstream m;
  m.precision(3);
  m << "rigid cells: the stiffness's factor for " << dofs << " free degrees of freedom would hold " << values
    << " values, " << need / (1 << 30) << " GiB beside the " << held / (1 << 30)
    << " GiB the run holds (CHOLMOD's int indices take at most " << kMostFactorValues << "); this machine has "
    << have / (1 << 30) << " GiB: use a larger l_min or a smaller specimen";
  throw InputError(m.str());
}

template <int D>
StaticSolver<D>::StaticSolver(const CellAssembly<D>& model, const std::vector<int>& prescribed)
    : StaticSolver(model, PlateConstraints<D>(model.cells()), prescribed) {}

// Every cell must be reachable from a held one through contact facets or a plate, or the stiffness is singular.
// Cells that share a reduced degree of freedom (the cells of one plate) hold each other.
template <int D>
void StaticSolver<D>::check_support(const CellAssembly<D>& model, const SparseMatrix& map,
                                    const std::vector<int>& prescribed, bool inertia) {
  if (inertia) return;
  const int n = model.cells();
  std::vector<std::vector<int>> neighbours(n), cells_of_dof(map.cols());
  for (std::size_t c = 0; c < model.contacts(); ++c) {
    const auto [a, b] = model.cells_of(c);
    neighbours[a].push_back(b);
    neighbours[b].push_back(a);
  }
  for (int k = 0; k < map.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(map, k); it; ++it) {
      auto& cells = cells_of_dof[it.col()];
      const int cell = static_cast<int>(it.row()) / CellAssembly<D>::kDofs;
      if (cells.empty() || cells.back() != cell) cells.push_back(cell);
    }
  for (const auto& cells : cells_of_dof)
    for (std::size_t i = 1; i < cells.size(); ++i) {
      neighbours[cells[0]].push_back(cells[i]);
      neighbours[cells[i]].push_back(cells[0]);
    }
  std::vector<bool> held(n, false);
  std::queue<int> todo;
  for (int d : prescribed)
    for (int cell : cells_of_dof.at(d)) {
      if (!held[cell]) todo.push(cell);
      held[cell] = true;
    }
  while (!todo.empty()) {
    const int c = todo.front();
    todo.pop();
    for (int k : neighbours[c])
      if (!held[k]) {
        held[k] = true;
        todo.push(k);
      }
  }
  const auto loose = std::find(held.begin(), held.end(), false);
  if (loose != held.end()) {
    std::ostringstream m;
    m << "rigid cells: cell " << (loose - held.begin())
      << " is not held: no chain of facets joins it to a support (an unsupported specimen)";
    throw InputError(m.str());
  }
}

template <int D>
void StaticSolver<D>::set_inertia(const SparseMatrix& mass, double c_M, double c_K) {
  mass_ = mass, c_M_ = c_M, c_K_ = c_K;
  const std::vector<double> intact(model_.contacts(), 0.0);
  const SparseMatrix mass_free = (select_ * mass_ * select_.transpose()).template triangularView<Eigen::Lower>();
  shift_free_ = c_M * mass_free + c_K * free_stiffness_(intact);
  factored_.clear();
  analysed_ = false;  // the pattern may have grown
}

template <int D>
const SparseMatrix& StaticSolver<D>::stiffness(const std::vector<double>& damage) {
  const SparseMatrix& K = free_stiffness_(damage);
  if (shift_free_.size() == 0) return K;
  shifted_ = K + shift_free_;  // the same pattern every time: CHOLMOD's one analysis holds
  return shifted_;
}

template <int D>
std::vector<double> StaticSolver<D>::stiffness_state(const std::vector<double>& damage) const {
  if (!bridges_) return damage;
  std::vector<double> state = damage;
  const std::vector<double> key = bridges_->stiffness_key();
  state.insert(state.end(), key.begin(), key.end());
  return state;
}

template <int D>
Eigen::VectorXd StaticSolver<D>::secant_forces(const Eigen::VectorXd& u, const std::vector<double>& damage) const {
  const Eigen::VectorXd u_cells = map_ * u;
  Eigen::VectorXd f_cells = model_.internal_forces(u_cells, damage);
  if (bridges_) bridges_->add_secant_forces(u_cells, f_cells);
  Eigen::VectorXd f = map_.transpose() * f_cells;
  if (c_M_ != 0) f += c_M_ * (mass_ * u);
  if (c_K_ != 0) f += c_K_ * intact_forces(u);
  return f;
}

template <int D>
Eigen::VectorXd StaticSolver<D>::forces(const Eigen::VectorXd& u, const std::vector<double>& damage) const {
  Eigen::VectorXd f_cells = model_.internal_forces(map_ * u, damage);
  if (bridges_) bridges_->add_forces(f_cells);
  Eigen::VectorXd f = map_.transpose() * f_cells;
  if (c_M_ != 0) f += c_M_ * (mass_ * u);
  if (c_K_ != 0) f += c_K_ * intact_forces(u);
  return f;
}

template <int D>
void StaticSolver<D>::factorise_at(const std::vector<double>& state) {
  const std::size_t n = model_.contacts();
  const std::vector<double> damage(state.begin(), state.begin() + static_cast<std::ptrdiff_t>(std::min(n, state.size())));
  if (!bridges_) return factorise(stiffness(damage), damage);
  const std::vector<double> now = bridges_->stiffness_key();
  bridges_->set_stiffness_key(state, n);
  factorise(stiffness(damage), damage);
  bridges_->set_stiffness_key(now, 0);
}

template <int D>
void StaticSolver<D>::discard_and_throw(const std::string& message) {
  if (bridges_) bridges_->discard();
  throw InstabilityError(message);
}

template <int D>
Eigen::VectorXd StaticSolver<D>::intact_forces(const Eigen::VectorXd& u) const {
  return map_.transpose() * model_.internal_forces(map_ * u, std::vector<double>(model_.contacts(), 0.0));
}

template <int D>
void StaticSolver<D>::factorise(const SparseMatrix& Kff, const std::vector<double>& damage) {
  // CHOLMOD's supernodal factorisation opens OpenMP regions with a thread count fixed when it was compiled (4 in
  // Debian's); on small supernodes their wake-ups cost more than they save (a 786-DOF disc: 2.9 s of system time
  // in 5.1 s). With no active level allowed they run on this thread alone.
  const int levels = omp_get_max_active_levels();
  omp_set_max_active_levels(0);
  if (!analysed_) {
    cholesky_.analyzePattern(Kff);
    analysed_ = true;
  }
  cholesky_.factorize(Kff);
  omp_set_max_active_levels(levels);
  factored_.clear();  // no usable factor until this one succeeds
  if (cholesky_.info() != Eigen::Success)
    discard_and_throw(
        "rigid cells: the stiffness is singular (a cell or group of cells moves freely, or "
        "damage has cut the specimen through)");
  factored_ = stiffness_state(damage);
  cg_.preconditioner().use(&cholesky_);
}

// The free displacements for the stiffness of `damage`: by the factor when it is that stiffness's, else by
// conjugate gradients preconditioned with it, else by a new factorisation.
template <int D>
Eigen::VectorXd StaticSolver<D>::free_solution(const std::vector<double>& damage, const Eigen::VectorXd& rhs,
                                               const Eigen::VectorXd& guess, StaticResult& r) {
  if (rhs.size() == 0) return rhs;  // every degree of freedom prescribed: nothing to solve
  if (!factored_.empty() && stiffness_state(damage) == factored_) return cholesky_.solve(rhs);
  const SparseMatrix& Kff = stiffness(damage);
  if (!factored_.empty()) {
    cg_.compute(Kff);
    const Eigen::VectorXd x = cg_.solveWithGuess(rhs, guess);
    if (cg_.info() == Eigen::Success) {
      r.cg_iterations += static_cast<int>(cg_.iterations());
      return x;
    }
  }
  factorise(Kff, damage);
  ++r.factorisations;
  return cholesky_.solve(rhs);
}

template <int D>
Eigen::VectorXd StaticSolver<D>::equilibrium(const std::vector<double>& damage, const Eigen::VectorXd& prescribed,
                                             const Eigen::VectorXd& f, const Eigen::VectorXd& guess, StaticResult& r) {
  // f_free − K_fp u_p, the prescribed displacements' forces on the free degrees of freedom for this damage.
  const Eigen::VectorXd rhs = select_ * (f - secant_forces(prescribed, damage));
  return prescribed + select_.transpose() * free_solution(damage, rhs, select_ * guess, r);
}

template <int D>
double StaticSolver<D>::gauge_sensitivity(const GaugeControl& control, const std::vector<double>& damage) {
  StaticResult r;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(control.drive.size());
  return control.gauge.dot(equilibrium(damage, control.drive, zero, zero, r));
}

template <int D>
StaticResult StaticSolver<D>::solve(Eigen::VectorXd& u, const Eigen::VectorXd& f_ext, std::vector<double>& damage,
                                    std::vector<FacetState>& states, const StaticOptions& options,
                                    const GaugeControl* control) {
  StaticResult r;
  double change = 0, previous_change = 0, smallest_change = 1, bridge_change = 0;
  int stalled = 0;
  std::vector<double> next(model_.contacts());
  Eigen::VectorXd prescribed = u;
  for (std::size_t d = 0; d < is_prescribed_.size(); ++d)
    if (!is_prescribed_[d]) prescribed[d] = 0;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(u.size());
  Eigen::VectorXd u1 = zero;  // the response to a unit drive
  if (control) r.lambda = control->lambda;
  for (r.iterations = 1; r.iterations <= options.max_iterations; ++r.iterations) {
    if (!control) {
      u = equilibrium(damage, prescribed, f_ext, u, r);
    } else {
      u1 = equilibrium(damage, control->drive, zero, u1, r);
      const Eigen::VectorXd u0 = equilibrium(damage, prescribed, f_ext, u - r.lambda * u1, r);
      const double sensitivity = control->gauge.dot(u1);
      if (!(std::abs(sensitivity) > 0))
        discard_and_throw("rigid cells: the controlling gauge no longer moves with the plate that drives it");
      r.lambda = (control->target - control->gauge.dot(u0)) / sensitivity;
      u = u0 + r.lambda * u1;
    }
    const Eigen::VectorXd u_cells = map_ * u;
    change = 0;
    for (std::size_t c = 0; c < model_.contacts(); ++c) {
      const double rate = options.strain_rates ? (*options.strain_rates)[c] : 0.0;
      next[c] = rigid_cell::damage(model_.strain(c, u_cells), model_.params(c), model_.length(c), states[c], rate);
      if (options.monotone) next[c] = std::max(next[c], damage[c]);
      change = std::max(change, std::abs(next[c] - damage[c]));
    }
    // Near a peak the secant iteration converges linearly, its changes shrinking by a steady ratio ρ close to 1
    // (0.95 measured on a Brazilian disc: 180 iterations from 1e-2 to 1e-6). Aitken's Δ² process jumps to the
    // limit of such a sequence, damage + Δ/(1 − ρ); the fixed point, and so the converged state, is unchanged.
    // (Under a gauge control λ couples every facet to every other: the extrapolation there grows the changes
    // instead, 58 snap-throughs on the notched beam of scenes/ where plain iteration needs none.)
    const double ratio = previous_change > 0 ? change / previous_change : 0;
    const double boost = !control && ratio > kSteadyRatio && ratio < 1 ? std::min(1 / (1 - ratio), kMaxBoost) : 1.0;
    for (std::size_t c = 0; c < model_.contacts(); ++c)
      damage[c] = std::clamp(damage[c] + boost * (next[c] - damage[c]), states[c].D_max,
                             std::max(next[c], kMaxExtrapolatedDamage));
    previous_change = change;
    // The fibres across the cracking facets, at this iterate and its damage: their secants go into the next solve.
    bridge_change = bridges_ ? bridges_->evaluate(u_cells, options.monotone && r.iterations > 1) : 0.0;
    const double moved = std::max(change, bridge_change);
    stalled = moved < smallest_change ? 0 : stalled + 1;
    smallest_change = std::min(smallest_change, moved);
    if (stalled == kStallIterations && !options.monotone) break;
    if (moved > options.damage_tolerance) continue;
    const Eigen::VectorXd f_int = forces(u, damage);
    const double scale = std::max(
        {largest(select_ * f_int), largest(f_int), largest(f_ext), 1e-300});
    r.residual = largest(select_ * (f_ext - f_int)) / scale;
    if (r.residual <= options.force_tolerance) {
      for (std::size_t c = 0; c < states.size(); ++c) states[c].D_max = damage[c];
      if (bridges_) bridges_->commit(damage);
      return r;
    }
    // No facet changed, but the forces are out of balance: the conjugate gradients' error, relative to their
    // right-hand side, is too large for a specimen nearly cut through (its forces are small against its
    // stiffness), and would repeat in every iteration. The next solves use the factor of this damage itself.
    if (moved == 0 && factored_ != stiffness_state(damage)) {
      factorise(stiffness(damage), damage);
      ++r.factorisations;
    }
  }
  std::ostringstream m;
  m << "rigid cells: the secant iteration did not converge in " << std::min(r.iterations, options.max_iterations)
    << " iterations ("
    << (stalled == kStallIterations ? "no smaller change in the last " + std::to_string(kStallIterations) + "; " : "")
    << "largest change of a facet's damage in the last one " << change << ", tolerance " << options.damage_tolerance
    << (bridges_ ? "; of a fibre's force over the largest " + std::to_string(bridge_change) : std::string())
    << "; out-of-balance ratio " << r.residual << ", tolerance " << options.force_tolerance << ")";
  discard_and_throw(m.str());
  return r;
}

template <int D>
Eigen::VectorXd StaticSolver<D>::reactions(const Eigen::VectorXd& u, const Eigen::VectorXd& f_ext,
                                           const std::vector<double>& damage) const {
  Eigen::VectorXd r = forces(u, damage) - f_ext;
  for (std::size_t d = 0; d < is_prescribed_.size(); ++d)
    if (!is_prescribed_[d]) r[d] = 0;
  return r;
}

template class StaticSolver<2>;
template class StaticSolver<3>;

}  // namespace mc::rigid_cell
