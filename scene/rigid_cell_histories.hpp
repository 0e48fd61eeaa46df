// The histories of a rigid-cell run, described as plain data: their names follow from the scene alone (so stop
// conditions and summaries are checked before anything runs, even in a build without the rigid-cell family), and
// scene/rigid_cell_build.cpp gives each its sampler.
#pragma once
#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace mc {

struct CellSeries {
  enum class What {
    Time,
    Step,
    Iterations,     // secant iterations of the last load step
    Residual,       // its out-of-balance ratio
    Cuts,           // how many times it was halved to converge
    SnapThroughs,   // parts of steps solved so far as snap-throughs (static_solver.hpp, monotone)
    FacetsDamaged,  // facets with D > 0
    FacetsCracked,  // facets with D ≥ 0.99
    MaxDamage,
    PlateReaction,      // the support's force (translations) or moment (rotations) on a plate
    PlateDisplacement,  // a plate's displacement or rotation
    PlateVelocity,      // a plate's velocity (dynamics; translations)
    Opening,            // an opening probe's reading (`plate` holds the probe's index)
    SectionStress,      // the mean normal stress across a section plane (`plate` holds its index)
    SectionBridging,    // the fibres' force across it
    Strain,             // a component of the mean strain over [rigid_cell.strain]'s box (`dof` holds its index)
    FibresBridging,     // fibres that carry a force across a crack
    FibresPulledOut,    // fibres pulled out of a side
    FibresRuptured,     // fibres broken
    BoundaryWork,
    StrainEnergy,
    KineticEnergy,  // dynamics
    Dissipated,
  } what;
  std::string name, unit;
  int plate = -1, dof = -1;
};

std::vector<CellSeries> rigid_cell_series(const Scene& s);

// The strain histories' components, in the order of RigidCellSystem::mean_strain: xx, yy, xy (2D); xx, yy, zz,
// yz, zx, xy (3D).
const char* const* strain_component_names(int dimension);

// "section.z_70mm": the history of the mean normal stress across a section plane.
std::string section_history_name(const SectionSpec& s);

}  // namespace mc
