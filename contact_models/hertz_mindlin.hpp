// Simplified Hertz–Mindlin contact (PFC): nonlinear normal spring, tangent shear stiffness that grows with
// the normal force, Coulomb slip. Tang (2013) eqs. 3.27–3.35.
#pragma once
#include <cmath>

#include "engine/contact_geometry.hpp"
#include "engine/contact_set.hpp"

namespace mc {

// Its keys, units, ranges and defaults: HertzMindlin::keys() (hertz_mindlin.cpp).
struct HertzMindlinParams {
  double shear_modulus = kNaN;  // G [Pa]
  double poisson = kNaN;        // ν [-]
  double friction = 0.0;        // μ [-]
  double damping_ratio = 0.0;   // ζ [-]
};

struct HertzMindlin {
  static constexpr const char* name = "hertz_mindlin";
  using Params = HertzMindlinParams;
  static const KeyTable& keys();
  static double damping_ratio(const Params& p) { return p.damping_ratio; }
  template <int D>
  struct State {
    Vec<D> fs = Vec<D>::Zero();
  };
  struct Coeffs {
    double cn;  // F^n = cn (U^n)^{3/2}: K^n of (3.27) is cn √U^n
    double cs;  // k^s = cs |F^n|^{1/3}, Tang (3.28)
    double mu, zeta;
  };

  // g_factor: the particles' stiffness factors enter ⟨G⟩ (3.30) as ½(f_A + f_B) G (one ball: f G, 3.33).
  static Coeffs make(const Params& p, double r_tilde, double mu, double g_factor) {
    const double g = p.shear_modulus * g_factor, nu = p.poisson;
    return {2.0 * g * std::sqrt(2.0 * r_tilde) / (3.0 * (1.0 - nu)),
            2.0 * std::cbrt(g * g * 3.0 * (1.0 - nu) * r_tilde) / (2.0 - nu), mu, p.damping_ratio};
  }
  template <int D>
  static Coeffs pair(const Params& p, double ra, double rb, double fa = 1, double fb = 1) {
    return make(p, 2.0 * ra * rb / (ra + rb), p.friction, 0.5 * (fa + fb));  // Tang (3.29)–(3.31)
  }
  template <int D>
  static Coeffs wall(const Params& p, const WallMaterial& w, double rb, double fb = 1) {
    return make(p, rb, w.friction, fb);  // Tang (3.32)–(3.34): the ball's G and ν, R̃ = R
  }

  template <int D, bool Energy>
  [[gnu::always_inline]] static ContactForce<D> force(const Coeffs& c, const ContactGeometry<D>& g, State<D>& s) {
    ContactForce<D> out;
    if (g.overlap <= 0) {
      s.fs.setZero();
      return out;
    }
    const double vn = g.v_rel.dot(g.n);
    const Vec<D> vs = g.v_rel - vn * g.n;
    const double sq = std::sqrt(g.overlap);
    const double fn = c.cn * sq * g.overlap;  // K^n U^n, Tang (3.27)
    const double ks = c.cs * std::cbrt(fn);   // Tang (3.28)
    Vec<D> fs = carry_shear<D>(s.fs, g.n, g.spin_n, g.dt) - ks * vs * g.dt;
    const double fs_max = c.mu * fn;  // Tang (3.35)–(3.36)
    const double fs_mag = fs.norm();
    const bool slipping = fs_mag > fs_max;
    if (slipping) {
      if constexpr (Energy) out.dissipated += fs_max * (fs_mag - fs_max) / ks;
      fs *= fs_max / fs_mag;
    }
    s.fs = fs;
    out.force = fn * g.n + fs;
    if (c.zeta > 0) {
      const double kn_tangent = 1.5 * c.cn * sq;
      Vec<D> fd = -2.0 * c.zeta * std::sqrt(g.m_eff() * kn_tangent) * vn * g.n;
      if (!slipping) fd -= 2.0 * c.zeta * std::sqrt(g.m_eff() * ks) * vs;
      out.force += fd;
      if constexpr (Energy) out.dashpot = fd;
    }
    return out;
  }

  // Tangent stiffnesses: what the explicit scheme feels. A contact that has not yet touched is given the
  // stiffness at an overlap of 1 % of the smaller radius, so that a fresh impact is not stepped over.
  template <int D>
  static ContactStiffness stiffness(const Coeffs& c, const ContactGeometry<D>& g, const State<D>&) {
    const double u = std::max(g.overlap, 0.01 * std::min(g.r_a, g.r_b));
    const double fn = c.cn * std::sqrt(u) * u;
    return {1.5 * c.cn * std::sqrt(u), c.cs * std::cbrt(fn), 0.0};
  }

  template <int D>
  static double strain_energy(const Coeffs& c, const ContactGeometry<D>& g, const State<D>& s) {
    if (g.overlap <= 0) return 0;
    const double fn = c.cn * std::sqrt(g.overlap) * g.overlap;
    const double ks = c.cs * std::cbrt(fn);
    return 0.4 * fn * g.overlap + 0.5 * s.fs.squaredNorm() / ks;  // ∫ cn u^{3/2} du = ⅖ F^n U^n
  }

  // At opening |F^s| ≤ μF^n and k^s ∝ (F^n)^{1/3}, so the shear energy left, ≤ μ²(F^n)^{5/3}/c_s, vanishes with
  // the normal force: nothing to book.
  template <int D>
  static double released_energy(const Coeffs&, const State<D>&) {
    return 0.0;
  }

  template <int D>
  static bool persistent(const State<D>&) {
    return false;
  }
};

// Compiled in hertz_mindlin.cpp.
extern template class ContactSet<HertzMindlin, 2>;
extern template class ContactSet<HertzMindlin, 3>;

}  // namespace mc
