// The rigid-cell system in time (Květoň ch. 8-9): the mass matrix and the scheme (Newmark's implicit steps or
// central differences), the applied loads in time (plate loads, the stress wave), one step of each scheme, and the
// plates' held motion.
#include <sstream>

#include "engine/errors.hpp"
#include "engine/ramp.hpp"
#include "rigid_cell/point_motion.hpp"
#include "rigid_cell/rigid_cell_system.hpp"

namespace mc::rigid_cell {

// Květoň (8.6)-(8.8): each cell's mass matrix about its node, assembled block-diagonally and carried to the
// reduced degrees of freedom (a plate's cells into one rigid body, Tᵀ M T); for Newmark, the solver's effective
// stiffness of (8.4) with Rayleigh damping, K + (a₀ + a_M γ/(βΔt)) M + a_K γ/(βΔt) K₀.
template <int D>
void RigidCellSystem<D>::build_dynamics() {
  if (!setup_.dynamics) return;
  const DynamicsSpec& d = *setup_.dynamics;
  std::vector<Eigen::Triplet<double>> t;
  for (int c = 0; c < cells(); ++c) {
    const double density = setup_.phase_density.at(phase_[c]);
    const auto M = tessellation_.cells[c].mass.mass_matrix(density);
    for (int i = 0; i < kDofs; ++i)
      for (int j = 0; j < kDofs; ++j) t.emplace_back(c * kDofs + i, c * kDofs + j, M(i, j));
  }
  SparseMatrix cells_mass(cells() * kDofs, cells() * kDofs);
  cells_mass.setFromTriplets(t.begin(), t.end());
  const SparseMatrix& T = plates_->map();
  mass_ = T.transpose() * cells_mass * T;
  if (d.scheme == DynamicsSpec::Scheme::CentralDifference) return build_explicit();
  newmark_.emplace(d.beta, d.gamma, setup_.load_step);
  const double c = newmark_->damping_coefficient();
  solver_->set_inertia(mass_, newmark_->a0() + d.mass_damping * c, d.stiffness_damping * c);
}

// Central differences: the critical step from the undamaged specimen's highest frequency; the step is the
// declared fraction of it, or the declared step if it is below it.
template <int D>
void RigidCellSystem<D>::build_explicit() {
  const DynamicsSpec& d = *setup_.dynamics;
  if (setup_.opening_control)
    throw InputError(
        "an opening control solves for the drive that keeps a gauge on target, which only the implicit (Newmark) "
        "scheme does: leave out [rigid_cell.opening_control] or use scheme = \"newmark\"");
  std::vector<bool> is_prescribed(plates_->reduced(), false);
  for (int dof : prescribed_) is_prescribed[dof] = true;
  explicit_ = std::make_unique<CentralDifference<D>>(*model_, plates_->map(), mass_, std::move(is_prescribed),
                                                     d.mass_damping, d.stiffness_damping, bridges_.get());
  const double critical = explicit_->critical_timestep();
  if (setup_.load_step == 0) {
    setup_.load_step = setup_.timestep_safety * critical;
  } else if (setup_.load_step > critical) {
    std::ostringstream m;
    m << "the explicit time step " << setup_.load_step << " s exceeds this specimen's critical step " << critical
      << " s (2/omega_max, omega_max = " << explicit_->highest_frequency()
      << " rad/s, with its damping): give a smaller step, or a safety factor instead of a fixed step";
    throw InputError(m.str());
  }
}

// Květoň (9.5): each surface facet in the wave's box takes −A n of a unit pressure at its centroid, carried to its
// cell's degrees of freedom (a force at c does the work of (A_x^c)ᵀ F on them, (3.2)) and through the plates.
template <int D>
void RigidCellSystem<D>::build_stress_wave() {
  if (!setup_.stress_wave) return;
  const StressWave<D>& w = *setup_.stress_wave;
  if (!setup_.dynamics)
    throw InputError("a stress wave (Kveton (9.5)) loads a specimen in time: it needs [rigid_cell.dynamics]");
  Eigen::VectorXd on_cells = Eigen::VectorXd::Zero(cells() * kDofs);
  int loaded = 0;
  for (std::size_t f = tessellation_.contacts; f < tessellation_.facets.size(); ++f) {
    const Facet<D>& facet = tessellation_.facets[f];
    if ((facet.centroid.array() < w.lo.array()).any() || (facet.centroid.array() > w.hi.array()).any()) continue;
    const Vec<D> force = -facet.area * facet.normal;
    on_cells.segment<kDofs>(facet.a * kDofs) +=
        point_motion<D>(tessellation_.cells[facet.a].node, facet.centroid).transpose() * force;
    ++loaded;
  }
  if (loaded == 0) {
    std::ostringstream m;
    m << "the stress wave's box [" << w.lo.transpose() << "] .. [" << w.hi.transpose()
      << "] m holds the centroid of no surface facet: it must take in a face of the specimen";
    throw InputError(m.str());
  }
  wave_load_ = plates_->map().transpose() * on_cells;
}

template <int D>
Eigen::VectorXd RigidCellSystem<D>::loads_at(double t) const {
  if (t <= 0) return Eigen::VectorXd::Zero(plate_loads_.size());
  Eigen::VectorXd f = plate_loads_;
  if (setup_.stress_wave) f += setup_.stress_wave->at(t) * wave_load_;
  return f;
}

// One Newmark step (8.4): the plates' held degrees of freedom at t + Δt, the inertial and damping loads of the last
// state, the secant iteration on the effective stiffness, then (8.2)-(8.3). A step whose iteration does not
// converge even with monotone damage stops the run (exit 4).
template <int D>
void RigidCellSystem<D>::dynamic_step() {
  const NewmarkScheme& s = *newmark_;
  const DynamicsSpec& d = *setup_.dynamics;
  const Eigen::VectorXd u = u_;
  prescribe(time_ + setup_.load_step);
  const SparseMatrix& M = mass_;
  const Eigen::VectorXd damped = s.damping_history(u, v_, a_);
  Eigen::VectorXd f = f_ext_ + M * s.inertial_history(u, v_, a_);
  if (d.mass_damping != 0) f += d.mass_damping * (M * damped);
  if (d.stiffness_damping != 0) f += d.stiffness_damping * solver_->intact_forces(damped);
  if (control_) control_->lambda = control_->drive.dot(u);
  StaticOptions options = setup_.options;
  if (rate_dependent_) {
    // (8.16)-(8.17): each facet's strain rate from the velocities at the step's start (the strain is linear in
    // the cells' motion, so the strain of the velocities is the strain rate).
    const Eigen::VectorXd v_cells = solver_->cell_displacements(v_);
    strain_rates_.resize(model_->contacts());
    for (std::size_t c = 0; c < model_->contacts(); ++c)
      strain_rates_[c] = strain_rate(model_->strain(c, v_cells), model_->params(c));
    options.strain_rates = &strain_rates_;
  }
  // A secant iteration that wanders (a crack running within the step) is done again with damage monotone within
  // it, which always converges (static_solver.hpp): the step is a snap-through. Halving it would change the
  // effective stiffness, and the dynamics with it.
  const Eigen::VectorXd u_start = u_;
  const std::vector<double> damage_start = damage_;
  const std::vector<FacetState> states_start = states_;
  for (bool monotone : {false, true}) {
    options.monotone = monotone;
    if (monotone) options.max_iterations *= kSnapThroughIterations;
    try {
      last_ = solver_->solve(u_, f, damage_, states_, options, control_ ? &*control_ : nullptr);
      snap_throughs_ += monotone;
      break;
    } catch (const InstabilityError& e) {
      if (!monotone) {
        u_ = u_start, damage_ = damage_start, states_ = states_start;
        if (control_) control_->lambda = control_->drive.dot(u);
        continue;
      }
      std::ostringstream m;
      m << "Newmark step " << step_ << " (t = " << time_ + setup_.load_step
        << " s; solved again with damage monotone within it): " << e.what();
      throw InstabilityError(m.str());
    }
  }
  const Eigen::VectorXd a_next = s.acceleration(u_, u, v_, a_);
  v_ = s.velocity(v_, a_, a_next);
  a_ = a_next;
  impose_held_motion(time_ + setup_.load_step);
  // The supports' force: K u + M ü + C u̇ − f at the held degrees of freedom.
  const Eigen::VectorXd cells_u = solver_->cell_displacements(u_);
  Eigen::VectorXd balance = plates_->map().transpose() * cell_forces(cells_u) + M * a_ - f_ext_;
  if (d.mass_damping != 0) balance += d.mass_damping * (M * v_);
  if (d.stiffness_damping != 0) balance += d.stiffness_damping * solver_->intact_forces(v_);
  reactions_.setZero();
  for (int dof : prescribed_) reactions_[dof] = balance[dof];
}

// One explicit step (central_difference.hpp): the new displacements from the mid-step velocities, the damage of
// the new strain, the accelerations of its forces.
template <int D>
void RigidCellSystem<D>::explicit_step() {
  const double t = time_ + setup_.load_step;
  KinematicState s{u_, v_, a_};
  f_ext_ = loads_at(t);
  strain_rates_.resize(rate_dependent_ ? model_->contacts() : 0);
  try {
    reactions_ = explicit_->step(setup_.load_step, s, held_motion(t), f_ext_, damage_, states_,
                                 rate_dependent_ ? &strain_rates_ : nullptr);
  } catch (const InstabilityError& e) {
    std::ostringstream m;
    m << "explicit step " << step_ << " (t = " << t << " s): " << e.what();
    throw InstabilityError(m.str());
  }
  u_ = std::move(s.u), v_ = std::move(s.v), a_ = std::move(s.a);
}

template <int D>
KinematicState RigidCellSystem<D>::held_motion(double t) const {
  const Eigen::Index n = plates_->reduced();
  KinematicState h{Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n)};
  for (int p = 0; p < plates_->plates(); ++p) {
    const PlateSpec<D>& s = setup_.plates[p];
    for (int k = 0; k < kDofs; ++k) {
      if (!s.held[k]) continue;
      const int dof = plates_->plate_dof(p, k);
      h.u[dof] = s.velocity[k] * smooth_rise_displacement(t, s.ramp_time);
      h.v[dof] = s.velocity[k] * smooth_rise_velocity(t, s.ramp_time);
      h.a[dof] = s.velocity[k] * smooth_rise_acceleration(t, s.ramp_time);
    }
  }
  return h;
}

// A held degree of freedom moves as its plate is told, not as Newmark's (8.2)-(8.3) would infer from its
// displacements: a plate set moving at once (no rise) would otherwise ring with an acceleration of v/(βΔt) that
// (8.2) passes on from step to step, and the reaction with it. The opening control's drive is left to the scheme.
template <int D>
void RigidCellSystem<D>::impose_held_motion(double t) {
  const KinematicState h = held_motion(t);
  for (int dof : prescribed_) {
    if (control_ && control_->drive[dof] != 0) continue;
    v_[dof] = h.v[dof], a_[dof] = h.a[dof];
  }
}

template <int D>
double RigidCellSystem<D>::kinetic_energy() const {
  return setup_.dynamics ? 0.5 * v_.dot(mass_ * v_) : 0.0;
}

template void RigidCellSystem<2>::build_dynamics();
template void RigidCellSystem<2>::build_explicit();
template void RigidCellSystem<2>::build_stress_wave();
template Eigen::VectorXd RigidCellSystem<2>::loads_at(double) const;
template void RigidCellSystem<2>::dynamic_step();
template void RigidCellSystem<2>::explicit_step();
template KinematicState RigidCellSystem<2>::held_motion(double) const;
template void RigidCellSystem<2>::impose_held_motion(double);
template double RigidCellSystem<2>::kinetic_energy() const;
template void RigidCellSystem<3>::build_dynamics();
template void RigidCellSystem<3>::build_explicit();
template void RigidCellSystem<3>::build_stress_wave();
template Eigen::VectorXd RigidCellSystem<3>::loads_at(double) const;
template void RigidCellSystem<3>::dynamic_step();
template void RigidCellSystem<3>::explicit_step();
template KinematicState RigidCellSystem<3>::held_motion(double) const;
template void RigidCellSystem<3>::impose_held_motion(double);
template double RigidCellSystem<3>::kinetic_energy() const;

}  // namespace mc::rigid_cell
