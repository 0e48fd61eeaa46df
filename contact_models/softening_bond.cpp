// Scene keys of the softening bond ([[contacts]] with model = "softening_bond"): the linear contact's keys
// (modulus, kn_ks_ratio, friction, damping_ratio), the bond's strengths as forces (normal distributions
// truncated to positive values, as the contact bond's), and how far it softens: bond_plastic_limit (U_p,max)
// or bond_fracture_energy (G_f, from which U_p,max = 2 G_f A / F_c^n per bond).
#include "contact_models/softening_bond.hpp"

#include "engine/contact_registry.hpp"

namespace mc {

void read_contact_bond_params(const Table& t, ContactBondParams& p);  // contact_models/contact_bond.cpp

ModelSpec softening_bond_model(const Table& t) {
  SofteningBondParams p;
  read_contact_bond_params(t, p);
  // Two ways to say one thing: both would contradict each other, neither leaves the softening undefined.
  const bool limit = t.has("bond_plastic_limit"), energy = t.has("bond_fracture_energy");
  const std::string allowed =
      "the softening bond takes exactly one of bond_plastic_limit (U_p,max, a length in m) and "
      "bond_fracture_energy (G_f, an energy per area in J/m2 or N/m)";
  if (limit && energy) t.fail("bond_fracture_energy", "given together with bond_plastic_limit; " + allowed);
  if (!limit && !energy) t.fail("bond_plastic_limit", "missing; " + allowed);
  if (limit) p.plastic_limit = t.number("bond_plastic_limit", Unit::Length, Range::positive());
  else p.fracture_energy = t.number("bond_fracture_energy", Unit::EnergyPerArea, Range::positive());
  return model_spec<SofteningBond>(p);
}

}  // namespace mc
