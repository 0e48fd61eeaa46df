// The Hertz–Mindlin contact's keys, and its contact sets compiled once here; hertz_mindlin.hpp announces them
// (extern template), so the registry, the preprocessor, the tests and the benchmarks share this one instantiation.
#include "contact_models/hertz_mindlin.hpp"

namespace mc {

const KeyTable& HertzMindlin::keys() {
  using P = HertzMindlinParams;
  static const KeyTable t = key_table<P>(
      "hertz_mindlin", "[[contacts]] model = \"hertz_mindlin\"",
      "PFC's simplified Hertz-Mindlin contact (Tang 3.27-3.35): a normal force growing with the overlap to the power "
      "3/2, a tangent shear stiffness growing with the normal force, Coulomb slip, optional viscous dashpots.",
      {
          bound(&P::shear_modulus, {.name = "shear_modulus",
                                   .unit = Unit::Pressure,
                                   .range = Range::positive(),
                                   .need = Need::Required,
                                   .doc = "shear modulus G of the grains, Tang (3.27), (3.28)",
                                   .example = "12 GPa"}),
          bound(&P::poisson, {.name = "poisson",
                             .range = Range{-1.0, 0.5, true, true},
                             .need = Need::Required,
                             .doc = "Poisson's ratio ν of the grains, Tang (3.27), (3.28)",
                             .example = "0.2"}),
          bound(&P::friction, {.name = "friction",
                              .range = Range::non_negative(),
                              .doc = "friction coefficient μ: the shear force slips at μ|F_n|, Tang (3.36)",
                              .example = "0.5"}),
          bound(&P::damping_ratio, {.name = "damping_ratio",
                                   .range = Range::open_fraction(),
                                   .doc = "ζ of viscous dashpots beside the springs, a fraction of critical; 0: none"}),
      });
  return t;
}

template class ContactSet<HertzMindlin, 2>;
template class ContactSet<HertzMindlin, 3>;

}  // namespace mc
