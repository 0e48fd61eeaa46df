// The contact sets of the displacement-softening bond, compiled once here; softening_bond.hpp announces them (extern
// template), so the registry, the preprocessor, the tests and the benchmarks share this one instantiation.
#include "contact_models/softening_bond.hpp"

namespace mc {

template class ContactSet<SofteningBond, 2>;
template class ContactSet<SofteningBond, 3>;

}  // namespace mc
