// The parallel bond's keys, and its contact sets compiled once here with its law in lanes (parallel_bond_lanes.hpp);
// parallel_bond.hpp announces them (extern template), so the registry, the preprocessor, the tests and the benchmarks
// share this one instantiation.
#include "contact_models/parallel_bond.hpp"

#include "contact_models/parallel_bond_lanes.hpp"

namespace mc {

const KeyTable& ParallelBond::keys() {
  using P = ParallelBondParams;
  static const KeyTable t = key_table<P>(
      "parallel_bond", "[[contacts]] model = \"parallel_bond\"",
      "The parallel bond (Potyondy & Cundall 2004; Tang 3.37-3.41) beside a linear contact with slip (the linear "
      "keys): a short elastic beam of radius R̄ glued between the particles carries normal and shear force, bending "
      "and (3D) twisting moments, incrementally; it breaks when its largest tensile or shear stress reaches its "
      "strength, and the pair is then a linear contact with slip. Each bond draws its strengths (and its modulus, "
      "when it scatters) from the scene's seed.",
      joined(keys_at(Linear::keys(), offset_of(&P::contact)), {
           bound(&P::bond_radius_multiplier,
                {.name = "bond_radius_multiplier",
                 .range = Range::positive(),
                 .doc = "λ̄: the bond's radius R̄ = λ̄ min(R_A, R_B), Tang (3.40)"}),
           bound(&P::bond_modulus, {.name = "bond_modulus",
                                   .unit = Unit::Pressure,
                                   .need = Need::Required,
                                   .doc = "the bond's modulus Ē_c: k̄_n = Ē_c/(R_A + R_B), Tang (3.38); each bond may "
                                          "draw its own (Tang §8.1.2)",
                                   .example = "30 GPa"}),
           bound(&P::bond_kn_ks_ratio, {.name = "bond_kn_ks_ratio",
                                       .range = Range::positive(),
                                       .doc = "k̄_n/k̄_s of the bond, Tang (3.38)",
                                       .example = "2.5"}),
           bound(&P::bond_tensile_strength,
                {.name = "bond_tensile_strength",
                 .unit = Unit::Pressure,
                 .need = Need::Required,
                 .doc = "σ̄_c: the bond breaks when the beam's largest tensile stress −F̄_n/Ā + |M̄|R̄/Ī reaches it, "
                        "Tang (3.41)",
                 .example = "20 MPa"}),
           bound(&P::bond_shear_strength,
                {.name = "bond_shear_strength",
                 .unit = Unit::Pressure,
                 .need = Need::Required,
                 .doc = "τ̄_c: the bond breaks when the beam's largest shear stress |F̄_s|/Ā + |M̄_n|R̄/J̄ reaches it, "
                        "Tang (3.41)",
                 .example = "40 MPa"}),
                                                              }));
  return t;
}

template class ContactSet<ParallelBond, 2>;
template class ContactSet<ParallelBond, 3>;

}  // namespace mc
