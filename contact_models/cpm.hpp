// Concrete Particle Model (CPM; Šmilauer 2010, the Yade CpmMat law, seed 002): a contact between two spheres
// carries stresses σ_N, σ_T on an equivalent cross-section A = π min(r_a, r_b)², from strains measured over the
// pair's reference length L (the centre distance when the contact was made): ε_N = (d − L)/L, tension positive,
// and a total shear strain ε_T that turns with the contact plane. Tension damages the contact (ω = g(κ),
// exponential softening, secant unloading), compression never does but hardens plastically beyond ε_s, shear
// is bounded by a linear yield surface in tension and a logarithmic one in compression. Optional visco-damage
// and visco-plasticity make the law rate-dependent; an isotropic confinement σ_0 can be applied at the contact.
//
// Cohesive contacts are made once, at the start, between spheres with d ≤ R_I (r_a + r_b); they live (and hold
// their pair) until damaged to break_damage. Spheres that meet later get non-cohesive contacts: fully damaged
// from the start (ω = 1), measured from touching (L = r_a + r_b), gone when the spheres part.
//
// Evaluation order: the document's "Contact model summary", steps 1–4, then σ_N ← σ_N − σ_0.
#pragma once
#include <algorithm>
#include <cmath>

#include "contact_models/linear.hpp"  // Linear::series: a wall's springs in series with the ball's
#include "engine/contact_geometry.hpp"
#include "engine/contact_set.hpp"

namespace mc {

// The shape of the yield surface in compression (Šmilauer (23) and "Confinement extension").
enum class CpmYield { Logarithmic, Linear };

// Its keys, units, ranges and defaults (the document's recommended values, viscosity off): Cpm::keys() (cpm.cpp).
struct CpmParams {
  double modulus = kNaN;                    // k_N [Pa], normal modulus: the particle material's E (Yade CpmMat.young)
  double kt_kn_ratio = 0.2;                 // k_T/k_N [-] (Yade CpmMat.poisson)
  double crack_onset_strain = kNaN;         // ε_0 [-], limit elastic strain (15)–(16)
  double relative_ductility = kNaN;         // ε_f/ε_0 [-]
  double cohesion = kNaN;                   // c_T0 [Pa], undamaged shear cohesion (23)
  double tan_friction = kNaN;               // tan φ [-]: the key is the angle φ, `friction_angle`
  bool compression_hardening = true;        // compressive plasticity: off as in Yade's public CpmMat (epsSoft ≥ 0)
  double hardening_strain = -3e-3;          // ε_s [-] (< 0), where the hardening branch begins
  double hardening_modulus_ratio = 0.3;     // K̃_s [-], its tangent modulus over k_N
  CpmYield compression_yield = CpmYield::Logarithmic;  // linear: (23) everywhere
  double yield_log_speed = 0.1;             // Y_0 [-]
  double damage_time = 0;                   // τ_d [s], visco-damage (18); 0: off
  double damage_rate_exponent = 0.3;        // M_d [-]
  double plastic_time = 0;                  // τ_pl [s], visco-plasticity; 0: off
  double plastic_rate_exponent = 0.3;       // M_pl [-]
  double confinement = 0;                   // σ_0 [Pa] (≤ 0), isotropic confinement at contact level
  bool never_damage = false;                // ω = 0 on cohesive contacts, for elastic calibration
  double interaction_radius = 1.5;          // R_I [-]: cohesive contacts where d ≤ R_I (r_a + r_b) at the start
  double break_damage = 1.0;                // ω at which a cohesive contact in tension breaks; 1: never (Yade's default)
};

// Šmilauer (22) and its visco-plastic twin: the root of ln(e^β + c e^{Mβ}) = 0 for c, M > 0. The function is
// convex, increasing and positive at β = 0, so Newton's method from β = 0 falls monotonically onto the unique
// (negative) root. It stops at |f| < 1e-12 (β is an exponent: the update e^β is then exact to 1e-12) or after
// 60 steps; from above, an unconverged β errs on the side of the step's elastic trial (less relaxation).
inline double cpm_solve_beta(double c, double m) {
  double b = 0;
  for (int i = 0; i < 60; ++i) {
    const double eb = std::exp(b), ec = c * std::exp(m * b), a = eb + ec;
    const double f = std::log(a);
    if (std::abs(f) < 1e-12) break;
    b -= f * a / (eb + m * ec);
  }
  return b;
}

struct Cpm {
  static constexpr const char* name = "cpm";
  using Params = CpmParams;
  static const KeyTable& keys();
  static double damping_ratio(const Params&) { return 0.0; }  // no dashpots: damage, plasticity and viscosity
  template <int D>
  struct State {
    Vec<D> eps_t = Vec<D>::Zero();  // ε_T, total shear strain on the contact plane (B relative to A)
    double length = 0;              // L [m], reference length of a cohesive contact; 0: non-cohesive
    double kappa = 0;               // κ, the largest ⟨ε_N − ε_N^pl⟩ so far (16)
    double eps_pl = 0;              // ε_N^pl, normal plastic strain (≤ 0, compressive hardening)
    double eps_d = 0;               // ε_d, damage strain of the visco-damage law (17)
  };
  struct Coeffs {
    double area;      // A [m²]
    double length;    // L of a non-cohesive contact: r_a + r_b (a wall: r_b) [m]
    double kn, kt;    // k_N, k_T [Pa]
    double tan_phi;   // tan φ (a wall: its friction coefficient)
    double cohesion;  // c_T0 [Pa] (a wall: 0, and a linear surface)
    double eps_conf;  // the strain shift of the confinement σ_0 (step 1)
    const Params* p;
  };

  // Šmilauer, "Isotropic confinement": the strain that σ_0 alone would cause, on the hardening branch if
  // σ_0 < k_N ε_s.
  static double confinement_strain(const Params& p) {
    if (p.confinement == 0) return 0;
    const double kns = p.modulus * p.hardening_strain;
    if (!p.compression_hardening || p.confinement > kns) return p.confinement / p.modulus;
    return p.hardening_strain + (p.confinement - kns) / (p.modulus * p.hardening_modulus_ratio);
  }

  // The law's arithmetic, written once over the number type N: double for one contact (force), Lane for kLanes
  // contacts at once (cpm_lanes.hpp); the same operations in the same order give the same bits. The two differ in
  // control only: one contact branches, the lanes choose lane by lane and hand rare events back.
  //
  // A = π min(r_a, r_b)² (Yade's crossSection); in 2D a strip 2 min(r) × 1 m, though scenes are refused in 2D.
  // Particles with stiffness factors f scale k_N and k_T by their harmonic mean 2 f_a f_b/(f_a + f_b).
  template <class N>
  struct Section {
    N area, kn, kt;
  };
  template <int D, class N>
  [[gnu::always_inline]] static Section<N> section(const Params& p, const N& ra, const N& rb, const N& fa,
                                                   const N& fb) {
    const N r = min_of(ra, rb);
    const N kn = p.modulus * pick(fa == fb, fa, 2.0 * fa * fb / (fa + fb));
    if constexpr (D == 2)
      return {2.0 * r, kn, kn * p.kt_kn_ratio};
    else
      return {M_PI * r * r, kn, kn * p.kt_kn_ratio};
  }
  // Step 1: the normal strain from the distance, over L from L (cohesive) or from touching (r_a + r_b).
  template <class N, class M>
  [[gnu::always_inline]] static N normal_strain(const M& cohesive, const N& ra, const N& rb, const N& overlap,
                                                const N& len, const N& inv_len) {
    return pick(cohesive, (ra + rb - overlap - len) * inv_len, -overlap * inv_len);
  }
  // Šmilauer (15): σ_N = (1 − ω) k_N ε in tension, k_N ε in compression (damage only in tension).
  template <class N>
  [[gnu::always_inline]] static N normal_stress(const N& el, const N& omega, const N& kn) {
    return pick(el > 0.0, 1.0 - omega, N(1.0)) * kn * el;
  }
  // The hardening branch at the total strain ε: σ_Ns = k_N (ε_s + K̃_s (ε_N − ε_s)).
  template <class N>
  [[gnu::always_inline]] static N hardening_stress(const Params& p, const N& kn, const N& eps) {
    return kn * (p.hardening_strain + p.hardening_modulus_ratio * (eps - p.hardening_strain));
  }
  // The linear yield surface (23), never below 0: max(0, c_T0 (1 − ω) − σ_N tan φ).
  template <class N>
  [[gnu::always_inline]] static N linear_radius(double cohesion, double tan_phi, const N& sn, const N& omega) {
    const N r = cohesion * (1.0 - omega) - sn * tan_phi;
    return pick(0.0 < r, r, N(0.0));
  }
  // A lower bound of the logarithmic radius in compression, ln(1 + x) ≥ x/(1 + x) with x = −σ_N/(c_T0 Y_0),
  // lowered by 1e-9, far beyond the few roundings of either side (may_yield).
  template <class N>
  [[gnu::always_inline]] static N log_radius_floor(double cohesion, double tan_phi, double y0, const N& sn,
                                                   const N& omega) {
    const N x = -sn / (cohesion * y0);
    return (cohesion * (1.0 - omega) + cohesion * y0 * tan_phi * (x / (1.0 + x))) * (1.0 - 1e-9);
  }

  template <int D>
  static Coeffs pair(const Params& p, double ra, double rb, double fa = 1, double fb = 1) {
    const Section<double> s = section<D>(p, ra, rb, fa, fb);
    return {s.area, ra + rb, s.kn, s.kt, p.tan_friction, p.cohesion, confinement_strain(p), &p};
  }
  // A wall is a non-cohesive partner (Yade: L = A's radius, A = π r²): the ball's springs k_N A/r in series
  // with the wall's, Coulomb friction with the wall's coefficient, no confinement.
  template <int D>
  static Coeffs wall(const Params& p, const WallMaterial& w, double rb, double fb = 1) {
    const double area = D == 2 ? 2.0 * rb : M_PI * rb * rb;
    const double to_force = area / rb;  // modulus → N/m over L = r_b
    const double kn = Linear::series(p.modulus * fb * to_force, w.kn) / to_force;
    const double kt = Linear::series(p.modulus * p.kt_kn_ratio * fb * to_force, w.ks) / to_force;
    return {area, rb, kn, kt, w.friction, 0.0, 0.0, &p};
  }

  static constexpr bool bondable = true;
  static constexpr bool yields = true;   // first damage goes to the crack log (kind Yield)
  static constexpr bool only_3d = true;  // the document's law and calibration are for spheres
  static double interaction_radius(const Params& p) { return p.interaction_radius; }
  template <int D>
  static bool bonded(const State<D>& s) {
    return s.length > 0;
  }
  template <int D>
  static bool persistent(const State<D>& s) {
    return bonded(s);
  }

  // A cohesive contact, virgin and stress-free at the distance where it is made (Yade's refLength).
  template <int D, class Normal>
  static void install(const Params&, const ContactGeometry<D>& g, State<D>& s, Normal&) {
    s = State<D>{};
    s.length = g.r_a + g.r_b - g.overlap;
  }

  // ω = g(κ) = 1 − (ε_0/κ) exp(−(κ − ε_0)/ε_f) for κ > ε_0, else 0. Šmilauer (16) prints ε_f/κ in front of the
  // exponential; that would give g(ε_0) = 1 − ε_f/ε_0 < 0, outside ⟨0, 1⟩, whereas ε_0/κ gives g(ε_0) = 0 and
  // the softening σ = k_N ε_0 exp(−(κ − ε_0)/ε_f) of Fig. 16 (and is Yade's funcG).
  static double damage(const Params& p, double kappa) {
    const double e0 = p.crack_onset_strain;
    if (kappa <= e0) return 0;
    return 1.0 - e0 / kappa * std::exp(-(kappa - e0) / (e0 * p.relative_ductility));
  }
  // Radius r_pl of the yield surface at σ_N (step 3): linear (23) in tension, logarithmic in compression
  // ("Confinement extension", C¹ at σ_N = 0; Y_0 → ∞ gives back the linear one). Never below 0.
  static double yield_radius(const Coeffs& c, double sn, double omega) {
    if (sn >= 0 || c.p->compression_yield == CpmYield::Linear || c.cohesion == 0)
      return linear_radius(c.cohesion, c.tan_phi, sn, omega);
    const double y0 = c.p->yield_log_speed;
    return c.cohesion * (1.0 - omega) + c.cohesion * y0 * c.tan_phi * std::log1p(-sn / (c.cohesion * y0));
  }

  // False when the trial shear stress √st2 lies inside a lower bound of r_pl, so that yield_radius (a logarithm,
  // a fifth of a CPM step where most contacts are in compression) need not be taken: ln(1 + x) ≥ x/(1 + x). The
  // bound is lowered by 1e-9, far beyond the few roundings of either side, so that it never passes a stress that
  // yield_radius as computed would not.
  static bool may_yield(const Coeffs& c, double sn, double omega, double st2) {
    if (sn >= 0 || c.p->compression_yield == CpmYield::Linear || c.cohesion == 0) return true;  // no logarithm to save
    const double low = log_radius_floor(c.cohesion, c.tan_phi, c.p->yield_log_speed, sn, omega);
    return st2 > low * low;
  }

  template <int D, bool Energy>
  [[gnu::always_inline]] static ContactForce<D> force(const Coeffs& c, const ContactGeometry<D>& g, State<D>& s) {
    ContactForce<D> out;
    const bool cohesive = bonded(s);
    if (!cohesive && g.overlap <= 0) {  // non-cohesive and apart: no force; the history starts anew at the next touch
      if constexpr (Energy) out.dissipated += released_energy<D>(c, s);
      s = State<D>{};
      return out;
    }
    const Params& p = *c.p;
    const double len = cohesive ? s.length : c.length;
    const double inv_len = 1.0 / len;
    const double vn = g.v_rel.dot(g.n);
    const Vec<D> vs = g.v_rel - vn * g.n;
    const double volume = c.area * len;  // stresses × strains × volume: energies
    // Strains: the normal one from the distance, the shear one incremented by this step's tangential motion.
    Vec<D> et = carry_shear<D>(s.eps_t, g.n, g.spin_n, g.dt) + vs * (g.dt * inv_len);
    const double eps_raw = normal_strain(cohesive, g.r_a, g.r_b, g.overlap, len, inv_len);
    // 1. Isotropic confinement: the strain σ_0 would cause is added here, σ_0 taken off at the end.
    const double eps = eps_raw + c.eps_conf;
    // 2. Normal stress. κ follows the elastic part of the strain in tension (ξ_1 = 0: no shear contribution).
    const double el = eps - s.eps_pl;
    double omega = 1.0;  // non-cohesive
    double omega_before = 1.0;
    if (cohesive) {
      if (p.never_damage) {
        omega = omega_before = 0.0;
      } else {
        if constexpr (Energy) omega_before = damage(p, s.kappa);
        if (el > s.kappa) {
          if (el > p.crack_onset_strain && s.kappa <= p.crack_onset_strain)
            out.event = {CrackMode::Tensile, CrackKind::Yield};
          s.kappa = el;
        }
        omega = damage(p, s.kappa);
      }
    }
    double sn = normal_stress(el, omega, c.kn);
    if constexpr (Energy)
      if (cohesive && el > 0) out.fractured += 0.5 * c.kn * el * el * (omega - omega_before) * volume;
    // Compressive hardening: beyond ε_s the stress follows σ_Ns = k_N (ε_s + K̃_s (ε_N − ε_s)), the excess
    // turning into plastic strain; unloading is elastic with k_N from there.
    if (p.compression_hardening && el < p.hardening_strain) {
      const double sns = hardening_stress(p, c.kn, eps);
      if (sns > sn) {
        const double dpl = (sn - sns) / c.kn;
        s.eps_pl += dpl;
        if constexpr (Energy) out.dissipated += sns * dpl * volume;
        sn = sns;
      }
    }
    // 3. Shear stress: trial k_T ε_T, radially returned onto r_pl(σ_N). The plastic strain is not stored: ε_T
    // itself is shortened to σ_T/k_T.
    const double st2 = c.kt * c.kt * et.squaredNorm();
    const double r_pl = may_yield(c, sn, omega, st2) ? yield_radius(c, sn, omega) : kInf;
    if (st2 > r_pl * r_pl) {
      const double st = std::sqrt(st2);
      double scale = r_pl / st;
      if (p.plastic_time > 0) {  // visco-plasticity: r'_pl = r_pl + c_T0 (τ_pl Δε_Tp/Δt)^M_pl
        const double m = p.plastic_rate_exponent;
        const double cc = c.cohesion * std::pow(p.plastic_time / (c.kt * g.dt), m) * std::pow(st - r_pl, m - 1.0);
        scale = 1.0 - std::exp(cpm_solve_beta(cc, m)) * (1.0 - r_pl / st);
      }
      if constexpr (Energy) out.dissipated += scale * st * (st - scale * st) / c.kt * volume;  // as Linear (3.77)
      et *= scale;
    }
    // 4. Visco-damage (cohesive contacts): the damage strain ε_d lags behind ω⟨ε_N⟩ (17); the lag is the
    // overstress σ_Nv = k_N (ω ε_N − ε_d). ⟨ε_N⟩: in compression σ_N = k_N ε_N, so ε_d = 0 there by (17).
    if (cohesive && p.damage_time > 0) {
      const double target = omega * std::max(el, 0.0);
      if (s.eps_d >= target) {
        s.eps_d = target;  // not growing: no overstress
      } else {
        // (20)–(22) with the document's coefficient c = ε_0 (1 − ω)(τ_d/Δt)^M_d (ωε_N − ε_d)^(M_d − 1) (as in
        // its summary and in Yade: the overstress (18) scaled by the undamaged fraction 1 − ω).
        const double m = p.damage_rate_exponent, y = target - s.eps_d;
        const double cc =
            p.crack_onset_strain * (1.0 - omega) * std::pow(p.damage_time / g.dt, m) * std::pow(y, m - 1.0);
        s.eps_d += y * std::exp(cpm_solve_beta(cc, m));
        const double sv = (target - s.eps_d) * c.kn;
        if constexpr (Energy) out.dissipated += sv * c.area * vn * g.dt;  // the overstress's work, Δε = v_n Δt/L
        sn += sv;
      }
    }
    sn -= p.confinement;  // σ_N' = σ_N − σ_0
    s.eps_t = et;
    out.force = -c.area * (sn * g.n + c.kt * et);  // on B: tension pulls it back towards A
    // A cohesive contact damaged to break_damage in tension is a crack: from the next step on the pair is
    // non-cohesive (it then parts, or touches again measured from touching). Its stored energy goes with it.
    if (cohesive && omega >= p.break_damage && el > 0) [[unlikely]] {
      out.event = {CrackMode::Tensile, CrackKind::Break};
      if constexpr (Energy) out.fractured += strain_energy<D>(c, g, s);
      s = State<D>{};
    }
    return out;
  }

  template <int D>
  static ContactStiffness stiffness(const Coeffs& c, const ContactGeometry<D>&, const State<D>& s) {
    const double k = c.area / (bonded(s) ? s.length : c.length);
    return {c.kn * k, c.kt * k, 0.0};
  }
  // Secant energy ½ σ_N ε_N^el + ½ k_T |ε_T|² per volume A L (unloading is secant, so all of it comes back),
  // less the work σ_0 does on the raw strain, so that its derivative is the force applied, σ_N − σ_0.
  template <int D>
  static double strain_energy(const Coeffs& c, const ContactGeometry<D>& g, const State<D>& s) {
    const bool cohesive = bonded(s);
    if (!cohesive && g.overlap <= 0) return 0;
    const double len = cohesive ? s.length : c.length;
    const double eps_raw = cohesive ? (g.r_a + g.r_b - g.overlap - len) / len : -g.overlap / len;
    const double el = eps_raw + c.eps_conf - s.eps_pl;
    const double omega = cohesive ? (c.p->never_damage ? 0.0 : damage(*c.p, s.kappa)) : 1.0;
    const double sn = normal_stress(el, omega, c.kn);
    return c.area * len * (0.5 * sn * el + 0.5 * c.kt * s.eps_t.squaredNorm() - c.p->confinement * eps_raw);
  }
  // A non-cohesive contact that opens lets its shear strain energy go.
  template <int D>
  static double released_energy(const Coeffs& c, const State<D>& s) {
    return 0.5 * c.kt * s.eps_t.squaredNorm() * c.area * c.length;
  }
};

// Compiled in cpm.cpp.
extern template class ContactSet<Cpm, 2>;
extern template class ContactSet<Cpm, 3>;

}  // namespace mc
