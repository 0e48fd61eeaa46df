// The contact sets of the linear contact, compiled once here; linear.hpp announces them (extern template), so the
// registry, the preprocessor, the tests and the benchmarks share this one instantiation.
#include "contact_models/linear.hpp"

namespace mc {

template class ContactSet<Linear, 2>;
template class ContactSet<Linear, 3>;

}  // namespace mc
