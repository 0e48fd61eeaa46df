// Scene keys of the Concrete Particle Model ([[contacts]] with model = "cpm"); the defaults are the document's
// recommended values (ε_s = −3e-3, K̃_s = 0.3, Y_0 = 0.1, k_T/k_N = 0.2, R_I = 1.5), viscosity off.
#include "contact_models/cpm.hpp"

#include "engine/contact_registry.hpp"

namespace mc {

ModelSpec cpm_model(const Table& t) {
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
    t.fail("confinement", "lies beyond the hardening stress k_N ε_s, where hardening_modulus_ratio = 0 gives no strain "
                          "for it; raise hardening_modulus_ratio above 0 or lower the confinement");
  return model_spec<Cpm>(p);
}

}  // namespace mc
