// Linear contact with Coulomb slip and optional viscous dashpots.
// Springs in series, Tang (2013) eqs. 3.25–3.26; normal force from overlap (3.9); incremental shear force
// (3.5–3.10); slip at μ|F^n| (3.36); ball stiffness from the contact modulus (3.38).
#pragma once
#include <cmath>
#include <string>

#include "engine/contact_geometry.hpp"
#include "engine/contact_set.hpp"

namespace mc {

// Its keys, units, ranges and defaults: Linear::keys() (linear.cpp).
struct LinearParams {
  double modulus = kNaN;     // contact modulus E_c [Pa]: ball k_n = 2 t E_c (2D, t = 1 m) or 4 R E_c (3D), Tang (3.38)
  double kn_ks_ratio = 1.0;  // k_n / k_s [-]
  double friction = 0.0;     // μ [-], Tang (3.36)
  double damping_ratio = 0.0;  // ζ [-], fraction of critical damping of normal and shear dashpots
};

struct Linear {
  static constexpr const char* name = "linear";
  using Params = LinearParams;
  static const KeyTable& keys();
  static double damping_ratio(const Params& p) { return p.damping_ratio; }
  template <int D>
  struct State {
    Vec<D> fs = Vec<D>::Zero();  // shear force on B [N]
  };
  struct Coeffs {
    double kn, ks, mu, zeta;
  };

  template <int D>
  static double ball_kn(const Params& p, double r) {
    return D == 2 ? 2.0 * p.modulus : 4.0 * r * p.modulus;  // Tang (3.38), t = 1 m
  }
  static double series(double a, double b) { return a * b / (a + b); }  // Tang (3.25)

  // Two balls in series, each with its stiffness factor f (1 unless the phase scatters it): in 2D (t = 1 m)
  // 2tE_c f_A · 2tE_c f_B / (2tE_c (f_A + f_B)), E_c for f = 1; in 3D 4E_c (R_A f_A)(R_B f_B)/(R_A f_A + R_B f_B).
  template <int D>
  static Coeffs pair(const Params& p, double ra, double rb, double fa = 1, double fb = 1) {
    const double a = D == 2 ? fa : ra * fa, b = D == 2 ? fb : rb * fb;
    return pair_from<D>(p, a * b / (a + b));
  }
  // From the series "length" a b/(a + b) (a = R f in 3D, f in 2D): a bond model that already holds 1/(R_A + R_B)
  // passes R_A R_B/(R_A + R_B) without a division of its own when both factors are 1.
  template <int D>
  static Coeffs pair_from(const Params& p, double series_ab) {
    const double kn = (D == 2 ? 2.0 : 4.0) * p.modulus * series_ab;
    return {kn, kn * (1.0 / p.kn_ks_ratio), p.friction, p.damping_ratio};
  }
  template <int D>
  static Coeffs wall(const Params& p, const WallMaterial& w, double rb, double fb = 1) {
    const double kb = ball_kn<D>(p, rb) * fb;
    return {series(kb, w.kn), series(kb / p.kn_ks_ratio, w.ks), w.friction, p.damping_ratio};
  }

  template <int D, bool Energy>
  [[gnu::always_inline]] static ContactForce<D> force(const Coeffs& c, const ContactGeometry<D>& g, State<D>& s) {
    ContactForce<D> out;
    if (g.overlap <= 0) {  // separated: no force, and the shear history starts again at the next touch
      if constexpr (Energy) out.dissipated += released_energy<D>(c, s);
      s.fs.setZero();
      return out;
    }
    const double vn = g.v_rel.dot(g.n);
    const Vec<D> vs = g.v_rel - vn * g.n;
    const double fn = c.kn * g.overlap;                                        // Tang (3.9)
    Vec<D> fs = carry_shear<D>(s.fs, g.n, g.spin_n, g.dt) - c.ks * vs * g.dt;  // Tang (3.5), (3.10)
    const double fs_max = c.mu * fn;                                           // Tang (3.36)
    const bool slipping = fs.squaredNorm() > fs_max * fs_max;
    if (slipping) {
      const double fs_mag = fs.norm();
      if constexpr (Energy) out.dissipated += fs_max * (fs_mag - fs_max) / c.ks;  // Tang (3.77)–(3.78)
      fs *= fs_max / fs_mag;
    }
    s.fs = fs;
    out.force = fn * g.n + fs;
    if (c.zeta > 0) add_dashpots<D, Energy>(c, g, vn, vs, slipping, out);
    return out;
  }

  // Dashpots act beside the springs and store nothing; the shear dashpot rests while the contact slides.
  template <int D, bool Energy>
  static void add_dashpots(const Coeffs& c, const ContactGeometry<D>& g, double vn, const Vec<D>& vs, bool slipping,
                           ContactForce<D>& out) {
    Vec<D> fd = -2.0 * c.zeta * std::sqrt(g.m_eff() * c.kn) * vn * g.n;
    if (!slipping) fd -= 2.0 * c.zeta * std::sqrt(g.m_eff() * c.ks) * vs;
    out.force += fd;
    if constexpr (Energy) out.dashpot = fd;
  }

  template <int D>
  static ContactStiffness stiffness(const Coeffs& c, const ContactGeometry<D>&, const State<D>&) {
    return {c.kn, c.ks, 0.0};
  }

  template <int D>
  static double strain_energy(const Coeffs& c, const ContactGeometry<D>& g, const State<D>& s) {
    if (g.overlap <= 0) return 0;
    const double fn = c.kn * g.overlap;
    return 0.5 * (fn * fn / c.kn + s.fs.squaredNorm() / c.ks);  // Tang (3.80)
  }

  // A shear spring still loaded when the contact opens lets its energy go; booked as dissipated, else the
  // balance would lose it (in a packing with friction too high to slip: 31 % of the initial energy).
  template <int D>
  static double released_energy(const Coeffs& c, const State<D>& s) {
    return 0.5 * s.fs.squaredNorm() / c.ks;
  }

  template <int D>
  static bool persistent(const State<D>&) {
    return false;
  }
};

// Compiled in linear.cpp.
extern template class ContactSet<Linear, 2>;
extern template class ContactSet<Linear, 3>;

}  // namespace mc
