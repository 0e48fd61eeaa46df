// The contact sets of the Concrete Particle Model, compiled once here with its law in lanes (cpm_lanes.hpp);
// cpm.hpp announces them (extern template), so the registry, the preprocessor, the tests and the benchmarks share
// this one instantiation.
#include "contact_models/cpm.hpp"
#include "contact_models/cpm_lanes.hpp"

namespace mc {

template class ContactSet<Cpm, 2>;
template class ContactSet<Cpm, 3>;

}  // namespace mc
