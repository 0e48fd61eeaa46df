// The Concrete Particle Model's keys, and its contact sets compiled once here with its law in lanes (cpm_lanes.hpp);
// cpm.hpp announces them (extern template), so the registry, the preprocessor, the tests and the benchmarks share
// this one instantiation.
#include "contact_models/cpm.hpp"

#include "contact_models/cpm_lanes.hpp"

namespace mc {

namespace {

// The confinement must not damage contacts at once (Šmilauer, "Isotropic confinement"): σ_0 ≤ 0 is checked by its
// range; a compressive σ_0 on the hardening branch needs K̃_s > 0 to have a strain at all.
std::optional<KeyProblem> confinement_has_a_strain(const CpmParams& p) {
  if (p.confinement < 0 && p.compression_hardening && p.confinement < p.modulus * p.hardening_strain &&
      p.hardening_modulus_ratio == 0)
    return KeyProblem{"confinement",
                      "lies beyond the hardening stress k_N ε_s, where hardening_modulus_ratio = 0 gives no strain "
                      "for it; raise hardening_modulus_ratio above 0 or lower the confinement"};
  return std::nullopt;
}

}  // namespace

const KeyTable& Cpm::keys() {
  using P = CpmParams;
  constexpr double inf = std::numeric_limits<double>::infinity();
  static const KeyTable t = key_table<P>(
      "cpm", "[[contacts]] model = \"cpm\"",
      "The Concrete Particle Model (Šmilauer 2010, Yade's CpmMat; 3D only): stresses on the cross-section "
      "A = π min(R_A, R_B)² from strains over the pair's reference length L (the centre distance when the contact "
      "was made): ε_N = (d − L)/L, tension positive, and a total shear strain ε_T. Tension damages, "
      "σ_N = (1 − ω) k_N ε_N with ω = 1 − (ε_0/κ) exp(−(κ − ε_0)/ε_f), unloading secant; compression never damages "
      "but hardens from ε_s; shear is returned radially onto the yield surface (23). Cohesive contacts are made by "
      "[bonds] at the start between spheres with d ≤ R_I (R_A + R_B); spheres that meet later get non-cohesive "
      "contacts (ω = 1, L = R_A + R_B). The defaults are the document's recommended values.",
      {
          bound(&P::modulus, {.name = "modulus",
                             .unit = Unit::Pressure,
                             .range = Range::positive(),
                             .need = Need::Required,
                             .doc = "k_N, the normal modulus: the material's E (Yade young), (15)",
                             .example = "30 GPa"}),
          bound(&P::kt_kn_ratio, {.name = "kt_kn_ratio",
                                 .range = Range::closed(0.0, 1.0),
                                 .doc = "k_T/k_N (Yade poisson)",
                                 .example = "0.2"}),
          bound(&P::crack_onset_strain, {.name = "crack_onset_strain",
                                        .range = Range::positive(),
                                        .need = Need::Required,
                                        .doc = "ε_0, the limit elastic strain: k_N ε_0 is the contact's tensile "
                                               "strength, (15)-(16)",
                                        .example = "1e-4"}),
          bound(&P::relative_ductility, {.name = "relative_ductility",
                                        .range = Range::positive(),
                                        .need = Need::Required,
                                        .doc = "ε_f/ε_0 of the exponential softening (16)",
                                        .example = "30"}),
          bound(&P::cohesion, {.name = "cohesion",
                              .unit = Unit::Pressure,
                              .range = Range::positive(),
                              .need = Need::Required,
                              .doc = "c_T0, the undamaged shear cohesion of the yield surface (23)",
                              .example = "3 MPa"}),
          bound(&P::tan_friction, {.name = "friction_angle",
                                  .unit = Unit::Angle,
                                  .range = Range{0.0, M_PI / 2, false, true},
                                  .need = Need::Required,
                                  .doc = "φ, the friction angle of the yield surface (23); the law keeps tan φ",
                                  .example = "38.66 deg",
                                  .tangent = true}),
          bound(&P::compression_hardening,
               {.name = "compression_hardening",
                .doc = "compressive plasticity beyond ε_s (false: as Yade's public CpmMat, epsSoft ≥ 0)"}),
          bound(&P::hardening_strain, {.name = "hardening_strain",
                                      .range = Range{-1.0, 0.0, true, true},
                                      .doc = "ε_s < 0, where the hardening branch begins"}),
          bound(&P::hardening_modulus_ratio,
               {.name = "hardening_modulus_ratio",
                .range = Range::closed(0.0, 1.0),
                .doc = "K̃_s: the hardening branch's tangent modulus over k_N"}),
          bound(&P::compression_yield,
               {.name = "compression_yield",
                .doc = "the yield surface in compression: logarithmic (the confinement extension) or linear (23), as "
                       "Yade's public CpmMat",
                .words = {"logarithmic", "linear"}}),
          bound(&P::yield_log_speed,
               {.name = "yield_log_speed", .range = Range::positive(), .doc = "Y_0 of the logarithmic surface"}),
          bound(&P::damage_time, {.name = "damage_time",
                                 .unit = Unit::Time,
                                 .range = Range::non_negative(),
                                 .doc = "τ_d of the visco-damage (18)-(22); 0: off (the document recommends 1000 s)"}),
          bound(&P::damage_rate_exponent,
               {.name = "damage_rate_exponent", .range = Range::positive(), .doc = "M_d of the visco-damage (18)"}),
          bound(&P::plastic_time, {.name = "plastic_time",
                                  .unit = Unit::Time,
                                  .range = Range::non_negative(),
                                  .doc = "τ_pl of the visco-plasticity; 0: off, as recommended"}),
          bound(&P::plastic_rate_exponent,
               {.name = "plastic_rate_exponent", .range = Range::positive(), .doc = "M_pl of the visco-plasticity"}),
          bound(&P::confinement, {.name = "confinement",
                                 .unit = Unit::Pressure,
                                 .range = Range{-inf, 0.0, false, false},
                                 .doc = "σ_0 ≤ 0, an isotropic confinement applied at every contact"}),
          bound(&P::never_damage,
               {.name = "never_damage", .doc = "ω = 0 on cohesive contacts (the elastic runs of a calibration)"}),
          bound(&P::interaction_radius,
               {.name = "interaction_radius",
                .range = Range::at_least(1.0),
                .doc = "R_I: cohesive contacts between spheres with d ≤ R_I (R_A + R_B) at the start"}),
          bound(&P::break_damage, {.name = "break_damage",
                                  .range = Range{0.0, 1.0, true, false},
                                  .doc = "ω at which a cohesive contact in tension breaks and becomes non-cohesive "
                                         "(a tensile break in the crack log); 1: never (Yade's omegaThreshold)"}),
      },
      {}, confinement_has_a_strain);
  return t;
}

template class ContactSet<Cpm, 2>;
template class ContactSet<Cpm, 3>;

}  // namespace mc
