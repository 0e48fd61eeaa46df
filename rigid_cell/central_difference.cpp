#include "rigid_cell/central_difference.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "engine/errors.hpp"

namespace mc::rigid_cell {

namespace {

// The power iteration stops when its Rayleigh quotient changes by less than this in one iteration; on the bar of
// tests/rigid_cell/central_difference.cpp it is then within 0.5 % of the largest eigenvalue (a dense solve's).
constexpr double kPowerTolerance = 1e-7;
constexpr int kPowerIterations = 3000;

}  // namespace

template <int D>
CentralDifference<D>::CentralDifference(const CellAssembly<D>& model, const SparseMatrix& map, const SparseMatrix& mass,
                                        std::vector<bool> is_prescribed, double mass_damping, double stiffness_damping,
                                        FibreBridges<D>* bridges)
    : model_(model),
      bridges_(bridges),
      map_(map),
      mass_(mass),
      is_prescribed_(std::move(is_prescribed)),
      select_(free_rows(is_prescribed_)),
      mass_damping_(mass_damping),
      stiffness_damping_(stiffness_damping) {
  const SparseMatrix mass_free = select_ * mass_ * select_.transpose();
  mass_free_.compute(mass_free);
  if (mass_free_.info() != Eigen::Success || (mass_free_.vectorD().array() <= 0).any())
    throw InputError("explicit dynamics: a free body has no mass (give every phase a density)");
  omega_max_ = std::sqrt(power_iteration());
}

template <int D>
Eigen::VectorXd CentralDifference<D>::intact_forces(const Eigen::VectorXd& u) const {
  const Eigen::VectorXd u_cells = map_ * u;
  Eigen::VectorXd f = model_.internal_forces(u_cells, std::vector<double>(model_.contacts(), 0.0));
  if (bridges_) bridges_->add_stiffest_forces(u_cells, f);
  return map_.transpose() * f;
}

// The largest eigenvalue ω² of K₀ x = ω² M x on the free degrees of freedom: x ← M⁻¹K₀x, normalised, until the
// Rayleigh quotient xᵀK₀x / xᵀMx settles. The start has a part along every mode (no symmetry of the specimen can
// hide the top one).
template <int D>
double CentralDifference<D>::power_iteration() const {
  const Eigen::Index n = select_.rows();
  if (n == 0) return 0;
  Eigen::VectorXd x(n);
  for (Eigen::Index i = 0; i < n; ++i) x[i] = 1 + 0.5 * std::sin(1.7 * static_cast<double>(i) + 0.3);
  const SparseMatrix mass_free = select_ * mass_ * select_.transpose();
  double quotient = 0;
  for (int k = 0; k < kPowerIterations; ++k) {
    const Eigen::VectorXd Kx = select_ * intact_forces(select_.transpose() * x);
    const double next = x.dot(Kx) / x.dot(mass_free * x);
    x = mass_free_.solve(Kx);
    x /= x.norm();
    if (std::abs(next - quotient) <= kPowerTolerance * next) return next;
    quotient = next;
  }
  return quotient;
}

template <int D>
double CentralDifference<D>::critical_timestep() const {
  if (omega_max_ <= 0) return std::numeric_limits<double>::infinity();
  const double xi = 0.5 * (mass_damping_ / omega_max_ + stiffness_damping_ * omega_max_);
  return 2 / omega_max_ * (std::sqrt(1 + xi * xi) - xi);
}

template <int D>
Eigen::VectorXd CentralDifference<D>::step(double dt, KinematicState& s, const KinematicState& held,
                                           const Eigen::VectorXd& f_ext, std::vector<double>& damage,
                                           std::vector<FacetState>& states, std::vector<double>* strain_rates) const {
  const Eigen::Index n = s.u.size();
  // The mid-step velocity, and from it the new displacements; the prescribed ones move as they are told.
  Eigen::VectorXd v_half = s.v + 0.5 * dt * s.a;
  for (Eigen::Index d = 0; d < n; ++d)
    if (is_prescribed_[d]) v_half[d] = (held.u[d] - s.u[d]) / dt;
  s.u += dt * v_half;
  for (Eigen::Index d = 0; d < n; ++d)
    if (is_prescribed_[d]) s.u[d] = held.u[d];

  // Each facet's damage from its new strain (3.12)-(3.19), its limit raised at the mid-step strain rate (8.16).
  const Eigen::VectorXd u_cells = map_ * s.u;
  const Eigen::VectorXd v_cells = strain_rates ? Eigen::VectorXd(map_ * v_half) : Eigen::VectorXd();
  for (std::size_t c = 0; c < model_.contacts(); ++c) {
    double rate = 0;
    if (strain_rates) rate = (*strain_rates)[c] = strain_rate(model_.strain(c, v_cells), model_.params(c));
    damage[c] = rigid_cell::damage(model_.strain(c, u_cells), model_.params(c), model_.length(c), states[c], rate);
    states[c].D_max = damage[c];
  }

  // The fibres across the cracking facets at the new displacements: their forces, no iteration.
  Eigen::VectorXd f_cells = model_.internal_forces(u_cells, damage);
  if (bridges_) {
    bridges_->evaluate(u_cells);
    bridges_->commit(damage);
    bridges_->add_forces(f_cells);
  }
  // M ü = f_ext − K(D) u − C u̇ at t + dt, the damping on the mid-step velocity (the scheme stays explicit).
  Eigen::VectorXd f = map_.transpose() * f_cells;
  if (mass_damping_ != 0) f += mass_damping_ * (mass_ * v_half);
  if (stiffness_damping_ != 0) f += stiffness_damping_ * intact_forces(v_half);
  Eigen::VectorXd a = Eigen::VectorXd::Zero(n);
  for (Eigen::Index d = 0; d < n; ++d)
    if (is_prescribed_[d]) a[d] = held.a[d];
  a += select_.transpose() * mass_free_.solve(select_ * (f_ext - f - mass_ * a));
  s.a = a;
  s.v = v_half + 0.5 * dt * s.a;
  Eigen::VectorXd reactions = f + mass_ * s.a - f_ext;
  for (Eigen::Index d = 0; d < n; ++d) {
    if (is_prescribed_[d]) s.v[d] = held.v[d];
    if (!is_prescribed_[d]) reactions[d] = 0;
  }
  for (Eigen::Index d = 0; d < n; ++d)
    if (!std::isfinite(s.u[d]) || !std::isfinite(s.a[d])) {
      std::ostringstream m;
      m << "explicit dynamics: reduced degree of freedom " << d << " is not finite after a step of " << dt
        << " s (the critical step is " << critical_timestep() << " s)";
      throw InstabilityError(m.str());
    }
  return reactions;
}

template class CentralDifference<2>;
template class CentralDifference<3>;

}  // namespace mc::rigid_cell
