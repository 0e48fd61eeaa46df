// The contact sets of the parallel bond, compiled once here with its law in lanes (parallel_bond_lanes.hpp);
// parallel_bond.hpp announces them (extern template), so the registry, the preprocessor, the tests and the benchmarks
// share this one instantiation.
#include "contact_models/parallel_bond.hpp"
#include "contact_models/parallel_bond_lanes.hpp"

namespace mc {

template class ContactSet<ParallelBond, 2>;
template class ContactSet<ParallelBond, 3>;

}  // namespace mc
