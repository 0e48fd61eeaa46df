// The linear contact with Coulomb slip (linear.hpp) and a rolling resistance beside it, as PFC's rolling-resistance
// linear model (Itasca, "rrlinear"; Iwashita & Oda 1998; Ai et al. 2011, type A): a spring of stiffness
// k_r = k_s R̄² carries a moment M_r against the pair's relative bending rotation, incrementally,
//   M_r ← M_r − k_r Δθ_b,   Δθ_b = (ω_B − ω_A)Δt less its twist about n (3D),
// bounded by |M_r| ≤ μ_r R̄ F_n, R̄ = R_A R_B/(R_A + R_B) (R_B against a wall). Grains that would roll freely on a
// frictional contact then resist rolling as angular grains do: a ball on a slope rolls only where tan θ > μ_r,
// at a = g (sin θ − μ_r cos θ)/(1 + I/(m R²)) (tests/rolling_resistance_slope.cpp).
#pragma once
#include <cmath>

#include "contact_models/bond_family.hpp"  // GrainContact: the linear contact on a state's `fs`
#include "contact_models/linear.hpp"
#include "engine/contact_geometry.hpp"
#include "engine/contact_set.hpp"

namespace mc {

// Its keys, units, ranges and defaults: RollingResistance::keys() (rolling_resistance.cpp).
struct RollingResistanceParams {
  LinearParams contact;          // the linear contact with slip it acts beside
  double rolling_friction = kNaN;  // μ_r [-]: the rolling moment is bounded by μ_r R̄ F_n
};

struct RollingResistance {
  static constexpr const char* name = "rolling_resistance";
  using Params = RollingResistanceParams;
  static const KeyTable& keys();
  static double damping_ratio(const Params& p) { return p.contact.damping_ratio; }
  template <int D>
  struct State {
    Vec<D> fs = Vec<D>::Zero();  // shear force on B [N]
    Rot<D> mr = Rot<D>::Zero();  // rolling moment on B [N m]: in the contact plane in 3D
  };
  struct Coeffs {
    Linear::Coeffs contact;
    double kr;         // k_r = k_s R̄² [N m/rad]
    double mu_r_lever;  // μ_r R̄ [m]: the moment's bound per newton of normal force
  };

  template <int D>
  static Coeffs pair(const Params& p, double ra, double rb, double fa = 1, double fb = 1) {
    return rolling(p, Linear::pair<D>(p.contact, ra, rb, fa, fb), ra * rb / (ra + rb));
  }
  template <int D>
  static Coeffs wall(const Params& p, const WallMaterial& w, double rb, double fb = 1) {
    return rolling(p, Linear::wall<D>(p.contact, w, rb, fb), rb);
  }
  static Coeffs rolling(const Params& p, const Linear::Coeffs& lc, double r_bar) {
    return {lc, lc.ks * r_bar * r_bar, p.rolling_friction * r_bar};
  }

  template <int D, bool Energy>
  [[gnu::always_inline]] static ContactForce<D> force(const Coeffs& c, const ContactGeometry<D>& g, State<D>& s) {
    ContactForce<D> out = GrainContact::force<D, Energy>(c.contact, g, s);
    if (g.overlap <= 0) {  // separated: the rolling history starts again at the next touch
      if constexpr (Energy) out.dissipated += rolling_energy<D>(c, s);
      s.mr.setZero();
      return out;
    }
    Rot<D> mr;
    if constexpr (D == 2) {
      mr = s.mr - c.kr * g.w_rel * g.dt;
    } else {  // the stored moment turns with the contact plane, as the shear force does; the twist is free
      const double wn = g.w_rel.dot(g.n);
      mr = carry_shear<3>(s.mr, g.n, g.spin_n, g.dt) - c.kr * (g.w_rel - wn * g.n) * g.dt;
    }
    const double m_max = c.mu_r_lever * c.contact.kn * g.overlap;  // μ_r R̄ F_n
    if (mr.squaredNorm() > m_max * m_max) {
      const double m_mag = mr.norm();
      if constexpr (Energy) out.dissipated += m_max * (m_mag - m_max) / c.kr;  // as the slip's, Tang (3.77)
      mr *= m_max / m_mag;
    }
    s.mr = mr;
    out.moment += mr;
    return out;
  }

  template <int D>
  static ContactStiffness stiffness(const Coeffs& c, const ContactGeometry<D>& g, const State<D>& s) {
    ContactStiffness k = GrainContact::stiffness<D>(c.contact, g, s);
    k.rotational += c.kr;
    return k;
  }
  template <int D>
  static double rolling_energy(const Coeffs& c, const State<D>& s) {
    return 0.5 * s.mr.squaredNorm() / c.kr;
  }
  template <int D>
  static double strain_energy(const Coeffs& c, const ContactGeometry<D>& g, const State<D>& s) {
    if (g.overlap <= 0) return 0;
    return GrainContact::strain_energy<D>(c.contact, g, s) + rolling_energy<D>(c, s);
  }
  // A contact that opens lets its shear and rolling springs' energy go.
  template <int D>
  static double released_energy(const Coeffs& c, const State<D>& s) {
    return GrainContact::released_energy<D>(c.contact, s) + rolling_energy<D>(c, s);
  }
  template <int D>
  static bool persistent(const State<D>&) {
    return false;
  }
};

// Compiled in rolling_resistance.cpp.
extern template class ContactSet<RollingResistance, 2>;
extern template class ContactSet<RollingResistance, 3>;

}  // namespace mc
