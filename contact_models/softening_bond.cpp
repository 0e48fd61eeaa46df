// The displacement-softening bond's keys, and its contact sets compiled once here; softening_bond.hpp announces them
// (extern template), so the registry, the preprocessor, the tests and the benchmarks share this one instantiation.
#include "contact_models/softening_bond.hpp"

namespace mc {

const KeyTable& SofteningBond::keys() {
  using P = SofteningBondParams;
  static const KeyTable t = key_table<P>(
      "softening_bond", "[[contacts]] model = \"softening_bond\"",
      "PFC's displacement-softening bond (Tang 3.42-3.48): the contact bond's springs and strengths (its keys), "
      "softening instead of letting go. In tension the strength is interpolated with the force angle (3.42) and the "
      "bond yields along the resultant force; in compression the shear limit is μ|F_n| + F_c^s (3.47); both fall "
      "linearly with the accumulated plastic displacement U_p, and the bond breaks at U_p,max. Breaking it in pure "
      "tension takes ½ F_c^n U_p,max.",
      joined(ContactBond::keys().keys,  // the base's members: at the same offsets in a SofteningBondParams
             {
                 bound(&P::bond_plastic_limit, {.name = "bond_plastic_limit",
                                               .unit = Unit::Length,
                                               .range = Range::positive(),
                                               .doc = "U_p,max: the plastic displacement at which the bond breaks, "
                                                      "Tang (3.48)",
                                               .example = "5 um"}),
                 bound(&P::bond_fracture_energy,
                      {.name = "bond_fracture_energy",
                       .unit = Unit::EnergyPerArea,
                       .range = Range::positive(),
                       .doc = "G_f over the bond's section A (3.39 with λ̄ = 1): U_p,max = 2 G_f A / F_c^n per bond"}),
             }),
      {{.keys = {"bond_plastic_limit", "bond_fracture_energy"},
        .one_required = true,
        .why = "the softening bond takes exactly one of bond_plastic_limit (U_p,max, a length in m) and "
               "bond_fracture_energy (G_f, an energy per area in J/m2 or N/m)"}});
  return t;
}

template class ContactSet<SofteningBond, 2>;
template class ContactSet<SofteningBond, 3>;

}  // namespace mc
