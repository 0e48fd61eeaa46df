// The key tables of a scene file's own tables (engine/keys.hpp), each declared beside its reader in scene/; the
// models' tables are beside their Params (contact models; the rigid-cell facet law, rigid_cell/facet_law.hpp). all_key_tables() lists every
// table a scene may hold, in the order of the key reference (`mesocrack keys`, docs/keys.md).
#pragma once
#include <vector>

#include "engine/keys.hpp"

namespace mc {

const KeyTable& scene_keys();     // the top level (scene/scene_read.cpp)
const KeyTable& phases_keys();    // [[phases]]
const KeyTable& contacts_keys();  // [[contacts]]: the model and the pair of phases; the model's own keys follow it
const KeyTable& bonds_keys();     // [bonds]
const KeyTable& run_keys();       // [run]
const KeyTable& stop_keys();      // [[run.stop]]
const KeyTable& summary_keys();   // [[summary]]
const KeyTable& output_keys();    // [output]

const KeyTable& specimen_keys();            // [specimen] (scene/specimen_read.cpp)
const KeyTable& specimen_particles_keys();  // [[specimen.particles]]
const KeyTable& specimen_cuts_keys();       // [[specimen.cuts]]
const KeyTable& specimen_regions_keys();    // [[specimen.regions]]
const KeyTable& mesostructure_keys();       // [mesostructure]
const KeyTable& grading_ranges_keys();      // [[mesostructure.ranges]]
const KeyTable& keep_out_keys();            // [[mesostructure.keep_out]]

const KeyTable& walls_keys();     // [[walls]] (scene/boundary_read.cpp)
const KeyTable& groups_keys();    // [[groups]]
const KeyTable& physics_keys();   // [physics]
const KeyTable& timestep_keys();  // [timestep]

const KeyTable& measure_keys();       // [[measure]] (scene/observers_read.cpp)
const KeyTable& wall_strains_keys();  // [[wall_strains]]
const KeyTable& probes_keys();        // [[probes]]

const KeyTable& rigid_cell_keys();           // [rigid_cell] (scene/rigid_cell_read.cpp)
const KeyTable& cell_specimen_keys();        // [specimen] of a rigid-cell scene
const KeyTable& random_field_keys();         // [rigid_cell.random_field]
const KeyTable& opening_control_keys();      // [rigid_cell.opening_control]
const KeyTable& cell_dynamics_keys();        // [rigid_cell.dynamics]
const KeyTable& stress_wave_keys();          // [rigid_cell.stress_wave]
const KeyTable& sections_keys();             // [rigid_cell.sections]
const KeyTable& strain_box_keys();           // [rigid_cell.strain]
const KeyTable& fibres_keys();               // [[rigid_cell.fibres]]

// Every table, the analyses' (scene/analysis.cpp) and the models' (scene/model_registry.cpp) included, in the
// reference's order.
std::vector<const KeyTable*> all_key_tables();

}  // namespace mc
