// What a contact model receives for one contact, and what it returns. The engine computes the geometry
// (Tang 3.1–3.4, 3.6) once; models only turn it into forces.
#pragma once
#include <algorithm>
#include <cmath>

#include "engine/crack.hpp"
#include "engine/dim.hpp"

namespace mc {

// Partner A (index i, or the wall) and partner B (index j, the ball for a ball–wall contact).
template <int D>
struct ContactGeometry {
  Vec<D> n;         // unit normal from A to B, Tang (3.1)
  double overlap;   // U^n = R_A + R_B − d (> 0 when touching), Tang (3.3)
  Vec<D> v_rel;     // velocity of B relative to A at the contact point, Tang (3.6)
  Rot<D> w_rel;     // ω_B − ω_A (bending and twisting of bonds)
  double spin_n;    // ½(ω_A + ω_B)·n (3D): rigid spin of the contact plane about its normal
  double r_a, r_b;  // radii (r_a = ∞ for a wall)
  double m_a, m_b;  // masses (m_a = 0 for a wall, which is immovable)
  double k_a, k_b;  // the particles' stiffness factors (1 for a wall, and unless heterogeneity is declared)
  double dt;
  // m_A m_B / (m_A + m_B) (m_B for a wall): the critical damping of dashpots. Only models with dashpots ask.
  double m_eff() const { return m_a > 0 ? m_a * m_b / (m_a + m_b) : m_b; }
};

// What a wall brings to a ball–wall contact: its own springs (in series with the ball's) and friction.
struct WallMaterial {
  double kn = kNaN;       // N/m
  double ks = kNaN;       // N/m
  double friction = 0.0;  // μ [-]
};

// Force on B (A receives −force). `moment` is a moment on B carried by the model itself (bond bending and
// twisting); A receives −moment. Moments of `force` about the particle centres are added by the engine.
template <int D>
struct ContactForce {
  Vec<D> force = Vec<D>::Zero();
  Rot<D> moment = Rot<D>::Zero();
  // Energy dissipated this step [J], filled only when energy is traced: by friction, plastic flow and viscosity,
  // and by the bond itself (breakage, softening, damage: the fracture work).
  double dissipated = 0;
  double fractured = 0;
  // The dashpot part of `force` (filled only when energy is traced). Its work is booked by the engine one
  // step later, against the velocity with which the particles actually moved under it.
  Vec<D> dashpot = Vec<D>::Zero();
  BondEvent event;  // a bond broke or first yielded this step (the crack log)
};

// Stiffness seen by the timestep estimate, Tang (3.22)–(3.24).
struct ContactStiffness {
  double normal = 0;  // N/m
  double shear = 0;   // N/m; acting at the contact point it also resists rotation (shear·lever², added by the engine)
  double rotational = 0;  // N m/rad carried by the model itself (bond bending)
};

// An incremental shear force lives in the contact plane. When the plane tilts (new normal) or spins about
// its normal, the stored force must turn with it, else it would do spurious work (Tang §3.2.1, PFC3D).
// Inlined: a bond carries three such vectors per step, and the three chains then overlap in the pipeline.
template <int D>
[[gnu::always_inline]] inline Vec<D> carry_shear(const Vec<D>& fs, const Vec<D>& n, double spin_n, double dt) {
  const double mag2 = fs.squaredNorm();
  const double p = fs.dot(n);
  Vec<D> t = fs - p * n;  // into the new plane: |t|² = |F|² − p²
  if constexpr (D == 3) {
    // Turn by a = spin·Δt about n (a ~ 1e-6 rad): Rodrigues' formula with cos a ≈ 1 − a²/2, sin a ≈ a keeps
    // |t| to O(a⁴) without a sine and a cosine per contact per step.
    const double a = spin_n * dt;
    t = (1.0 - 0.5 * a * a) * t + a * n.cross(t);
  }
  // The projection shortened the force by cos θ ≈ 1 − θ²/2, θ the angle the plane tilted, sin²θ = p²/|F|². In a
  // stable step θ ≲ 1e-6: the loss (≲ 1e-12 of |F| per step, dissipative, never generative) is left, which
  // spares a division on the critical path of every carried vector. A tilt above 1e-4 rad in one step (violent
  // impacts) restores the magnitude exactly.
  if (p * p <= 1e-8 * mag2) [[likely]]
    return t;
  const double t2 = mag2 - p * p;
  return t2 > 0 ? Vec<D>(t * std::sqrt(mag2 / t2)) : Vec<D>::Zero();
}

// One contact's numbers in the words of a law written once over its number type (engine/lanes.hpp has the same
// words for kLanes contacts at once): a dot product in Eigen's order, the smaller of two, a magnitude, a choice.
template <class A, class B>
[[gnu::always_inline]] inline double dot(const Eigen::MatrixBase<A>& a, const Eigen::MatrixBase<B>& b) {
  return a.dot(b);
}
[[gnu::always_inline]] inline double min_of(double a, double b) { return std::min(a, b); }
[[gnu::always_inline]] inline double abs_of(double a) { return std::abs(a); }
[[gnu::always_inline]] inline double pick(bool m, double a, double b) { return m ? a : b; }

}  // namespace mc
