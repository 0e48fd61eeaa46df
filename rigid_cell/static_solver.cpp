#include "rigid_cell/static_solver.hpp"

#include <algorithm>
#include <cmath>
#include <queue>
#include <sstream>

#include "engine/errors.hpp"

namespace mc::rigid_cell {

template <int D>
StaticSolver<D>::StaticSolver(const CellAssembly<D>& model, std::vector<int> prescribed)
    : model_(model), is_prescribed_(model.dofs(), false) {
  for (int d : prescribed) is_prescribed_.at(d) = true;
  check_support(prescribed);
  std::vector<Eigen::Triplet<double>> pick;
  for (int d = 0, row = 0; d < model.dofs(); ++d)
    if (!is_prescribed_[d]) pick.emplace_back(row++, d, 1.0);
  select_.resize(static_cast<Eigen::Index>(pick.size()), model.dofs());
  select_.setFromTriplets(pick.begin(), pick.end());
}

// Every cell must be reachable from a held one through contact facets, or the stiffness is singular.
template <int D>
void StaticSolver<D>::check_support(const std::vector<int>& prescribed) const {
  const int n = model_.cells();
  std::vector<std::vector<int>> neighbours(n);
  for (std::size_t c = 0; c < model_.contacts(); ++c) {
    const auto [a, b] = model_.cells_of(c);
    neighbours[a].push_back(b);
    neighbours[b].push_back(a);
  }
  std::vector<bool> held(n, false);
  std::queue<int> todo;
  for (int d : prescribed) {
    const int cell = d / CellAssembly<D>::kDofs;
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
void StaticSolver<D>::factorise(const std::vector<double>& damage) {
  stiffness_ = model_.stiffness(damage);
  const SparseMatrix Kff = select_ * stiffness_ * select_.transpose();
  if (!analysed_) {
    cholesky_.analyzePattern(Kff);
    analysed_ = true;
  }
  cholesky_.factorize(Kff);
  if (cholesky_.info() != Eigen::Success)
    throw InstabilityError("rigid cells: the stiffness is singular (a cell or group of cells moves freely, or "
                           "damage has cut the specimen through)");
  factored_ = damage;
}

template <int D>
StaticResult StaticSolver<D>::solve(Eigen::VectorXd& u, const Eigen::VectorXd& f_ext, std::vector<double>& damage,
                                    std::vector<FacetState>& states, const StaticOptions& options) {
  StaticResult r;
  Eigen::VectorXd prescribed = u;
  for (int d = 0; d < model_.dofs(); ++d)
    if (!is_prescribed_[d]) prescribed[d] = 0;
  for (r.iterations = 1; r.iterations <= options.max_iterations; ++r.iterations) {
    if (!analysed_ || damage != factored_) {
      factorise(damage);
      ++r.factorisations;
    }
    const Eigen::VectorXd rhs = select_ * (f_ext - stiffness_ * prescribed);
    u = prescribed + select_.transpose() * cholesky_.solve(rhs);
    double change = 0;
    for (std::size_t c = 0; c < model_.contacts(); ++c) {
      const double d = rigid_cell::damage(model_.strain(c, u), model_.params(c), model_.length(c), states[c]);
      change = std::max(change, std::abs(d - damage[c]));
      damage[c] = d;
    }
    if (change > options.damage_tolerance) continue;
    const Eigen::VectorXd f_int = model_.internal_forces(u, damage);
    const double scale = std::max({(select_ * f_int).cwiseAbs().maxCoeff(), f_int.cwiseAbs().maxCoeff(),
                                   f_ext.cwiseAbs().maxCoeff(), 1e-300});
    r.residual = (select_ * (f_ext - f_int)).cwiseAbs().maxCoeff() / scale;
    if (r.residual <= options.force_tolerance) {
      for (std::size_t c = 0; c < states.size(); ++c) states[c].D_max = damage[c];
      return r;
    }
  }
  std::ostringstream m;
  m << "rigid cells: the secant iteration did not converge in " << options.max_iterations
    << " iterations (out-of-balance ratio " << r.residual << ")";
  throw InstabilityError(m.str());
}

template <int D>
Eigen::VectorXd StaticSolver<D>::reactions(const Eigen::VectorXd& u, const Eigen::VectorXd& f_ext,
                                           const std::vector<double>& damage) const {
  Eigen::VectorXd r = model_.internal_forces(u, damage) - f_ext;
  for (int d = 0; d < model_.dofs(); ++d)
    if (!is_prescribed_[d]) r[d] = 0;
  return r;
}

template class StaticSolver<2>;
template class StaticSolver<3>;

}  // namespace mc::rigid_cell
