// The rolling-resistance contact's keys, and its contact sets compiled once here; rolling_resistance.hpp announces
// them (extern template).
#include "contact_models/rolling_resistance.hpp"

namespace mc {

const KeyTable& RollingResistance::keys() {
  using P = RollingResistanceParams;
  static const KeyTable t = key_table<P>(
      "rolling_resistance", "[[contacts]] model = \"rolling_resistance\"",
      "The linear contact with slip (the linear keys) and a rolling resistance beside it, as PFC's rolling-resistance "
      "linear model (Iwashita & Oda 1998; Ai et al. 2011): a moment spring k_r = k_s R̄² against the relative bending "
      "rotation, R̄ = R_A R_B/(R_A + R_B), bounded by μ_r R̄ F_n.",
      joined(keys_at(Linear::keys(), offset_of(&P::contact)),
             {
                 bound(&P::rolling_friction,
                       {.name = "rolling_friction",
                        .range = Range::non_negative(),
                        .need = Need::Required,
                        .doc = "μ_r: the rolling moment is bounded by μ_r R̄ F_n; a ball on a slope rolls where "
                               "tan θ > μ_r (0: free rolling, the linear contact)",
                        .example = "0.1"}),
             }));
  return t;
}

template class ContactSet<RollingResistance, 2>;
template class ContactSet<RollingResistance, 3>;

}  // namespace mc
