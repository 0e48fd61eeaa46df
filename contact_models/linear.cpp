// Scene keys of the linear contact model ([[contacts]] with model = "linear").
#include "contact_models/linear.hpp"

#include "engine/contact_registry.hpp"

namespace mc {

LinearParams read_linear_params(const Table& t) {
  LinearParams p;
  p.modulus = t.number("modulus", Unit::Pressure, Range::positive());
  p.kn_ks_ratio = t.number("kn_ks_ratio", Unit::None, Range::positive(), 1.0);
  p.friction = t.number("friction", Unit::None, Range::non_negative(), 0.0);
  p.damping_ratio = t.number("damping_ratio", Unit::None, Range::open_fraction(), 0.0);
  return p;
}

ModelSpec linear_model(const Table& t) { return model_spec<Linear>(read_linear_params(t)); }

}  // namespace mc
