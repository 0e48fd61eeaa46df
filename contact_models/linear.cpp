// The linear contact's keys, and its contact sets compiled once here; linear.hpp announces them (extern template), so
// the registry, the preprocessor, the tests and the benchmarks share this one instantiation.
#include "contact_models/linear.hpp"

namespace mc {

const KeyTable& Linear::keys() {
  using P = LinearParams;
  static const KeyTable t = key_table<P>(
      "linear", "[[contacts]] model = \"linear\"",
      "The linear contact with Coulomb slip (Tang 3.5-3.10, 3.25-3.26, 3.36, 3.38): a normal spring on the overlap "
      "and an incremental shear spring, two balls' springs in series, with optional viscous dashpots.",
      {
          bound(&P::modulus, {.name = "modulus",
                             .unit = Unit::Pressure,
                             .range = Range::positive(),
                             .need = Need::Required,
                             .doc = "contact modulus E_c: ball k_n = 2tE_c in 2D (t = 1 m), 4RE_c in 3D, two balls "
                                    "in series, Tang (3.25), (3.38)",
                             .example = "30 GPa"}),
          bound(&P::kn_ks_ratio, {.name = "kn_ks_ratio",
                                 .range = Range::positive(),
                                 .doc = "k_n/k_s of the ball springs, Tang (3.26)",
                                 .example = "2.5"}),
          bound(&P::friction, {.name = "friction",
                              .range = Range::non_negative(),
                              .doc = "friction coefficient μ: the shear force slips at μ|F_n|, Tang (3.36)",
                              .example = "0.5"}),
          bound(&P::damping_ratio,
               {.name = "damping_ratio",
                .range = Range::open_fraction(),
                .doc = "ζ of viscous dashpots beside the normal and shear springs, a fraction of critical "
                       "damping (the shear dashpot rests while the contact slides); 0: none"}),
      });
  return t;
}

template class ContactSet<Linear, 2>;
template class ContactSet<Linear, 3>;

}  // namespace mc
