// Scene keys of the parallel bond ([[contacts]] with model = "parallel_bond"): the grain contact's keys
// (modulus, kn_ks_ratio, friction, damping_ratio) and the bond's, prefixed "bond_". Strengths are normal
// distributions truncated to positive values, as in Tang (2013) Table 5.1 (mean ± std).
#include "contact_models/parallel_bond.hpp"

#include <tuple>

#include "engine/contact_registry.hpp"

namespace mc {

LinearParams read_linear_params(const Table& t);                                   // contact_models/linear.cpp
std::tuple<double, double, double> read_distribution(const Table& t, const std::string& key, Unit u);  // contact_models/linear.cpp

ModelSpec parallel_bond_model(const Table& t) {
  ParallelBondParams p;
  p.contact = read_linear_params(t);
  p.radius_multiplier = t.number("bond_radius_multiplier", Unit::None, Range::positive(), 1.0);
  std::tie(p.modulus, p.modulus_std, p.modulus_weibull) = read_distribution(t, "bond_modulus", Unit::Pressure);
  p.kn_ks_ratio = t.number("bond_kn_ks_ratio", Unit::None, Range::positive(), 1.0);
  std::tie(p.tensile_mean, p.tensile_std, p.tensile_weibull) = read_distribution(t, "bond_tensile_strength", Unit::Pressure);
  std::tie(p.shear_mean, p.shear_std, p.shear_weibull) = read_distribution(t, "bond_shear_strength", Unit::Pressure);
  return model_spec<ParallelBond>(p);
}

}  // namespace mc
