// The stability guard: a run that goes wrong stops with a message naming the step, the particle or wall and the
// likely cause, instead of writing nonsense.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "engine/errors.hpp"
#include "engine/world.hpp"

namespace mc {

namespace {

// "at step N (t = T s)": every message says when.
template <int D>
std::string when(const World<D>& w) {
  std::ostringstream m;
  m << "at step " << w.step_count << " (t = " << w.time << " s)";
  return m.str();
}

// "in step N+1 (from t = T s)": what the step under way found, before it was counted.
template <int D>
std::string during(const World<D>& w) {
  std::ostringstream m;
  m << "in step " << w.step_count + 1 << " (from t = " << w.time << " s)";
  return m.str();
}

}  // namespace

template <int D>
std::string World<D>::too_far_message(int i) const {
  const auto& p = particles;
  std::ostringstream m;
  m << "unstable " << during(*this) << ": " << particle_name(i);
  if (!p.x[i].allFinite() || !p.v[i].allFinite()) {
    m << " has a non-finite position or velocity";
  } else {
    m << " moved " << p.v[i].norm() * dt / p.radius[i] << " of its radius in one step (|v| = " << p.v[i].norm()
      << " m/s)";
  }
  m << "; likely cause: timestep " << dt << " s too large for the contact stiffness (critical estimate " << dt_critical
    << " s), or forces out of all proportion (particles placed deep inside each other, an applied "
    << "load or a wall speed far beyond what the specimen can take)";
  return m.str();
}

// Two particles (or a particle and a wall) closer than half the smaller radius: the springs could not stop them,
// and once the centres pass, the contact normal turns round and pushes them on through. No contact law holds
// such a pair apart; the run cannot be trusted from here.
template <int D>
std::string World<D>::passing_message(const Pair& pair) const {
  const auto& p = particles;
  const auto [a, b] = pair;
  std::ostringstream m;
  m << "stopped " << during(*this) << ": ";
  if (a < 0) {
    const Wall<D>& wl = walls[-1 - a];
    const double depth = p.radius[b] - (p.x[b] - wl.closest(p.x[b])).norm();
    m << particle_name(b) << " is " << depth / p.radius[b] << " of its radius inside wall '" << wl.name
      << "' (speed towards it " << std::max(0.0, -(p.v[b] - wl.velocity).dot(wl.normal)) << " m/s)";
  } else {
    const Vec<D> d = p.x[b] - p.x[a];
    const double depth = p.radius[a] + p.radius[b] - d.norm();
    m << particle_name(a) << " and " << particle_name(b) << " overlap by " << depth / std::min(p.radius[a], p.radius[b])
      << " of the smaller radius (approaching at " << std::max(0.0, -(p.v[b] - p.v[a]).dot(d.normalized())) << " m/s)";
  }
  m << ": they are passing through each other, which no contact law can stop; likely cause: an impact too fast "
       "for the contact stiffness (the kinetic energy exceeds what the springs store at half a radius of overlap: "
       "stiffen the contact or slow the impact), or particles placed deep inside each other";
  return m.str();
}

template <int D>
void World<D>::check_stability() const {
  const auto& p = particles;
  const int n = p.size();
  // The first own particle (in the whole world's order) outside the domain, and the axis it left along.
  auto axis_out = [&](int i) {
    int k = 0;
    while (k < D && p.x[i][k] >= domain_lo[k] && p.x[i][k] <= domain_hi[k]) ++k;
    return k;  // D: inside
  };
  int outside = -1, k = D;
  for (int i = 0; i < n && outside < 0; ++i)
    if (!p.is_ghost(i) && (k = axis_out(i)) < D) outside = i;
  std::string message;
  if (outside >= 0) {
    const int i = outside;
    std::ostringstream m;
    m << "stopped " << when(*this) << ": " << particle_name(i) << " left the domain (coordinate " << k << " = "
      << p.x[i][k] << " m, domain " << domain_lo[k] << " .. " << domain_hi[k] << " m, |v| = " << p.v[i].norm()
      << " m/s); likely cause: a gap in the walls, an explosion of the packing, a particle shot out by an "
         "impact, or a domain set too small";
    message = m.str();
  }
  // A split world stops on every process together, with the message of the first such particle of all.
  if (split_) message = first_failure({outside >= 0 ? global_index(outside) : 0, 0, 0}, message);
  if (!message.empty()) throw InstabilityError(message);
  for (std::size_t w = 0; w < walls.size(); ++w)
    if (!walls[w].origin.allFinite() || !walls[w].force.allFinite()) {
      std::ostringstream m;
      m << "unstable " << when(*this) << ": wall '" << walls[w].name
        << "' has a non-finite position or force; likely cause: servo gain or timestep too large";
      throw InstabilityError(m.str());
    }
  check_opening_control();
  if (trace_energy) check_energy();
}

// An opening servo corrects gain × Δt of its error per step (if the gauge followed the wall one to one): at 1 or
// more it overshoots its own error every step and the wall oscillates with growing amplitude. A gauge whose
// particles went non-finite leaves the wall without a reading.
template <int D>
void World<D>::check_opening_control() const {
  for (const auto& wl : walls) {
    if (wl.control != WallControl::Opening) continue;
    // A split world's gauge reads the whole world's particles only where the processes share their sums.
    const double reading = split_ ? gauges[wl.gauge].reading() : gauges[wl.gauge].value(particles);
    if (!std::isfinite(reading) || wl.opening_gain * dt >= 1) {
      std::ostringstream m;
      m << "unstable " << when(*this) << ": wall '" << wl.name << "' under opening control: ";
      if (!std::isfinite(reading))
        m << "its gauge reads " << reading << "; likely cause: the gauge's particles became unstable";
      else
        m << "gain " << wl.opening_gain << " /s times the timestep " << dt << " s is " << wl.opening_gain * dt
          << " >= 1, so each step overshoots the opening error; lower the gain below " << 1 / dt << " /s";
      throw InstabilityError(m.str());
    }
  }
}

// What has come out as motion, friction and damping cannot exceed all the energy ever put in; if it does, the
// integration is making energy. The kinetic term alone is not enough: an unstable mode held in check by friction
// or by contacts opening never grows without bound (its energy goes to friction), and its ½ m v(t−Δt/2)·v(t+Δt/2)
// is even negative when the velocities reverse every step. Two causes make energy: a timestep above the limit,
// and impacts resolved in too few steps (central differences conserve energy exactly only while contacts stay
// closed; a contact that opens or closes between two steps gains or loses a share of order (ωΔt)² of what it
// stores, and undamped impacts add these up like a random walk: ±30 % in 0.5 s for two discs bouncing between
// walls at a safety factor of 0.8, ±1 % at 0.1).
template <int D>
void World<D>::check_energy() const {
  const auto& p = particles;
  const int n = p.size();
  const double budget = std::abs(energy.initial) + std::abs(energy.body_work) + std::abs(energy.boundary_work);
  const double out = energy.kinetic + energy.dissipated_contacts + energy.dissipated_bonds + energy.dissipated_local;
  if (out <= 2.0 * budget + 1e-12) return;
  int fastest = 0;  // the particle with the most kinetic energy, to point at
  double e_max = -1;
  for (int i = 0; i < n; ++i) {
    const double e = 0.5 * (p.mass[i] * p.v[i].squaredNorm() + p.inertia[i] * p.w[i].squaredNorm());
    if (e > e_max) e_max = e, fastest = i;
  }
  std::ostringstream m;
  m << "unstable " << when(*this) << ": kinetic energy " << energy.kinetic << " J plus dissipated "
    << energy.dissipated_contacts + energy.dissipated_bonds + energy.dissipated_local
    << " J exceeds twice the energy put in (" << budget << " J)";
  if (n > 0) m << ", " << particle_name(fastest) << " moving fastest (|v| = " << p.v[fastest].norm() << " m/s)";
  // The fastest contact vibration's half period, π over its angular frequency, is π times the critical estimate.
  const double steps = M_PI * dt_critical / dt;
  m << "; the timestep " << dt << " s is " << dt / dt_critical << " of its critical estimate " << dt_critical
    << " s, so the stiffest contacts last about " << steps << " steps. Likely cause: ";
  if (dt < 0.95 * dt_critical)
    m << "impacts resolved in too few steps (each contact that opens or closes between two steps gains or loses "
         "energy, and undamped impacts add it up): lower the timestep safety factor (0.1 gives some 30 steps per "
         "contact) or damp the impacts";
  else
    m << "a timestep at the stability limit: lower the timestep safety factor";
  throw InstabilityError(m.str());
}

template void World<2>::check_stability() const;
template void World<3>::check_stability() const;
template std::string World<2>::too_far_message(int) const;
template std::string World<3>::too_far_message(int) const;
template std::string World<2>::passing_message(const Pair&) const;
template std::string World<3>::passing_message(const Pair&) const;
template void World<2>::check_energy() const;
template void World<2>::check_opening_control() const;
template void World<3>::check_opening_control() const;
template void World<3>::check_energy() const;

}  // namespace mc
