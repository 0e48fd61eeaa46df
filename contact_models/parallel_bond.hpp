// Parallel bond (Potyondy & Cundall 2004; Tang 2013 eqs. 3.37–3.41) acting beside a linear contact with slip:
// a short elastic beam of radius R̄ = λ̄ min(R_A, R_B) glued between the particles carries normal and shear force,
// twisting (3D) and bending moments, incrementally; it breaks when the beam's maximum tensile or shear stress
// reaches its strength. After the break the pair is a plain linear contact with slip.
#pragma once
#include <cmath>
#include <cstdint>
#include <type_traits>

#include "contact_models/bond_family.hpp"
#include "contact_models/linear.hpp"
#include "engine/contact_geometry.hpp"
#include "engine/contact_set.hpp"

namespace mc {

// Its keys, units, ranges and defaults: ParallelBond::keys() (parallel_bond.cpp).
struct ParallelBondParams {
  LinearParams contact;                 // the grain contact in parallel (Tang 3.38: k_n = 2tE_c / 4RE_c)
  double bond_radius_multiplier = 1.0;  // λ̄ [-], Tang (3.40)
  Scatter bond_modulus;                 // Ē_c [Pa]: k̄_n = Ē_c / (R_A + R_B), Tang (3.38); per bond (§8.1.2)
  double bond_kn_ks_ratio = 1.0;        // k̄_n / k̄_s [-]
  Scatter bond_tensile_strength;        // σ̄_c [Pa], drawn per bond (Tang Table 5.1, 8.4)
  Scatter bond_shear_strength;          // τ̄_c [Pa], likewise
};

// Beam section of a bond, Tang (3.39): area, second moment, polar moment (2D: t = 1 m, J unused).
template <int D>
struct BondSection {
  double radius, area, inertia, polar;
  static BondSection of(double lambda, double ra, double rb) {
    const double r = lambda * std::min(ra, rb);  // Tang (3.40)
    if constexpr (D == 2)
      return {r, 2.0 * r, 2.0 / 3.0 * r * r * r, 0.0};
    else
      return {r, M_PI * r * r, 0.25 * M_PI * r * r * r * r, 0.5 * M_PI * r * r * r * r};
  }
};

struct ParallelBond {
  static constexpr const char* name = "parallel_bond";
  using Params = ParallelBondParams;
  static const KeyTable& keys();
  static double damping_ratio(const Params& p) { return p.contact.damping_ratio; }
  // What the force pass rewrites every step.
  template <int D>
  struct History {
    Vec<D> fs = Vec<D>::Zero();       // linear contact shear force [N]
    Vec<D> bond_fs = Vec<D>::Zero();  // F̄^s [N]
    Rot<D> bond_ms = Rot<D>::Zero();  // M̄^s, bending [N m] (2D: the only moment)
    double bond_fn = 0;               // F̄^n [N], positive in compression
    double bond_mn = 0;               // M̄^n, twisting [N m] (3D)
  };
  // What is drawn when the pair bonds, and reset when the bond breaks; the default: no bond.
  template <int D>
  struct Properties {
    double stiffness = 1;  // this bond's Ē_c over the scene's bond_modulus (heterogeneity, Tang §8.1.2)
    // This bond's strengths σ̄_c, τ̄_c [Pa]; 0: no bond (never bonded or broken). Drawn numbers, in single
    // precision, as 6e-8 of a strength is far below its scatter: 8 bytes less per pair.
    float tensile = 0, shear = 0;
  };
  // In 3D the contact set keeps the two parts in two arrays (engine/state_columns.hpp), so that the force pass
  // writes 88 bytes per bond instead of 104. In 2D the history of 7 doubles would be padded to 8 by Vec<2>'s
  // 16-byte alignment, and two floats would leave 8 bytes of padding too: the state stays one array of 10 doubles.
  template <int D>
  struct Split : History<D>, Properties<D> {};
  template <int D>
  struct Whole {
    Vec<D> fs = Vec<D>::Zero(), bond_fs = Vec<D>::Zero();
    Rot<D> bond_ms = Rot<D>::Zero();
    double bond_fn = 0, bond_mn = 0, stiffness = 1, tensile = 0, shear = 0;
  };
  template <int D>
  using State = std::conditional_t<D == 3, Split<D>, Whole<D>>;
  // The state of a pair that holds no bond: its grain contact's shear force alone.
  template <int D>
  static State<D> unbonded(const State<D>& s) {
    State<D> u;
    u.fs = s.fs;
    return u;
  }
  // What the force pass needs of a pair, computed every step from the radii (cheaper than storing it: two
  // divisions and a few products, against 56 more bytes per bond to stream).
  struct Coeffs {
    Linear::Coeffs contact;
    double kn_a, ks_a;       // k̄_n A, k̄_s A [N/m], Tang (3.37)
    double kn_i, ks_j;       // k̄_n I, k̄_s J [N m/rad]
    double inv_a, r_i, r_j;  // 1/A, R̄/I, R̄/J: stress per unit force and moment, Tang (3.41)
  };

  // The beam's arithmetic in 3D, written once over the number type N: double for one contact (force), Lane for
  // kLanes contacts at once (parallel_bond_lanes.hpp), V its 3-vector; the same operations in the same order give
  // the same bits. Its section and stiffnesses from the radii, 1/(R_A + R_B) given: Tang (3.37)–(3.41), A = πR̄²,
  // I = πR̄⁴/4, J = πR̄⁴/2.
  template <class N>
  struct Beam {
    N kn_a, ks_a, kn_i, ks_j, inv_a, r_i, r_j;  // as Coeffs
  };
  template <class N>
  [[gnu::always_inline]] static Beam<N> beam(const Params& p, const N& ra, const N& rb, const N& inv_sum) {
    const N kn = p.bond_modulus.mean * inv_sum;                                  // Tang (3.38)
    const N ks = kn * (1.0 / p.bond_kn_ks_ratio);                                // the reciprocal is hoisted
    const N r = p.bond_radius_multiplier * min_of(ra, rb), inv_r = 1.0 / r;     // Tang (3.40)
    const N r4 = r * r * r * r, inv_r3 = inv_r * inv_r * inv_r;
    return {kn * M_PI * r * r,     ks * M_PI * r * r,     kn * 0.25 * M_PI * r4,  ks * 0.5 * M_PI * r4,
            inv_r * inv_r * M_1_PI, 4.0 * M_1_PI * inv_r3, 2.0 * M_1_PI * inv_r3};
  }
  // Tang (3.37) in 3D: this step's increments from the relative motion (normal speed vn, shear velocity vs, relative
  // spin w_rel), the shear force and the bending moment turned with the contact plane by `carry`.
  template <class N, class V, class Carry>
  [[gnu::always_inline]] static void load_beam(const Beam<N>& c, const V& n, const N& vn, const V& vs, const V& w_rel,
                                               const N& kdt, N& fn, V& fs, N& mn, V& ms, Carry&& carry) {
    fn = fn - c.kn_a * vn * kdt;
    fs = carry(fs) - c.ks_a * vs * kdt;
    const N wn = dot(w_rel, n);
    mn = mn - c.ks_j * wn * kdt;
    ms = carry(ms) - c.kn_i * (w_rel - wn * n) * kdt;
  }
  // Tang (3.41) without square roots: a stress |X|k (|X|² = x2, k per unit of X) reaches what the strength leaves,
  // `need`, when need ≤ 0 or x2 k² ≥ need².
  template <class N>
  [[gnu::always_inline]] static auto exceeds(const N& need, const N& x2, const N& k) {
    return need <= 0.0 || x2 * (k * k) >= need * need;
  }

  template <int D>
  static Coeffs pair(const Params& p, double ra, double rb, double fa = 1, double fb = 1) {
    const double inv_sum = 1.0 / (ra + rb);
    // The grain contact (Linear::pair), sharing 1/(R_A + R_B) when the particles have no stiffness factors.
    const Linear::Coeffs lc = fa == 1 && fb == 1 ? Linear::pair_from<D>(p.contact, D == 2 ? 0.5 : ra * rb * inv_sum)
                                                 : Linear::pair<D>(p.contact, ra, rb, fa, fb);
    if constexpr (D == 2) {  // A = 2R̄, I = 2R̄³/3 (t = 1 m), Tang (3.39)
      const double kn = p.bond_modulus.mean * inv_sum, ks = kn * (1.0 / p.bond_kn_ks_ratio);
      const double r = p.bond_radius_multiplier * std::min(ra, rb), inv_r = 1.0 / r;
      return {lc, kn * 2 * r, ks * 2 * r, kn * (2.0 / 3.0) * r * r * r, 0.0, 0.5 * inv_r, 1.5 * inv_r * inv_r, 0.0};
    } else {
      const Beam<double> b = beam(p, ra, rb, inv_sum);
      return {lc, b.kn_a, b.ks_a, b.kn_i, b.ks_j, b.inv_a, b.r_i, b.r_j};
    }
  }
  template <int D>
  static Coeffs wall(const Params& p, const WallMaterial& w, double rb, double fb = 1) {
    return {Linear::wall<D>(p.contact, w, rb, fb), 0, 0, 0, 0, 0, 0, 0};  // walls are never bonded
  }

  static constexpr bool bondable = true;

  template <int D>
  static bool bonded(const State<D>& s) {
    return s.tensile > 0;
  }

  // A new bond: stress-free, with its own strengths drawn from the scene's distributions (Tang Table 5.1).
  template <int D, class Normal>
  static void install(const Params& p, const ContactGeometry<D>&, State<D>& s, Normal& normal) {
    s = unbonded<D>(s);
    s.stiffness = normal(p.bond_modulus) / p.bond_modulus.mean;
    using Strength = decltype(s.tensile);
    s.tensile = static_cast<Strength>(normal(p.bond_tensile_strength));
    s.shear = static_cast<Strength>(normal(p.bond_shear_strength));
  }

  // Tang (3.41): the beam's largest tensile stress −F_n/A + |M|R̄/I and shear stress |F_s|/A + |M_n|R̄/J against
  // the strengths.
  template <int D>
  [[gnu::always_inline]] static bool breaks_in_tension(const Coeffs& c, const State<D>& s) {
    return exceeds<double>(s.tensile + s.bond_fn * c.inv_a, s.bond_ms.squaredNorm(), c.r_i);
  }
  template <int D>
  [[gnu::always_inline]] static bool breaks_in_shear(const Coeffs& c, const State<D>& s) {
    double need = s.shear;
    if constexpr (D == 3) need = need - abs_of(s.bond_mn) * c.r_j;
    return exceeds<double>(need, s.bond_fs.squaredNorm(), c.inv_a);
  }

  template <int D, bool Energy>
  [[gnu::always_inline]] static ContactForce<D> force(const Coeffs& c, const ContactGeometry<D>& g, State<D>& s) {
    ContactForce<D> out = GrainContact::force<D, Energy>(c.contact, g, s);  // the grain contact, in parallel
    if (!bonded<D>(s)) return out;
    const double dt = g.dt;
    const State<D> before = s;
    const double vn = g.v_rel.dot(g.n);
    const Vec<D> vs = g.v_rel - vn * g.n;
    // Tang (3.37), increments from the relative motion of this step; the shear force and the bending moment
    // turn with the contact plane.
    const double kdt = s.stiffness * dt;
    if constexpr (D == 2) {
      s.bond_fn -= c.kn_a * vn * kdt;
      s.bond_fs = carry_shear<2>(s.bond_fs, g.n, g.spin_n, dt) - c.ks_a * vs * kdt;
      s.bond_ms -= c.kn_i * g.w_rel * kdt;
    } else {
      const Beam<double> b{c.kn_a, c.ks_a, c.kn_i, c.ks_j, c.inv_a, c.r_i, c.r_j};
      load_beam(b, g.n, vn, vs, g.w_rel, kdt, s.bond_fn, s.bond_fs, s.bond_mn, s.bond_ms,
                [&](const Vec<3>& v) { return carry_shear<3>(v, g.n, g.spin_n, dt); });
    }
    if (breaks_in_tension<D>(c, s)) [[unlikely]]
      out.event.mode = CrackMode::Tensile;
    else if (breaks_in_shear<D>(c, s)) [[unlikely]]
      out.event.mode = CrackMode::Shear;
    if (out.event.mode != CrackMode::None) [[unlikely]] {
      if constexpr (Energy) out.fractured += bond_energy<D>(c, before, s);  // released with the crack
      s = unbonded<D>(s);
      return out;
    }
    out.force += s.bond_fn * g.n + s.bond_fs;
    if constexpr (D == 2)
      out.moment += s.bond_ms;
    else
      out.moment += s.bond_mn * g.n + s.bond_ms;
    return out;
  }

  template <int D>
  static ContactStiffness stiffness(const Coeffs& c, const ContactGeometry<D>& g, const State<D>& s) {
    ContactStiffness k = GrainContact::stiffness<D>(c.contact, g, s);
    if (!bonded<D>(s)) return k;
    k.normal += c.kn_a * s.stiffness;
    k.shear += c.ks_a * s.stiffness;
    k.rotational += (c.kn_i + c.ks_j) * s.stiffness;
    return k;
  }

  // Tang (3.75), with the twisting term in 3D: bond_energy(c, s, s). With two states, ½ Σ F_a F_b / K: the
  // energy a bond releases when it breaks in the force pass that took it from a to b. Central differences
  // conserve ½ m v(t−Δt/2)·v(t+Δt/2) + U(x(t)); a spring whose force vanishes at t has, by that identity,
  // stored ½ K x(t−Δt) x(t), not ½ K x(t)²: the difference is O(Δt) per break and adds up over a crack.
  template <int D>
  static double bond_energy(const Coeffs& c, const State<D>& a, const State<D>& b) {
    double e = a.bond_fn * b.bond_fn / c.kn_a + a.bond_fs.dot(b.bond_fs) / c.ks_a + a.bond_ms.dot(b.bond_ms) / c.kn_i;
    if constexpr (D == 3) e += a.bond_mn * b.bond_mn / c.ks_j;
    return 0.5 * e / a.stiffness;
  }
  template <int D>
  static double strain_energy_bond(const Coeffs& c, const State<D>& s) {
    return bond_energy<D>(c, s, s);
  }
  template <int D>
  static double strain_energy(const Coeffs& c, const ContactGeometry<D>& g, const State<D>& s) {
    return GrainContact::strain_energy<D>(c.contact, g, s) + (bonded<D>(s) ? strain_energy_bond<D>(c, s) : 0.0);
  }
  template <int D>
  static double released_energy(const Coeffs& c, const State<D>& s) {
    return GrainContact::released_energy<D>(c.contact, s);
  }
  template <int D>
  static bool persistent(const State<D>& s) {
    return bonded<D>(s);
  }
};

// Checkpoints copy states as bytes: no padding, whose bytes would be undetermined.
static_assert(sizeof(ParallelBond::State<2>) == 10 * sizeof(double) &&
              sizeof(ParallelBond::State<3>) == 13 * sizeof(double));
// The 3D contact sets keep history and properties apart (engine/state_columns.hpp); the 2D ones keep states whole.
static_assert(SplitState<ParallelBond, 3> && !SplitState<ParallelBond, 2>);

// Compiled in parallel_bond.cpp.
extern template class ContactSet<ParallelBond, 2>;
extern template class ContactSet<ParallelBond, 3>;

}  // namespace mc
