// Scene keys of the linear contact model ([[contacts]] with model = "linear").
#include "contact_models/linear.hpp"

#include <tuple>

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

// A bond parameter (strength, modulus) drawn per bond: `key` (mean, or the Weibull scale λ) with either `key_std` (normal truncated to
// positive values) or `key_weibull_shape` (Weibull, Tang 8.4), not both. Returns {mean or λ, std, shape}.
std::tuple<double, double, double> read_distribution(const Table& t, const std::string& key, Unit u) {
  const double a = t.number(key, u, Range::positive());
  const bool normal = t.has(key + "_std"), weibull = t.has(key + "_weibull_shape");
  if (normal && weibull)
    t.fail(key + "_weibull_shape", "given together with " + key + "_std: a bond parameter is drawn either from a normal "
                                   "distribution (" + key + " = mean, " + key + "_std) or from a Weibull distribution (" +
                                   key + " = scale, " + key + "_weibull_shape), not both");
  const double b = t.number(key + "_std", u, Range::non_negative(), 0.0);
  const double k = t.number(key + "_weibull_shape", Unit::None, Range::positive(), 0.0);
  return {a, b, k};
}

ModelSpec linear_model(const Table& t) { return model_spec<Linear>(read_linear_params(t)); }

}  // namespace mc
