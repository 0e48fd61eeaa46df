// A scene, parsed and validated: everything a run needs, in SI units, before anything runs.
// Vectors are stored with `dimension` components. What a scene does not declare is absent (empty or nullopt)
// and is not computed.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/world.hpp"
#include "rigid_cell/facet_law.hpp"     // FacetIntegration: plain data
#include "rigid_cell/fibre_pullout.hpp"  // FibreMaterial: plain data

namespace mc {

class Analysis;
class TomlDoc;

// A contact model with validated parameters, able to make its contact set in either dimension.
struct ModelSpec {
  std::string name;
  bool bonds = false;   // the model bonds pairs (and so breaks them: cracks)
  bool yields = false;  // its bonds yield before they break (softening): first yields are logged too
  std::function<std::unique_ptr<ContactSetBase<2>>()> make2;
  std::function<std::unique_ptr<ContactSetBase<3>>()> make3;
};

struct PhaseSpec {
  std::string name;
  double density = kNaN;  // kg/m³
  // Heterogeneity (Tang §8.1.2): each particle's springs scaled by a factor drawn from a normal (mean 1,
  // stiffness_std, truncated to > 0) or a Weibull (scale 1, shape stiffness_weibull_shape, 8.4); 0: all 1.
  double stiffness_std = 0, stiffness_weibull_shape = 0;
};

struct ContactSpec {
  int phase_a, phase_b;
  ModelSpec model;
};

struct InlineParticle {
  std::vector<double> x, v, w;
  double radius;
  int phase;
};

struct SpecimenSpec {
  enum class Kind { Particles, SphereList, Output, RandomBox, Lattice, Packing } kind;
  std::vector<InlineParticle> particles;  // Particles
  std::string file;                       // SphereList, Output
  std::vector<int> tag_phase;             // SphereList: phase of each tag (index = tag)
  std::vector<double> box_lo, box_hi;     // RandomBox, Lattice: region filled
  std::int64_t count = 0;                 // RandomBox
  double radius_min = 0, radius_max = 0;  // RandomBox, uniform in [min, max]; Lattice: radius_min
  int phase = 0;                          // RandomBox, Lattice, Packing
  // Packing (PFC genesis, preprocess/dense_packing.hpp): radius_min, and
  bool cylinder = false;  // 3D: carve a cylinder (axis z) out of the box
  double radius_ratio = 1.66, porosity = 0.16, stress = 1e5, modulus = 0;
  int floater_contacts = 0;  // PFC's n_f (1 … D + 1): particles with fewer neighbours fill their cage; 0: off
  // Boxes (lo, hi) whose particles are removed after the specimen is made: notches (Tang §7.1).
  std::vector<std::pair<std::vector<double>, std::vector<double>>> cuts;
  // Boxes whose particles join a phase (an FRP sheet on a concrete prism, Tang §8.1); a later box wins.
  struct Region {
    std::vector<double> lo, hi;
    int phase = 0;
  };
  std::vector<Region> regions;
  // Not a key: set for a run resumed from the output file named here, whose /specimen holds what this scene's
  // genesis made (Packing): it is read back instead of run again (the checkpoint then restores the state).
  std::string genesis_from;
};

// Coarse aggregate laid over the specimen (Tang ch. 4): particles of the mortar phase whose centres fall in an
// aggregate join the aggregate phase; the contact table then gives aggregate, mortar and ITZ pairs their models.
struct MesostructureSpec {
  bool present = false;
  double fraction = 0;                                        // target aggregate area / volume fraction of the domain
  std::vector<std::array<double, 3>> ranges;                  // (lo, hi, share) [m, m, -]; shares normalised
  std::vector<double> lo, hi;                                 // the domain; empty: the specimen's bounding box
  std::vector<std::vector<double>> keep_out_lo, keep_out_hi;  // boxes that stay mortar (a notch)
  std::vector<std::vector<double>> keep_out_centre;           // balls that stay mortar (around a notch tip)
  std::vector<double> keep_out_radius;
  double cells_per_dmin = 5;  // background grid, Tang (4.6)
  int mortar_phase = 0, aggregate_phase = 0;
};

struct WallSpec {
  std::string name;
  enum class Kind { Plane, Segment, Rectangle } kind;
  std::vector<double> point, normal, a, b,
      axis;                     // plane: point+normal; segment: a,b (+inside); rectangle: point(centre)+normal+axis
  std::vector<double> inside;   // segment: a point on the material side
  double size0 = 0, size1 = 0;  // rectangle edge lengths
  WallMaterial material;
  WallControl control = WallControl::Fixed;
  std::vector<double> velocity;  // Velocity
  double ramp_time = 0;
  double stress = 0, servo_area = kNaN, gain = 0.5, max_speed = kInf;  // Servo (max_speed: Opening too)
  double retreat_speed = kInf;                                         // Opening
  std::vector<std::string> area_between;                               // Servo: names of opposite walls, in pairs
  std::string probe;                                                   // Opening: the opening probe it drives
  double opening_rate = 0, opening_gain = 0;                           // Opening: [m/s], [1/s]
};

// Boundary conditions on a group of particles chosen by tag (sphere lists), by index or by a box.
struct GroupSpec {
  std::string name;
  std::vector<std::int64_t> tags, ids;
  std::vector<double> box_lo, box_hi;
  FixMask fix = 0;
  std::vector<double> velocity, angular_velocity;  // set at the start (held if the DOF is fixed)
  std::optional<double> ramp_time;                 // given: driven, the velocity reached over it on held axes
  std::vector<double> force, moment;               // applied loads
};

struct RegionSpec {
  std::string name;
  std::vector<double> centre;
  double radius;
  bool stress = false, strain = false, porosity = false, coordination = false;
};

// Strain measured by two opposite walls: (L − L0)/L0, L their distance along the first wall's normal.
struct WallStrainSpec {
  std::string name;
  std::array<int, 2> walls;  // indices into Scene::walls
};

struct ProbeSpec {
  std::string name;
  enum class Kind { Overlap, Gap, RelativeSpeed, Position, Velocity, AngularVelocity, Opening } kind;
  std::vector<std::int64_t> particles;  // one or two
  int component = -1;                   // −1: magnitude (vectors) / normal component (relative speed)
  // Opening: the two sides are two particles, or two groups (indices into Scene::groups); the direction from
  // the first side to the second (empty: the line between them at the start).
  std::array<int, 2> groups = {-1, -1};
  std::vector<double> direction;
};

struct StopSpec {
  std::string quantity;  // a history name
  // MagnitudeAbove: |value| > threshold; not a scene key, `calibrate` uses it to end its elastic runs early.
  enum class Kind { Below, Above, PostPeak, MagnitudeAbove } kind;
  double value;           // threshold, or the fraction of the peak
  double after_time = 0;  // not before this time [s]
};

struct SummarySpec {
  std::string name, of;
  enum class Reduce { Max, Min, Final, Initial, TimeOfMax, DurationPositive, FinalOverInitial, MeanFinal10 } reduce;
};

// The rigid-cell family (Květoň 2019; rigid_cell/): a scene with a [rigid_cell] table fills a shape with Voronoi
// cells of nodes l_min apart, joins them by the facet law of [[contacts]] (model = "facet_damage") and loads them
// through rigid plates ([[groups]] by box) in static load steps of timestep.fixed.
struct CellSpecimenSpec {
  enum class Shape { Box, Disc, Polygon } shape = Shape::Box;
  std::vector<double> size;                     // Box, from the origin [m]
  std::vector<double> centre;                   // Disc: the axis in the x-y plane [m]
  double radius = 0;                            // Disc [m]
  std::vector<std::array<double, 2>> vertices;  // Polygon, counter-clockwise [m]
  double thickness = 0;                         // 3D disc and polygon: along z from 0 [m]
  double l_min = 0;                             // least node distance [m]
  double l_max = 0;                             // coarsening away from the fine box up to this; 0: none [m]
  std::vector<double> fine_lo, fine_hi;         // the box where nodes are l_min apart [m]
  double grading = 0.25;                        // growth of the distance per unit distance from it
  int max_rejections = 2000;                    // placement saturation (rigid_cell/node_placement.hpp)
  std::vector<double> nodes;                    // the cells' nodes, when given (D numbers each) [m]
};

// The facet law between two phases (rigid_cell/facet_law.hpp): E₀ and α given, or from the macroscopic E and ν
// by (3.8) (E0 = 0 then). tensile_strength 0: elastic.
struct FacetLawSpec {
  int phase_a = 0, phase_b = 0;
  double E0 = 0, alpha = 0, modulus = 0, poisson_ratio = 0;
  double tensile_strength = 0, fracture_energy = 0;
  double rate_c0 = 0, rate_c1 = 0;  // (8.17); rate_c1 = 0: rate-independent
  std::string where;                // the table, for messages: "file: contacts[0]"
};

// Květoň §3.4 (3.21): one random field h(x) of mean 1 scales each contact facet's tensile strength by h and its
// fracture energy by h², at the facet's centroid (rigid_cell/random_field.hpp).
struct RandomFieldSpec {
  double correlation_length = 0;  // l_c of the autocorrelation exp(−|Δx|²/l_c²) [m]
  double std = 0;                 // standard deviation of h [-]
  double grid_spacing = 0;        // of the Karhunen–Loève grid over the specimen's box [m] (by default l_c/3)
  double variance_kept = 0.99;    // fraction of the grid's variance the modes kept carry
  double weibull_modulus = 24, grafting_probability = 1e-3;  // the left tail (Bažant & Pang 2007)
  std::uint64_t seed_offset = 0;  // the field's seed is the scene's plus this: several fields on the same cells
};

// Indirect displacement control of a rigid-cell scene ([rigid_cell.opening_control]): a plate travels along
// `direction` so that an opening probe (between two plates) opens at `rate` through the smooth rise (9.1).
struct OpeningControlSpec {
  int probe = 0;  // index into Scene::probes
  int plate = 0;  // index into Scene::groups
  std::vector<double> direction;
  double rate = 0, ramp_time = 0;
};

// Dynamics of a rigid-cell scene ([rigid_cell.dynamics], Květoň ch. 8): implicit by Newmark's β, γ, or explicit by
// central differences; Rayleigh damping.
struct CellDynamicsSpec {
  bool central_difference = false;
  double beta = 0.3, gamma = 0.55;                 // Květoň §9.1
  double mass_damping = 0, stiffness_damping = 0;  // a_M [1/s], a_K [s] of C = a_M M + a_K K₀
};

// A pressure wave on the surface facets in a box ([rigid_cell.stress_wave]): Květoň's cosine pulse (9.5), or a
// piecewise-linear one through given points (the measured waves of his §9.5.3).
struct StressWaveSpec {
  std::vector<double> box_lo, box_hi;
  double pressure = 0, duration = 0;     // σ_max [Pa] (positive: pushing in), t_P [s]
  std::vector<double> times, pressures;  // [s], [Pa]; non-empty: the piecewise-linear wave
};

// A section plane normal to an axis ([rigid_cell.sections]): the mean normal stress across it is a history.
struct SectionSpec {
  int axis = 0;
  double at = 0;  // [m]
};

// A family of short fibres ([[rigid_cell.fibres]], Květoň Part II; rigid_cell/fibre_*.hpp), 3D only: the fibres'
// material, and their placement by volume fraction or count, orientation and boundary rule, or given one by one.
struct FibreFamilySpec {
  std::string name;
  rigid_cell::FibreMaterial material;
  double volume_fraction = 0;  // V_f [-]; 0: by count, or given
  std::int64_t count = 0;
  double length = 0;  // l_f [m]
  enum class Orientation { Isotropic, Aligned, Preferential } orientation = Orientation::Isotropic;
  std::vector<double> direction;  // aligned, preferential
  double concentration = 0;       // κ of the preferential spread [-]
  bool cut = false;               // a fibre partly outside is cut at the surface (else drawn again, §5.4)
  std::vector<double> ends;       // given fibres: x, y, z of end a, then of end b, per fibre [m]
};

// The mean strain of the cells whose nodes lie in a box ([rigid_cell.strain]): the least-squares displacement
// gradient of their nodes, its symmetric part a history per component (an extensometer over the box).
struct StrainBoxSpec {
  std::vector<double> box_lo, box_hi;
};

struct RigidCellSpec {
  CellSpecimenSpec specimen;
  std::optional<StrainBoxSpec> strain;
  std::vector<FibreFamilySpec> fibres;
  std::vector<SectionSpec> sections;
  std::optional<StressWaveSpec> stress_wave;
  std::optional<CellDynamicsSpec> dynamics;  // absent: static load steps
  std::optional<OpeningControlSpec> opening_control;
  std::vector<FacetLawSpec> facets;
  std::optional<RandomFieldSpec> random_field;             // absent: f_t and G_t as the facet laws give them
  double damage_tolerance = 1e-6, force_tolerance = 1e-6;  // rigid_cell/static_solver.hpp
  int max_iterations = 500;
  bool crack_log = false;  // each facet's first damage and its crack (D ≥ 0.99) written to /cracks
  bool energy = false;     // boundary work, stored and dissipated energy as histories
  rigid_cell::FacetIntegration facet_integration = rigid_cell::FacetIntegration::Simple;  // Květoň §3.3
};

struct Scene {
  std::string file;  // for messages
  std::string text;  // the scene as run (stored in the output)
  int dimension = 3;
  std::uint64_t seed = 1;
  std::string title;

  SpecimenSpec specimen;
  MesostructureSpec mesostructure;
  std::vector<PhaseSpec> phases;
  std::vector<ContactSpec> contacts;
  std::vector<WallSpec> walls;
  std::vector<GroupSpec> groups;

  double bond_tolerance = -1;  // [bonds]: bond pairs with gap ≤ tolerance·min(R_A, R_B) at the start; < 0: none
  bool crack_log = false;      // [bonds] crack_log: every break (and first yield) written to /cracks
  std::optional<std::vector<double>> gravity;
  double local_damping = 0;
  double density_scaling = 1;  // inertial mass factor for quasi-static runs (PFC density scaling); 1: off
  double skin = 0;             // 0: 0.1 R_min
  int rebuild_interval = 30;   // adaptive skin: steps aimed for between list rebuilds; 0: the skin stays fixed
  TimestepControl timestep;
  bool energy = false;
  std::vector<RegionSpec> regions;
  std::vector<ProbeSpec> probes;
  std::vector<WallStrainSpec> wall_strains;
  std::vector<double> domain_lo, domain_hi;  // empty: derived from the specimen and walls

  std::int64_t steps = 0;  // stop after this many steps (0: no limit)
  double duration = 0;     // stop at this simulated time (0: no limit)
  std::vector<StopSpec> stops;
  std::vector<SummarySpec> summaries;
  std::optional<RigidCellSpec> rigid_cell;                // present: the scene runs on the rigid-cell family
  std::vector<std::shared_ptr<const Analysis>> analyses;  // [uniaxial] … (scene/analysis.hpp), in registry order
  std::string xy_plots;                                   // "x:y;x2:y2" drawn by report
  std::vector<std::string> warnings;                      // TomlDoc::warnings of the file read

  std::int64_t history_every = 100, frame_every = 0, checkpoint_every = 0, guard_every = 100;
  std::int64_t frames = 50;    // frames over the run when frame_every is 0 (studies/runner.cpp: frame_cadence)
  bool frame_contacts = true;  // each frame's contacts between particles (/contacts)

  // The index in World::gauges of the opening probe named `name` (one gauge per opening probe, in the order
  // of [[probes]]), or −1 when no opening probe has that name.
  int opening_gauge(const std::string& name) const {
    int g = 0;
    for (const auto& p : probes) {
      if (p.kind != ProbeSpec::Kind::Opening) continue;
      if (p.name == name) return g;
      ++g;
    }
    return -1;
  }

  // The analysis of type A the scene declares, or null.
  template <class A>
  const A* analysis() const {
    for (const auto& a : analyses)
      if (const auto* p = dynamic_cast<const A*>(a.get())) return p;
    return nullptr;
  }
};

// Reads and validates a scene; throws InputError naming the file, key, value and what is allowed.
Scene read_scene(const TomlDoc& doc, const std::string& file);

}  // namespace mc
