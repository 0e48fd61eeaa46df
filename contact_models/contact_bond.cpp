// Scene keys of the contact bond ([[contacts]] with model = "contact_bond"): the linear contact's keys
// (modulus, kn_ks_ratio, friction, damping_ratio) and the bond's strengths as forces, normal distributions
// truncated to positive values.
#include "contact_models/contact_bond.hpp"

#include "engine/contact_registry.hpp"

namespace mc {

LinearParams read_linear_params(const Table& t);  // contact_models/linear.cpp

// Also read by the softening bond, which has these keys too.
void read_contact_bond_params(const Table& t, ContactBondParams& p) {
  p.contact = read_linear_params(t);
  p.normal_mean = t.number("bond_normal_strength", Unit::Force, Range::positive());
  p.normal_std = t.number("bond_normal_strength_std", Unit::Force, Range::non_negative(), 0.0);
  p.shear_mean = t.number("bond_shear_strength", Unit::Force, Range::positive());
  p.shear_std = t.number("bond_shear_strength_std", Unit::Force, Range::non_negative(), 0.0);
}

ModelSpec contact_bond_model(const Table& t) {
  ContactBondParams p;
  read_contact_bond_params(t, p);
  return model_spec<ContactBond>(p);
}

}  // namespace mc
