// Newmark's implicit time integration (Květoň §8.1, (8.2)-(8.5); Newmark 1959, Bathe 1996): the acceleration and
// velocity at t + Δt from the displacement there, and the effective load's inertial part. A step solves
// (K + a₀M) u_{t+Δt} = F_{t+Δt} + M (a₀ u_t + a₁ u̇_t + a₂ ü_t), (8.4) without damping (the thesis omits C), then
// updates ü and u̇ by (8.2)-(8.3). Unconditionally stable for 2β ≥ γ ≥ ½ (8.5).
#pragma once
#include <cmath>
#include <numbers>
#include <string>

#include "engine/errors.hpp"

namespace mc::rigid_cell {

struct NewmarkScheme {
  static constexpr double kBeta = 0.3, kGamma = 0.55;  // Květoň §9.1
  double beta, gamma, dt;

  NewmarkScheme(double beta, double gamma, double dt) : beta(beta), gamma(gamma), dt(dt) {
    if (!(2 * beta >= gamma && gamma >= 0.5))
      throw InputError("Newmark beta = " + std::to_string(beta) + ", gamma = " + std::to_string(gamma) +
                       ": 2 beta >= gamma >= 0.5 is required for unconditional stability (Kveton (8.5))");
    if (!(dt > 0)) throw InputError("Newmark: the time step must be positive");
  }

  // The coefficients of (8.2) and (8.4): ü_{t+Δt} = a₀ (u_{t+Δt} − u_t) − a₁ u̇_t − a₂ ü_t.
  double a0() const { return 1 / (beta * dt * dt); }
  double a1() const { return 1 / (beta * dt); }
  double a2() const { return 1 / (2 * beta) - 1; }

  // (8.2): the acceleration at t + Δt.
  template <class V>
  V acceleration(const V& u_next, const V& u, const V& v, const V& a) const {
    return a0() * (u_next - u) - a1() * v - a2() * a;
  }
  // (8.3): the velocity at t + Δt.
  template <class V>
  V velocity(const V& v, const V& a, const V& a_next) const {
    return v + dt * (1 - gamma) * a + gamma * dt * a_next;
  }
  // The inertial part of (8.4)'s effective load, before M: a₀ u_t + a₁ u̇_t + a₂ ü_t.
  template <class V>
  V inertial_history(const V& u, const V& v, const V& a) const {
    return a0() * u + a1() * v + a2() * a;
  }
  // The damping part of (8.4): C multiplies γ/(βΔt) u_{t+Δt} on the left, and this on the right.
  double damping_coefficient() const { return gamma / (beta * dt); }
  template <class V>
  V damping_history(const V& u, const V& v, const V& a) const {
    return damping_coefficient() * u + (gamma / beta - 1) * v + 0.5 * dt * (gamma / beta - 2) * a;
  }
};

// What the scheme does to an undamped oscillator of circular frequency ω (Hughes 1987, §9.1): its displacements
// follow x_{n+1} − 2A₁ x_n + A₂ x_{n−1} = 0 with Ω = ωΔt,
//   A₁ = 1 − Ω² (γ + ½) / (2 (1 + βΩ²)),   A₂ = 1 − Ω² (γ − ½) / (1 + βΩ²),
// so x_n = ρⁿ (c₁ cos nΩ̄ + c₂ sin nΩ̄) with ρ = √A₂ and cos Ω̄ = A₁/ρ: the period grows to T Ω/Ω̄ and the
// amplitude shrinks by ρ^(2π/Ω̄) per period.
struct NewmarkOscillator {
  double rho = 1, omega_bar = 0;  // spectral radius, numerical phase per step Ω̄

  NewmarkOscillator(const NewmarkScheme& s, double omega) {
    const double W2 = omega * omega * s.dt * s.dt, d = 1 + s.beta * W2;
    const double A1 = 1 - W2 * (s.gamma + 0.5) / (2 * d), A2 = 1 - W2 * (s.gamma - 0.5) / d;
    rho = std::sqrt(A2);
    omega_bar = std::acos(A1 / rho);
  }
  double period_ratio(const NewmarkScheme& s, double omega) const { return omega * s.dt / omega_bar; }
  double decay_per_period() const { return std::pow(rho, 2 * std::numbers::pi / omega_bar); }
};

}  // namespace mc::rigid_cell
