#include "scene/model_keys.hpp"

#include <cmath>
#include <string>
#include <tuple>

namespace mc {

namespace {

// A bond parameter (strength, modulus) drawn per bond: `key` (mean, or the Weibull scale λ) with either
// `key_std` (normal truncated to positive values) or `key_weibull_shape` (Weibull, Tang 8.4), not both.
// Returns {mean or λ, std, shape}.
std::tuple<double, double, double> read_distribution(const Table& t, const std::string& key, Unit u) {
  const double a = t.number(key, u, Range::positive());
  const bool normal = t.has(key + "_std"), weibull = t.has(key + "_weibull_shape");
  if (normal && weibull)
    t.fail(key + "_weibull_shape", "given together with " + key +
                                       "_std: a bond parameter is drawn either from a normal "
                                       "distribution (" +
                                       key + " = mean, " + key + "_std) or from a Weibull distribution (" + key +
                                       " = scale, " + key + "_weibull_shape), not both");
  const double b = t.number(key + "_std", u, Range::non_negative(), 0.0);
  const double k = t.number(key + "_weibull_shape", Unit::None, Range::positive(), 0.0);
  return {a, b, k};
}

// The contact bond's keys, which the softening bond has too: the linear contact's, and the strengths as forces.
void read_glued_bond(const Table& t, ContactBondParams& p) {
  p.contact = read_params<Linear>(t);
  std::tie(p.normal_mean, p.normal_std, p.normal_weibull) = read_distribution(t, "bond_normal_strength", Unit::Force);
  std::tie(p.shear_mean, p.shear_std, p.shear_weibull) = read_distribution(t, "bond_shear_strength", Unit::Force);
}

}  // namespace

// Tang (3.25)–(3.26), (3.36), (3.38).
template <>
LinearParams read_params<Linear>(const Table& t) {
  LinearParams p;
  p.modulus = t.number("modulus", Unit::Pressure, Range::positive());
  p.kn_ks_ratio = t.number("kn_ks_ratio", Unit::None, Range::positive(), 1.0);
  p.friction = t.number("friction", Unit::None, Range::non_negative(), 0.0);
  p.damping_ratio = t.number("damping_ratio", Unit::None, Range::open_fraction(), 0.0);
  return p;
}

// Tang (3.27)–(3.35).
template <>
HertzMindlinParams read_params<HertzMindlin>(const Table& t) {
  HertzMindlinParams p;
  p.shear_modulus = t.number("shear_modulus", Unit::Pressure, Range::positive());
  p.poisson = t.number("poisson", Unit::None, Range{-1.0, 0.5, true, true});
  p.friction = t.number("friction", Unit::None, Range::non_negative(), 0.0);
  p.damping_ratio = t.number("damping_ratio", Unit::None, Range::open_fraction(), 0.0);
  return p;
}

// The grain contact's keys (modulus, kn_ks_ratio, friction, damping_ratio) and the bond's, prefixed "bond_"
// (Tang 3.37–3.41, Table 5.1: strengths mean ± std).
template <>
ParallelBondParams read_params<ParallelBond>(const Table& t) {
  ParallelBondParams p;
  p.contact = read_params<Linear>(t);
  p.radius_multiplier = t.number("bond_radius_multiplier", Unit::None, Range::positive(), 1.0);
  std::tie(p.modulus, p.modulus_std, p.modulus_weibull) = read_distribution(t, "bond_modulus", Unit::Pressure);
  p.kn_ks_ratio = t.number("bond_kn_ks_ratio", Unit::None, Range::positive(), 1.0);
  std::tie(p.tensile_mean, p.tensile_std, p.tensile_weibull) =
      read_distribution(t, "bond_tensile_strength", Unit::Pressure);
  std::tie(p.shear_mean, p.shear_std, p.shear_weibull) = read_distribution(t, "bond_shear_strength", Unit::Pressure);
  return p;
}

template <>
ContactBondParams read_params<ContactBond>(const Table& t) {
  ContactBondParams p;
  read_glued_bond(t, p);
  return p;
}

// The contact bond's keys, and how far it softens: bond_plastic_limit (U_p,max) or bond_fracture_energy (G_f,
// from which U_p,max = 2 G_f A / F_c^n per bond), Tang (3.42)–(3.48).
template <>
SofteningBondParams read_params<SofteningBond>(const Table& t) {
  SofteningBondParams p;
  read_glued_bond(t, p);
  // Two ways to say one thing: both would contradict each other, neither leaves the softening undefined.
  const bool limit = t.has("bond_plastic_limit"), energy = t.has("bond_fracture_energy");
  const std::string allowed =
      "the softening bond takes exactly one of bond_plastic_limit (U_p,max, a length in m) and "
      "bond_fracture_energy (G_f, an energy per area in J/m2 or N/m)";
  if (limit && energy) t.fail("bond_fracture_energy", "given together with bond_plastic_limit; " + allowed);
  if (!limit && !energy) t.fail("bond_plastic_limit", "missing; " + allowed);
  if (limit)
    p.plastic_limit = t.number("bond_plastic_limit", Unit::Length, Range::positive());
  else
    p.fracture_energy = t.number("bond_fracture_energy", Unit::EnergyPerArea, Range::positive());
  return p;
}

// The defaults are the CPM document's recommended values (ε_s = −3e-3, K̃_s = 0.3, Y_0 = 0.1, k_T/k_N = 0.2,
// R_I = 1.5), viscosity off.
template <>
CpmParams read_params<Cpm>(const Table& t) {
  CpmParams p;
  p.modulus = t.number("modulus", Unit::Pressure, Range::positive());
  p.kt_kn_ratio = t.number("kt_kn_ratio", Unit::None, Range::closed(0.0, 1.0), 0.2);
  p.crack_onset_strain = t.number("crack_onset_strain", Unit::None, Range::positive());
  p.relative_ductility = t.number("relative_ductility", Unit::None, Range::positive());
  p.cohesion = t.number("cohesion", Unit::Pressure, Range::positive());
  p.tan_friction = std::tan(t.number("friction_angle", Unit::Angle, Range{0.0, M_PI / 2, false, true}));
  p.hardening = t.boolean("compression_hardening", true);
  p.hardening_strain = t.number("hardening_strain", Unit::None, Range{-1.0, 0.0, true, true}, -3e-3);
  p.hardening_ratio = t.number("hardening_modulus_ratio", Unit::None, Range::closed(0.0, 1.0), 0.3);
  p.log_yield = t.choice("compression_yield", {"logarithmic", "linear"}, "logarithmic") == "logarithmic";
  p.yield_log_speed = t.number("yield_log_speed", Unit::None, Range::positive(), 0.1);
  p.damage_time = t.number("damage_time", Unit::Time, Range::non_negative(), 0.0);
  p.damage_rate_exponent = t.number("damage_rate_exponent", Unit::None, Range::positive(), 0.3);
  p.plastic_time = t.number("plastic_time", Unit::Time, Range::non_negative(), 0.0);
  p.plastic_rate_exponent = t.number("plastic_rate_exponent", Unit::None, Range::positive(), 0.3);
  p.confinement = t.number("confinement", Unit::Pressure, Range{-kInf, 0.0, false, false}, 0.0);
  p.never_damage = t.boolean("never_damage", false);
  p.interaction_radius = t.number("interaction_radius", Unit::None, Range::at_least(1.0), 1.5);
  p.break_damage = t.number("break_damage", Unit::None, Range{0.0, 1.0, true, false}, 1.0);
  // The confinement must not damage contacts at once (Šmilauer, "Isotropic confinement"): σ_0 ≤ 0 is checked by
  // its range; a compressive σ_0 on the hardening branch needs K̃_s > 0 to have a strain at all.
  if (p.confinement < 0 && p.hardening && p.confinement < p.modulus * p.hardening_strain && p.hardening_ratio == 0)
    t.fail("confinement",
           "lies beyond the hardening stress k_N ε_s, where hardening_modulus_ratio = 0 gives no strain "
           "for it; raise hardening_modulus_ratio above 0 or lower the confinement");
  return p;
}

}  // namespace mc
