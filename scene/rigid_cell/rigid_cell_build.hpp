// Scene → the rigid-cell family's System (rigid_cell/rigid_cell_system.hpp): the shape, the phases from the
// mesostructure, the facet law of each phase pair, the random field of their strength, the plates, the load step
// and the histories the scene records.
// Compiled only when the family is (MESOCRACK_RIGID_CELL).
#pragma once
#include <memory>

#include "engine/system.hpp"
#include "scene/scene.hpp"

namespace mc {

// Throws InputError naming the scene file and the table, cell, facet or plate that makes the setup impossible.
std::unique_ptr<System> make_rigid_cell_system(const Scene& scene);

}  // namespace mc
