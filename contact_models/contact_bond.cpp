// The contact sets of the contact bond, compiled once here; contact_bond.hpp announces them (extern template), so the
// registry, the preprocessor, the tests and the benchmarks share this one instantiation.
#include "contact_models/contact_bond.hpp"

namespace mc {

template class ContactSet<ContactBond, 2>;
template class ContactSet<ContactBond, 3>;

}  // namespace mc
