// Pieces the bond models share (contact_bond, softening_bond, parallel_bond), and rolling_resistance the first:
//  - GrainContact: the linear contact with Coulomb slip that a parallel bond acts beside, and that a contact or
//    softening bond becomes once broken, working on the shear force the bond's state carries (`fs`);
//  - GluedTrial: the trial forces of the springs glued at the contact point while a contact or softening bond
//    holds: normal force from the gap at bonding (tension allowed), shear force without slip.
#pragma once
#include "contact_models/linear.hpp"
#include "engine/contact_geometry.hpp"

namespace mc {

struct GrainContact {
  template <int D, bool Energy, class State>
  [[gnu::always_inline]] static ContactForce<D> force(const Linear::Coeffs& c, const ContactGeometry<D>& g, State& s) {
    Linear::State<D> ls{s.fs};
    const ContactForce<D> out = Linear::force<D, Energy>(c, g, ls);
    s.fs = ls.fs;
    return out;
  }
  template <int D, class State>
  static ContactStiffness stiffness(const Linear::Coeffs& c, const ContactGeometry<D>& g, const State& s) {
    return Linear::stiffness<D>(c, g, Linear::State<D>{s.fs});
  }
  template <int D, class State>
  static double strain_energy(const Linear::Coeffs& c, const ContactGeometry<D>& g, const State& s) {
    return Linear::strain_energy<D>(c, g, Linear::State<D>{s.fs});
  }
  template <int D, class State>
  static double released_energy(const Linear::Coeffs& c, const State& s) {
    return Linear::released_energy<D>(c, Linear::State<D>{s.fs});
  }
};

// One step of the glued springs, before the bond's strength is consulted.
template <int D>
struct GluedTrial {
  double vn;          // normal relative velocity (> 0 opening)
  Vec<D> vs;          // shear relative velocity
  double fn;          // normal force, Tang (3.9), from the gap at bonding: negative (tension) allowed
  Vec<D> fs_carried;  // last step's shear force turned into the new contact plane
  Vec<D> fs;          // the trial shear force, Tang (3.5), (3.10): no slip while bonded

  [[gnu::always_inline]] static GluedTrial of(const Linear::Coeffs& c, const ContactGeometry<D>& g, const Vec<D>& fs,
                                              double gap0) {
    GluedTrial t;
    t.vn = g.v_rel.dot(g.n);
    t.vs = g.v_rel - t.vn * g.n;
    t.fn = c.kn * (g.overlap + gap0);
    t.fs_carried = carry_shear<D>(fs, g.n, g.spin_n, g.dt);
    t.fs = t.fs_carried - c.ks * t.vs * g.dt;
    return t;
  }
};

}  // namespace mc
