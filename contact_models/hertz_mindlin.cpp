// The contact sets of the Hertz–Mindlin contact, compiled once here; hertz_mindlin.hpp announces them (extern
// template), so the registry, the preprocessor, the tests and the benchmarks share this one instantiation.
#include "contact_models/hertz_mindlin.hpp"

namespace mc {

template class ContactSet<HertzMindlin, 2>;
template class ContactSet<HertzMindlin, 3>;

}  // namespace mc
