// Scene keys of the simplified Hertz–Mindlin model ([[contacts]] with model = "hertz_mindlin").
#include "contact_models/hertz_mindlin.hpp"

#include "engine/contact_registry.hpp"

namespace mc {

ModelSpec hertz_mindlin_model(const Table& t) {
  HertzMindlinParams p;
  p.shear_modulus = t.number("shear_modulus", Unit::Pressure, Range::positive());
  p.poisson = t.number("poisson", Unit::None, Range{-1.0, 0.5, true, true});
  p.friction = t.number("friction", Unit::None, Range::non_negative(), 0.0);
  p.damping_ratio = t.number("damping_ratio", Unit::None, Range::open_fraction(), 0.0);
  return model_spec<HertzMindlin>(p);
}

}  // namespace mc
