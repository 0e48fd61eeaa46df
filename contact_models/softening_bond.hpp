// Displacement-softening bond (PFC; Tang 2013 §3.3.3, eqs. 3.42–3.48): a contact bond that does not let go at
// its strength but softens, like a cohesive zone. Linear springs glued at the contact point carry tension and
// shear; a force beyond the bond's strength is returned onto it and the excess displacement becomes plastic,
// and the strength falls linearly with the plastic displacement accumulated. When that reaches U_p,max the bond
// is broken and the pair is a linear contact with Coulomb slip (3.36). The area under the softening curve,
// ½ F_c^n U_p,max in pure tension, is the energy it takes to open the crack.
#pragma once
#include <algorithm>
#include <cmath>

#include "contact_models/contact_bond.hpp"
#include "contact_models/linear.hpp"
#include "engine/contact_geometry.hpp"
#include "engine/contact_set.hpp"

namespace mc {

// The contact bond's springs and strengths (F_c^n, F_c^s [N]), and how far the bond softens. Its keys, units,
// ranges and defaults: SofteningBond::keys() (softening_bond.cpp).
struct SofteningBondParams : ContactBondParams {
  // U_p,max comes from exactly one of these (the other is 0).
  double bond_plastic_limit = 0.0;    // U_p,max [m]
  double bond_fracture_energy = 0.0;  // G_f [J/m²] over the bond's section
};

// What it shares with the contact bond (glued springs measured from the gap at bonding, their energy, the
// pair kept while bonded, the linear contact after the break) it inherits; the force law is its own.
struct SofteningBond : ContactBond {
  static constexpr const char* name = "softening_bond";
  using Params = SofteningBondParams;
  static const KeyTable& keys();  // its own, not the contact bond's it would inherit
  // The contact bond's state (shear force, strengths, gap0) and U_p. Here gap0 also widens with the bond's
  // plastic opening.
  template <int D>
  struct State : ContactBond::State<D> {
    double up = 0;  // U_p, accumulated plastic displacement [m], Tang (3.48); every yield adds to it, so
                    // U_p > 0 also marks a bond whose first yield was reported
  };
  struct Coeffs : Linear::Coeffs {
    double plastic_limit;  // U_p,max [m], or 0: from fracture_work and the bond's own F_c^n
    double fracture_work;  // G_f A [J]
  };

  template <int D>
  static Coeffs pair(const Params& p, double ra, double rb, double fa = 1, double fb = 1) {
    const double r = std::min(ra, rb);
    const double area = D == 2 ? 2.0 * r : M_PI * r * r;  // Tang (3.39) with λ̄ = 1, t = 1 m
    return {Linear::pair<D>(p.contact, ra, rb, fa, fb), p.bond_plastic_limit, p.bond_fracture_energy * area};
  }
  template <int D>
  static Coeffs wall(const Params& p, const WallMaterial& w, double rb, double fb = 1) {
    return {Linear::wall<D>(p.contact, w, rb, fb), 0.0, 0.0};  // walls are never bonded
  }

  // Given, or such that opening the bond in pure tension takes G_f A: the triangle ½ F_c^n U_p,max under
  // the softening curve (3.48). A bond with a weaker draw of F_c^n then softens over a longer way.
  template <int D>
  static double plastic_limit(const Coeffs& c, const State<D>& s) {
    return c.plastic_limit > 0 ? c.plastic_limit : 2.0 * c.fracture_work / s.normal;
  }

  static constexpr bool yields = true;  // first yields go to the crack log too
  // Glued where it stands, as a contact bond: across a small gap the normal spring measures from that gap.
  template <int D, class Normal>
  static void install(const Params& p, const ContactGeometry<D>& g, State<D>& s, Normal& normal) {
    s = State<D>{{s.fs}};
    ContactBond::install<D>(p, g, s, normal);
  }

  template <int D, bool Energy>
  [[gnu::always_inline]] static ContactForce<D> force(const Coeffs& c, const ContactGeometry<D>& g, State<D>& s) {
    if (!bonded(s)) return GrainContact::force<D, Energy>(c, g, s);  // never bonded, or broken
    ContactForce<D> out;
    const auto t = GluedTrial<D>::of(c, g, s.fs, s.gap0);
    const double vn = t.vn;
    const Vec<D>& vs = t.vs;
    double fn = t.fn;
    Vec<D> fs = t.fs;
    const double fs_mag = fs.norm();
    const double up_max = plastic_limit(c, s);
    // Both regimes bound a magnitude m of the trial force by base + h (U_p,max − U_p): the strengths fall
    // linearly to zero at U_p,max (3.48). e is the elastic displacement along the force: returning the force
    // by a factor r turns (1 − r) e of it into plastic displacement (3.45)–(3.46).
    const bool tension = fn < 0;
    double m, base, h, e;
    CrackMode mode;
    if (tension) {
      m = std::sqrt(fn * fn + fs_mag * fs_mag);                 // Tang (3.43)
      const double a = std::atan2(fs_mag, -fn) / (0.5 * M_PI);  // 2α/π
      h = ((1.0 - a) * s.normal + a * s.shear) / up_max;        // Tang (3.42)
      base = 0.0;
      e = std::sqrt(fn * fn / (c.kn * c.kn) + fs_mag * fs_mag / (c.ks * c.ks));
      mode = fs_mag < -fn ? CrackMode::Tensile : CrackMode::Shear;  // α < π/4: opened rather than slid
    } else {
      m = fs_mag;
      base = c.mu * fn;  // Tang (3.47)
      h = s.shear / up_max;
      e = fs_mag / c.ks;
      mode = CrackMode::Shear;
    }
    const double limit = base + h * (up_max - s.up);
    if (m <= limit) {  // Tang (3.44): holds elastically
      s.fs = fs;
      out.force = fn * g.n + fs;
      if (c.zeta > 0) Linear::add_dashpots<D, Energy>(c, g, vn, vs, false, out);
      return out;
    }
    // Yields. The returned force r m must sit on the limit softened by the plastic displacement the return
    // itself makes, r m = limit − h (1 − r) e: solved exactly, as the limit is linear in U_p, so the force
    // stays on the softening line whatever the step. With m ≤ h e (a limit shorter than the elastic
    // displacement at the peak) the softening branch would snap back: the bond breaks at once.
    const double fn_trial = fn;
    const Vec<D> fs_trial = fs;
    const double denom = m - h * e;
    const double r = denom > 0 ? (limit - h * e) / denom : 0.0;
    const double dup = (1.0 - r) * e;
    if (denom > 0 && s.up + dup < up_max) {
      if (s.up == 0) out.event = {mode, CrackKind::Yield};
      s.up += dup;
      fs *= r;
      if (tension) {  // the plastic flow follows the force (3.46): the normal spring's rest gap widens too
        s.gap0 += (r - 1.0) * fn / c.kn;
        fn *= r;
      }
      if constexpr (Energy) out.fractured += returned_energy(c, g, fn_trial, fs_trial, fn, fs);
      s.fs = fs;
      out.force = fn * g.n + fs;
      // The shear dashpot rests while the bond yields, as while a contact slides.
      if (c.zeta > 0) Linear::add_dashpots<D, Energy>(c, g, vn, vs, true, out);
      return out;
    }
    // Broken (U_p = U_p,max, no strength left): a linear contact with slip from this force pass on. A break
    // supersedes a first yield in the same step. What the springs held beyond what an unbonded contact can
    // hold is released with the crack.
    out.event = {mode, CrackKind::Break};
    s = State<D>{};
    if (g.overlap <= 0) {  // apart: no force at all
      if constexpr (Energy) out.fractured += returned_energy<D>(c, g, fn_trial, fs_trial, 0.0, Vec<D>::Zero());
      return out;
    }
    fn = c.kn * g.overlap;
    const double fs_max = c.mu * fn;  // Tang (3.36)
    const bool slipping = fs_mag > fs_max;
    if (slipping) fs *= fs_max / fs_mag;
    if constexpr (Energy) out.fractured += returned_energy(c, g, fn_trial, fs_trial, fn, fs);
    s.fs = fs;
    out.force = fn * g.n + fs;
    if (c.zeta > 0) Linear::add_dashpots<D, Energy>(c, g, vn, vs, slipping, out);
    return out;
  }

  // The energy a return from the trial force F_t = (fn_t, fs_t) to F = (fn, fs) dissipates. The engine books
  // the work of a step with the mean of the forces of its two force passes, −½(F_prev + F)·Δx (F on B,
  // Δx = v_rel Δt the step's relative motion); the trial springs stored −½(F_prev + F_t)·Δx. So the return
  // dissipates the strain energy between trial and returned force less what was never booked,
  // −½(F_t − F)·Δx: together ½(F_prev + F)·ΔU_p, the trapezoid rule along the plastic displacement (in
  // steady sliding it is Linear's slip work, 3.77). The strain energy difference alone would leave
  // −k_n Δx / F_c^n of the work in the balance (one elastic loading step in N: −1e-3 in
  // tests/softening_bond_single.cpp, and F·ΔU_p with the returned force +2.5e-4); this closes it to round-off.
  template <int D>
  static double returned_energy(const Coeffs& c, const ContactGeometry<D>& g, double fn_t, const Vec<D>& fs_t,
                                double fn, const Vec<D>& fs) {
    const double strain = 0.5 * ((fn_t * fn_t - fn * fn) / c.kn + (fs_t.squaredNorm() - fs.squaredNorm()) / c.ks);
    return strain + 0.5 * ((fn_t - fn) * g.n + (fs_t - fs)).dot(g.v_rel) * g.dt;
  }
};

// Compiled in softening_bond.cpp.
extern template class ContactSet<SofteningBond, 2>;
extern template class ContactSet<SofteningBond, 3>;

}  // namespace mc
