// Scene keys of the contact bond ([[contacts]] with model = "contact_bond"): the linear contact's keys
// (modulus, kn_ks_ratio, friction, damping_ratio) and the bond's strengths as forces, normal distributions
// truncated to positive values.
#include "contact_models/contact_bond.hpp"

#include <tuple>

#include "engine/contact_registry.hpp"

namespace mc {

LinearParams read_linear_params(const Table& t);                                   // contact_models/linear.cpp
std::tuple<double, double, double> read_distribution(const Table& t, const std::string& key, Unit u);  // contact_models/linear.cpp

// Also read by the softening bond, which has these keys too.
void read_contact_bond_params(const Table& t, ContactBondParams& p) {
  p.contact = read_linear_params(t);
  std::tie(p.normal_mean, p.normal_std, p.normal_weibull) = read_distribution(t, "bond_normal_strength", Unit::Force);
  std::tie(p.shear_mean, p.shear_std, p.shear_weibull) = read_distribution(t, "bond_shear_strength", Unit::Force);
}

ModelSpec contact_bond_model(const Table& t) {
  ContactBondParams p;
  read_contact_bond_params(t, p);
  return model_spec<ContactBond>(p);
}

}  // namespace mc
