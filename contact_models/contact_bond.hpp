// Contact bond (PFC; Tang 2013 §3.3.3, Fig. 3.6): a linear contact glued at its contact point. While the bond
// holds, the normal spring carries tension as well as compression and the shear spring does not slip; the bond
// breaks when the tensile normal force reaches its normal strength or the shear force its shear strength (both
// forces, N). Afterwards the pair is a linear contact with Coulomb slip (3.36).
#pragma once
#include <cmath>

#include "contact_models/bond_family.hpp"
#include "contact_models/linear.hpp"
#include "engine/contact_geometry.hpp"
#include "engine/contact_set.hpp"

namespace mc {

// Its keys, units, ranges and defaults: ContactBond::keys() (contact_bond.cpp).
struct ContactBondParams {
  LinearParams contact;          // springs, friction and dashpots, Tang (3.25)–(3.26), (3.38)
  Scatter bond_normal_strength;  // tensile strength F_c^n [N], drawn per bond (Tang 8.4)
  Scatter bond_shear_strength;   // shear strength F_c^s [N], likewise
};

struct ContactBond {
  static constexpr const char* name = "contact_bond";
  using Params = ContactBondParams;
  static const KeyTable& keys();
  static double damping_ratio(const Params& p) { return p.contact.damping_ratio; }
  template <int D>
  struct State {
    Vec<D> fs = Vec<D>::Zero();    // shear force on B [N]
    double normal = 0, shear = 0;  // this bond's strengths [N]; 0: no bond (never bonded, or broken)
    double gap0 = 0;               // gap when bonded [m] (≥ 0): the bonded springs are unstrained there
  };
  using Coeffs = Linear::Coeffs;

  template <int D>
  static Coeffs pair(const Params& p, double ra, double rb, double fa = 1, double fb = 1) {
    return Linear::pair<D>(p.contact, ra, rb, fa, fb);
  }
  template <int D>
  static Coeffs wall(const Params& p, const WallMaterial& w, double rb, double fb = 1) {
    return Linear::wall<D>(p.contact, w, rb, fb);
  }

  static constexpr bool bondable = true;
  template <int D>
  static bool bonded(const State<D>& s) {
    return s.normal > 0;
  }
  // A bond glues the pair where it stands: a pair bonded across a small gap (the installation tolerance) is
  // not pulled shut, its normal spring measures from that gap (PFC's reference gap). Overlapping pairs keep
  // their compression.
  template <int D, class Normal>
  static void install(const Params& p, const ContactGeometry<D>& g, State<D>& s, Normal& normal) {
    s.gap0 = std::max(0.0, -g.overlap);
    s.normal = normal(p.bond_normal_strength);
    s.shear = normal(p.bond_shear_strength);
  }

  template <int D, bool Energy>
  [[gnu::always_inline]] static ContactForce<D> force(const Coeffs& c, const ContactGeometry<D>& g, State<D>& s) {
    if (!bonded(s)) return GrainContact::force<D, Energy>(c, g, s);  // never bonded, or broken
    ContactForce<D> out;
    const auto t = GluedTrial<D>::of(c, g, s.fs, s.gap0);
    const double vn = t.vn, fn = t.fn;
    const Vec<D>& vs = t.vs;
    const Vec<D>& fs_before = t.fs_carried;
    Vec<D> fs = t.fs;
    if (-fn >= s.normal)
      out.event.mode = CrackMode::Tensile;
    else if (fs.norm() >= s.shear)
      out.event.mode = CrackMode::Shear;
    if (out.event.mode == CrackMode::None) {
      s.fs = fs;
      out.force = fn * g.n + fs;
      if (c.zeta > 0) Linear::add_dashpots<D, Energy>(c, g, vn, vs, false, out);
      return out;
    }
    // Broken: from this force pass on a linear contact with slip. What its springs held beyond what an
    // unbonded contact can hold is released with the crack. A spring whose force vanishes in this pass had
    // stored ½ F(t−Δt)·F(t)/K by the energy identity of central differences (see ParallelBond::bond_energy).
    s.normal = s.shear = s.gap0 = 0;
    const double fn_before = fn + c.kn * vn * g.dt;  // the overlap closes by v_n Δt per step
    if (g.overlap <= 0) {                            // apart: no force at all
      if constexpr (Energy) out.fractured += 0.5 * fn * fn_before / c.kn + 0.5 * fs.dot(fs_before) / c.ks;
      s.fs.setZero();
      return out;
    }
    // Touching: the normal force is the overlap's again; the gap's share of the bonded force goes with the bond.
    if constexpr (Energy) out.fractured += 0.5 * (fn - c.kn * g.overlap) * (fn_before - c.kn * g.overlap) / c.kn;
    const double fn_contact = c.kn * g.overlap;
    const double fs_max = c.mu * fn_contact, fs_mag = fs.norm();  // Tang (3.36)
    const bool slipping = fs_mag > fs_max;
    if (slipping) {
      if constexpr (Energy) out.dissipated += 0.5 * (fs_mag * fs_mag - fs_max * fs_max) / c.ks;
      fs *= fs_max / fs_mag;
    }
    s.fs = fs;
    out.force = fn_contact * g.n + fs;
    if (c.zeta > 0) Linear::add_dashpots<D, Energy>(c, g, vn, vs, slipping, out);
    return out;
  }

  template <int D>
  static ContactStiffness stiffness(const Coeffs& c, const ContactGeometry<D>&, const State<D>&) {
    return {c.kn, c.ks, 0.0};
  }
  template <int D>
  static double strain_energy(const Coeffs& c, const ContactGeometry<D>& g, const State<D>& s) {
    if (!bonded(s)) return GrainContact::strain_energy<D>(c, g, s);
    const double fn = c.kn * (g.overlap + s.gap0);
    return 0.5 * (fn * fn / c.kn + s.fs.squaredNorm() / c.ks);  // Tang (3.80), tension included
  }
  template <int D>
  static double released_energy(const Coeffs& c, const State<D>& s) {
    return GrainContact::released_energy<D>(c, s);
  }
  template <int D>
  static bool persistent(const State<D>& s) {
    return bonded(s);
  }
};

// Compiled in contact_bond.cpp.
extern template class ContactSet<ContactBond, 2>;
extern template class ContactSet<ContactBond, 3>;

}  // namespace mc
