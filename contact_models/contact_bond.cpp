// The contact bond's keys, and its contact sets compiled once here; contact_bond.hpp announces them (extern
// template), so the registry, the preprocessor, the tests and the benchmarks share this one instantiation.
#include "contact_models/contact_bond.hpp"

namespace mc {

const KeyTable& ContactBond::keys() {
  using P = ContactBondParams;
  static const KeyTable t = key_table<P>(
      "contact_bond", "[[contacts]] model = \"contact_bond\"",
      "PFC's contact bond (Tang §3.3.3): a linear contact (the linear keys) glued at its contact point. While the "
      "bond holds, the springs carry tension (measured from the gap at bonding) and never slip; it breaks when the "
      "tensile normal force or the shear force reaches its strength, and the pair is then a linear contact with "
      "slip. Each bond draws its strengths from the scene's seed.",
      joined(keys_at(Linear::keys(), offset_of(&P::contact)),
                {
                    bound(&P::bond_normal_strength,
                         {.name = "bond_normal_strength",
                          .unit = Unit::Force,
                          .need = Need::Required,
                          .doc = "F_c^n: the bond breaks (or, softening, yields) when the tensile normal force "
                                 "reaches it, Tang §3.3.3",
                          .example = "500 N"}),
                    bound(&P::bond_shear_strength,
                         {.name = "bond_shear_strength",
                          .unit = Unit::Force,
                          .need = Need::Required,
                          .doc = "F_c^s: the bond breaks (or, softening, yields) when the shear force reaches it, "
                                 "Tang §3.3.3",
                          .example = "1 kN"}),
                }));
  return t;
}

template class ContactSet<ContactBond, 2>;
template class ContactSet<ContactBond, 3>;

}  // namespace mc
