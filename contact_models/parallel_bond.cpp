// Scene keys of the parallel bond ([[contacts]] with model = "parallel_bond"): the grain contact's keys
// (modulus, kn_ks_ratio, friction, damping_ratio) and the bond's, prefixed "bond_". Strengths are normal
// distributions truncated to positive values, as in Tang (2013) Table 5.1 (mean ± std).
#include "contact_models/parallel_bond.hpp"

#include "engine/contact_registry.hpp"

namespace mc {

LinearParams read_linear_params(const Table& t);  // contact_models/linear.cpp

ModelSpec parallel_bond_model(const Table& t) {
  ParallelBondParams p;
  p.contact = read_linear_params(t);
  p.radius_multiplier = t.number("bond_radius_multiplier", Unit::None, Range::positive(), 1.0);
  p.modulus = t.number("bond_modulus", Unit::Pressure, Range::positive());
  p.kn_ks_ratio = t.number("bond_kn_ks_ratio", Unit::None, Range::positive(), 1.0);
  p.tensile_mean = t.number("bond_tensile_strength", Unit::Pressure, Range::positive());
  p.tensile_std = t.number("bond_tensile_strength_std", Unit::Pressure, Range::non_negative(), 0.0);
  p.shear_mean = t.number("bond_shear_strength", Unit::Pressure, Range::positive());
  p.shear_std = t.number("bond_shear_strength_std", Unit::Pressure, Range::non_negative(), 0.0);
  return model_spec<ParallelBond>(p);
}

}  // namespace mc
