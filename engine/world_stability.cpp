// The stability guard: a run that goes wrong stops with a message naming the step, the particle or wall and the
// likely cause, instead of writing nonsense.
#include <sstream>

#include "engine/errors.hpp"
#include "engine/world.hpp"

namespace mc {

template <int D>
void World<D>::check_stability() const {
  const auto& p = particles;
  const int n = p.size();
  for (int i = 0; i < n; ++i) {
    std::ostringstream m;
    bool finite = p.x[i].allFinite() && p.v[i].allFinite() && p.w[i].allFinite();
    if (!finite) {
      m << "unstable at step " << step_count << " (t = " << time << " s): particle " << i
        << " has a non-finite position or velocity; likely cause: timestep " << dt
        << " s too large for the contact stiffness (critical estimate " << dt_critical << " s)";
      throw InstabilityError(m.str());
    }
    if (p.v[i].norm() * dt > 0.5 * p.radius[i]) {
      m << "unstable at step " << step_count << " (t = " << time << " s): particle " << i << " moved "
        << p.v[i].norm() * dt / p.radius[i] << " of its radius in one step (|v| = " << p.v[i].norm()
        << " m/s); likely cause: timestep " << dt << " s above the stability limit (critical estimate " << dt_critical
        << " s), or stiffness too high for it";
      throw InstabilityError(m.str());
    }
    for (int k = 0; k < D; ++k)
      if (p.x[i][k] < domain_lo[k] || p.x[i][k] > domain_hi[k]) {
        m << "stopped at step " << step_count << " (t = " << time << " s): particle " << i << " left the domain ("
          << "coordinate " << k << " = " << p.x[i][k] << " m, domain " << domain_lo[k] << " .. " << domain_hi[k]
          << " m); likely cause: a gap in the walls, an explosion of the packing, or a domain set too small";
        throw InstabilityError(m.str());
      }
  }
  for (std::size_t w = 0; w < walls.size(); ++w)
    if (!walls[w].origin.allFinite() || !walls[w].force.allFinite()) {
      std::ostringstream m;
      m << "unstable at step " << step_count << ": wall '" << walls[w].name
        << "' has a non-finite position or force; likely cause: servo gain or timestep too large";
      throw InstabilityError(m.str());
    }
  if (trace_energy) {
    // What has come out as motion, friction and damping cannot exceed all the energy ever put in; if it does,
    // the integration is making energy. The kinetic term alone is not enough: an unstable mode held in check by
    // friction or by contacts opening never grows without bound (its energy goes to friction), and its
    // ½ m v(t−Δt/2)·v(t+Δt/2) is even negative when the velocities reverse every step.
    const double budget = std::abs(energy.initial) + std::abs(energy.body_work) + std::abs(energy.boundary_work);
    const double out = energy.kinetic + energy.dissipated_contacts + energy.dissipated_local;
    if (out > 2.0 * budget + 1e-12) {
      int fastest = 0;  // the particle with the most kinetic energy, to point at
      double e_max = -1;
      for (int i = 0; i < n; ++i) {
        const double e = 0.5 * (p.mass[i] * p.v[i].squaredNorm() + p.inertia[i] * p.w[i].squaredNorm());
        if (e > e_max) e_max = e, fastest = i;
      }
      std::ostringstream m;
      m << "unstable at step " << step_count << " (t = " << time << " s): kinetic energy " << energy.kinetic
        << " J plus dissipated " << energy.dissipated_contacts + energy.dissipated_local
        << " J exceeds twice the energy put in (" << budget << " J)";
      if (n > 0) m << ", particle " << fastest << " moving fastest (|v| = " << p.v[fastest].norm() << " m/s)";
      m << "; likely cause: timestep " << dt << " s above the stability limit (critical estimate " << dt_critical
        << " s)";
      throw InstabilityError(m.str());
    }
  }
}

template void World<2>::check_stability() const;
template void World<3>::check_stability() const;

}  // namespace mc
