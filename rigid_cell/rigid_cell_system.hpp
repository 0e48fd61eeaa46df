// The rigid-cell model as a System (engine/system.hpp), loaded quasi-statically: a specimen shape filled with
// Voronoi cells (node placement, tessellation), one facet law per contact from the phases of its two cells,
// rigid plates that hold or drive groups of cells, and one static solve per load step (Květoň §3.2.3). A step
// advances the loading time by `load_step`; the plates' held degrees of freedom follow their velocity through the
// smooth rise (9.1). What the scene records is given to it as series (set_histories) reading the accessors below.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "engine/crack.hpp"
#include "engine/system.hpp"
#include "rigid_cell/cell_assembly.hpp"
#include "rigid_cell/cell_polygons.hpp"
#include "rigid_cell/central_difference.hpp"
#include "rigid_cell/facet_discretization.hpp"
#include "rigid_cell/fibre_bridges.hpp"
#include "rigid_cell/fibre_placement.hpp"
#include "rigid_cell/newmark.hpp"
#include "rigid_cell/node_placement.hpp"
#include "rigid_cell/plate_constraints.hpp"
#include "rigid_cell/random_field.hpp"
#include "rigid_cell/static_solver.hpp"

namespace mc::rigid_cell {

// A rigid plate: the cells whose nodes lie in a box, moving as one body about their volume centroid. Held
// degrees of freedom (translations, then rotations) follow velocity × the smooth rise (9.1); the others are free.
template <int D>
struct PlateSpec {
  std::string name;
  Vec<D> lo, hi;
  std::array<bool, D + Dim<D>::rot> held{};
  Eigen::Matrix<double, D + Dim<D>::rot, 1> velocity = Eigen::Matrix<double, D + Dim<D>::rot, 1>::Zero();
  double ramp_time = 0;  // T of (9.1) [s]
  // Force and moment on its free degrees of freedom about its reference point, acting from the first step on.
  Eigen::Matrix<double, D + Dim<D>::rot, 1> load = Eigen::Matrix<double, D + Dim<D>::rot, 1>::Zero();
};

// Dynamics (Květoň ch. 8): implicit by Newmark's β and γ (8.2)-(8.5), or explicit by central differences
// (central_difference.hpp); Rayleigh damping C = a_M M + a_K K₀ on the undamaged stiffness. Absent: each step is a
// static solve.
struct DynamicsSpec {
  enum class Scheme { Newmark, CentralDifference } scheme = Scheme::Newmark;
  double beta = NewmarkScheme::kBeta, gamma = NewmarkScheme::kGamma;
  double mass_damping = 0;       // a_M [1/s]
  double stiffness_damping = 0;  // a_K [s]
};

// An opening gauge (a clip gauge, the CMOD) between two plates: n · (U_b − U_a), the relative displacement of their
// reference points along n.
template <int D>
struct PlateGauge {
  std::string name;
  int plate_a = 0, plate_b = 0;
  Vec<D> direction = Vec<D>::Zero();  // zero: the line from a's reference point to b's
};

// Indirect displacement control (static_solver.hpp GaugeControl): a plate travels along `direction` on held
// translations so that a gauge opens by rate × the smooth rise (9.1).
template <int D>
struct OpeningDrive {
  int gauge = 0, plate = 0;
  Vec<D> direction = Vec<D>::Zero();
  double rate = 0;       // [m/s]
  double ramp_time = 0;  // T of (9.1) [s]
};

// A stress wave on the specimen's surface, on the surface facets whose centroids lie in a box (positive: pushing
// into the specimen): Květoň's (9.5), one cosine pulse σ(t) = ½ σ_max (1 − cos 2πt/t_P) for t ≤ t_P, then none; or
// a piecewise-linear pressure through given points (a measured wave, §9.5.3), none after the last.
template <int D>
struct StressWave {
  Vec<D> lo, hi;
  double pressure = 0;                   // σ_max [Pa]
  double duration = 0;                   // t_P [s]
  std::vector<double> times, pressures;  // the piecewise-linear wave, when given [s], [Pa]
  double at(double t) const {
    if (times.empty())
      return t <= duration ? 0.5 * pressure * (1 - std::cos(2 * std::numbers::pi * t / duration)) : 0.0;
    if (t <= times.front() || t >= times.back()) return 0.0;
    const auto i = static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin());
    const double s = (t - times[i - 1]) / (times[i] - times[i - 1]);
    return pressures[i - 1] + s * (pressures[i] - pressures[i - 1]);
  }
};

// A plane across the specimen, normal to an axis, across which the mean normal stress is read.
struct SectionPlane {
  int axis = 0;
  double at = 0;  // [m]
};

// A family of short fibres (Květoň Part II): one material, placed by volume fraction (or count) and orientation,
// or given one by one (`given`, placed as they are).
struct FibreFamily {
  std::string name;
  FibreMaterial material;
  FibrePlacement placement;
  std::vector<Fibre> given;
};

template <int D>
struct RigidCellSetup {
  std::shared_ptr<const SpecimenShape<D>> shape;
  NodeSpacing<D> spacing;  // l_min, or l_min in a box coarsening to l_max away from it
  std::uint64_t seed = 1;
  int max_rejections = 2000;
  std::vector<std::string> phase_names;
  std::vector<double> phase_density;                  // [kg/m³]: the cells' mass, for dynamics
  std::function<int(const Vec<D>&)> phase_at;         // the phase of the cell with this node (the mesostructure)
  std::function<FacetParams(int, int)> facet;         // the law between two phases (InputError if none is declared)
  std::vector<std::pair<std::string, double>> facts;  // what building the mesostructure measured
  std::vector<std::vector<std::array<double, 2>>> outlines;
  std::vector<PlateSpec<D>> plates;
  std::vector<PlateGauge<D>> gauges;
  std::optional<OpeningDrive<D>> opening_control;
  double load_step = 0;  // [s] of loading time per static solve, or the time step of a dynamic one
  // Central differences: a load_step of 0 asks for this fraction of the critical step (0 < safety ≤ 1).
  double timestep_safety = 0;
  std::optional<DynamicsSpec> dynamics;
  std::optional<StressWave<D>> stress_wave;
  std::vector<SectionPlane> sections;
  std::optional<std::pair<Vec<D>, Vec<D>>> strain_box;  // low and high corners of the mean-strain box
  StaticOptions options;
  bool crack_log = false;
  // Květoň (3.21): the field h that scales each contact facet's f_t by h and G_t by h² at its centroid; null: none.
  std::shared_ptr<const RandomField<D>> strength_field;
  // The nodes of the cells, when given (else placed at random, `spacing` apart, in the shape) [m].
  std::vector<Vec<D>> nodes;
  std::vector<FibreFamily> fibres;  // 3D only
  // Where each contact facet's law is evaluated: at its centroid, or at its parts' (Květoň §3.3). Discretized, every
  // count, frame and log of facets is of their parts.
  FacetIntegration facet_integration = FacetIntegration::Simple;
};

template <int D>
class RigidCellSystem final : public System {
 public:
  static constexpr int kDofs = CellAssembly<D>::kDofs;
  // A facet is counted cracked (and logged as a break) once its damage reaches this: it then carries under 1 % of
  // the stress its strain would give intact, (3.11).
  static constexpr double kCracked = 0.99;
  // A load step whose secant iteration does not converge is cut in halves, down to 1/2^kMaxCuts of itself; a
  // smallest part that still does not converge is solved with damage monotone within its iteration (a snap-through,
  // static_solver.hpp).
  static constexpr int kMaxCuts = 6;
  static constexpr int kSnapThroughIterations = 10;  // × max_iterations for a snap-through

  // Places the nodes, tessellates, assigns phases and laws, ties the plates. Throws InputError naming the cell,
  // facet or plate that makes the setup impossible.
  explicit RigidCellSystem(RigidCellSetup<D> setup);
  RigidCellSystem(const RigidCellSystem&) = delete;  // the history samplers point into it
  RigidCellSystem& operator=(const RigidCellSystem&) = delete;

  void set_histories(std::vector<Series> series) { series_ = std::move(series); }

  int dimension() const override { return D; }
  void start() override {}
  void step() override;
  std::int64_t step_count() const override { return step_; }
  double time() const override { return time_; }
  double timestep() const override { return setup_.load_step; }
  void check_stability() const override;
  const std::vector<Series>& histories() const override { return series_; }
  SpecimenData specimen() const override;
  void frame(std::vector<double>& x, std::vector<double>& v, std::vector<double>& force) const override;
  CellFrame cell_frame() const override;
  std::string cost_report(double wall_seconds) const override;
  std::vector<std::string> crack_models() const override;
  std::size_t crack_count() const override { return cracks_.size(); }
  CrackRows cracks(std::size_t first) const override;
  void save(Archive& a) const override;
  void restore(const Archive& a) override;

  // What histories read.
  int cells() const { return static_cast<int>(tessellation_.cells.size()); }
  double plate_reaction(int plate, int k) const { return reactions_[plates_->plate_dof(plate, k)]; }
  double plate_displacement(int plate, int k) const { return u_[plates_->plate_dof(plate, k)]; }
  double plate_velocity(int plate, int k) const { return v_[plates_->plate_dof(plate, k)]; }  // dynamics
  double opening(int gauge) const { return gauges_[gauge].dot(u_); }
  // The mean normal stress across a section plane [Pa], tension positive: the facets between cells on its two
  // sides, their forces' component along the axis over their area projected on the plane.
  double section_stress(int section) const;
  // Component c (xx, yy, xy in 2D; xx, yy, zz, yz, zx, xy in 3D) of the mean strain over the strain box
  // (box_strain.hpp).
  double mean_strain(int c) const { return strain_rows_[c].dot(u_); }
  std::size_t facets_damaged() const;
  std::size_t facets_cracked() const;
  double max_damage() const;
  int last_iterations() const { return last_.iterations; }  // of the last step, its cuts included
  double last_residual() const { return last_.residual; }
  int last_cuts() const { return cuts_; }                        // how many times the last step was halved
  std::int64_t snap_throughs() const { return snap_throughs_; }  // parts of steps solved so far as snap-throughs
  // Work of the plates on the specimen, the elastic energy its facets store, and their difference: what the
  // damage dissipated (a static solve has no kinetic energy).
  double boundary_work() const { return work_; }
  double strain_energy() const;
  double kinetic_energy() const;  // ½ u̇ᵀ M u̇ (dynamics; 0 for static solves)
  // The fibres (none without [rigid_cell.fibres]): each fibre's ends and family, and their crossings.
  const std::vector<Fibre>& fibres() const { return fibres_; }
  const std::vector<int>& fibre_families() const { return family_of_fibre_; }
  const FibreBridges<D>* bridges() const { return bridges_.get(); }
  // Each fibre's state, by its most advanced crossing (broken, then pulled out of a side, anchored no more, then
  // bridging: carrying a force; idle else).
  std::vector<FibreState> fibre_states() const;
  // How many fibres bridge a crack now, have been pulled out, have broken; the bridges' force across a section along
  // its axis [N].
  std::array<std::size_t, 3> fibre_counts() const;
  double section_bridging_force(int section) const;
  double fibre_placement_seconds() const { return fibre_seconds_[0]; }
  double fibre_crossing_seconds() const { return fibre_seconds_[1]; }
  // Central differences: the undamaged specimen's highest frequency [rad/s] and the critical step it sets [s].
  double highest_frequency() const { return explicit_ ? explicit_->highest_frequency() : 0.0; }
  double critical_timestep() const { return explicit_ ? explicit_->critical_timestep() : 0.0; }

 private:
  RigidCellSetup<D> setup_;
  Tessellation<D> tessellation_;
  std::vector<std::size_t> part_first_;  // discretized facets: contact facet f's parts [part_first_[f], [f + 1])
  std::vector<int> phase_;  // per cell
  std::unique_ptr<const CellPolygons<D>> polygons_;
  std::unique_ptr<CellAssembly<D>> model_;
  std::vector<Fibre> fibres_;
  std::vector<int> family_of_fibre_;
  std::unique_ptr<FibreBridges<D>> bridges_;
  double fibre_seconds_[2] = {0, 0};
  std::unique_ptr<PlateConstraints<D>> plates_;
  std::vector<int> prescribed_;  // reduced degrees of freedom
  std::unique_ptr<StaticSolver<D>> solver_;
  std::vector<Eigen::VectorXd> gauges_;  // reduced rows: a gauge's reading is its row · u
  std::vector<Eigen::VectorXd> strain_rows_;  // the same for each mean-strain component
  std::optional<GaugeControl> control_;
  std::vector<Series> series_;

  std::int64_t step_ = 0;
  double time_ = 0, work_ = 0;
  Eigen::VectorXd u_, u_before_, reactions_, f_ext_;  // reduced
  Eigen::VectorXd plate_loads_, wave_load_;           // the plates' loads; the stress wave's at unit pressure
  // Dynamics: the reduced mass matrix, the scheme, velocities and accelerations.
  SparseMatrix mass_;
  std::optional<NewmarkScheme> newmark_;
  std::unique_ptr<CentralDifference<D>> explicit_;
  Eigen::VectorXd v_, a_;
  std::vector<double> damage_;
  std::vector<FacetState> states_;
  std::vector<Crack<D>> cracks_;
  StaticResult last_;
  int cuts_ = 0;
  std::int64_t snap_throughs_ = 0;

  void build_cells();
  void build_fibres();
  FibreGeometry fibre_geometry() const;
  // The cells' internal forces: the facets' and the fibres' of their last evaluation.
  Eigen::VectorXd cell_forces(const Eigen::VectorXd& u_cells) const;
  void apply_strength_field(std::vector<FacetParams>& params);
  void build_plates();
  void build_gauges();
  void build_strain_rows();
  void build_dynamics();
  void dynamic_step();
  void explicit_step();
  void build_explicit();
  // The plates' held motion at t (on their held degrees of freedom; zero elsewhere): velocity × the smooth rise
  // (9.1) and its derivatives.
  KinematicState held_motion(double t) const;
  void impose_held_motion(double t);  // v and a of the held degrees of freedom as held_motion says
  void add_work(const Eigen::VectorXd& reactions_before, const Eigen::VectorXd& loads_before);
  void build_stress_wave();
  void build_sections();
  struct SectionFacets {
    std::vector<std::pair<std::size_t, double>> facets;  // contact facet, +1 if its cell b lies beyond the plane
    double area = 0;                                     // Σ sign A n_axis: the section's area
  };
  std::vector<SectionFacets> sections_;
  Eigen::VectorXd loads_at(double t) const;  // the applied loads at time t (none at t = 0)
  // Rate dependence (8.16)-(8.17), when a facet law declares it: each facet's strain rate at the step's start.
  bool rate_dependent_ = false;
  std::vector<double> strain_rates_;
  void prescribe(double t);
  void advance(double from, double to, int cuts);
  void log_cracks(const std::vector<double>& before);
};

extern template class RigidCellSystem<2>;
extern template class RigidCellSystem<3>;

}  // namespace mc::rigid_cell
