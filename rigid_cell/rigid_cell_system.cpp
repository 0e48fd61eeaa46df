#include "rigid_cell/rigid_cell_system.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

#include "engine/errors.hpp"
#include "engine/ramp.hpp"
#include "rigid_cell/box_strain.hpp"
#include "rigid_cell/fibre_crossings.hpp"
#include "rigid_cell/node_placement.hpp"

namespace mc::rigid_cell {

namespace {

// Cells reach at most about l_min (l_max where they coarsen) from their node once the placement is saturated;
// three times that is a safe band for the mirror images (tessellation.hpp).
constexpr double kReachPerLmin = 3.0;

template <int D>
std::string box_text(const Vec<D>& lo, const Vec<D>& hi) {
  std::ostringstream m;
  m << "[" << lo.transpose() << "] .. [" << hi.transpose() << "] m";
  return m.str();
}

}  // namespace

template <int D>
RigidCellSystem<D>::RigidCellSystem(RigidCellSetup<D> setup) : setup_(std::move(setup)) {
  build_cells();
  build_fibres();
  build_plates();
  solver_ = std::make_unique<StaticSolver<D>>(*model_, *plates_, prescribed_, setup_.dynamics.has_value(),
                                              bridges_.get());
  u_ = u_before_ = reactions_ = f_ext_ = v_ = a_ = plate_loads_ = wave_load_ =
      Eigen::VectorXd::Zero(plates_->reduced());
  for (int p = 0; p < plates_->plates(); ++p)
    for (int k = 0; k < kDofs; ++k) plate_loads_[plates_->plate_dof(p, k)] = setup_.plates[p].load[k];
  build_stress_wave();
  build_sections();
  damage_.assign(model_->contacts(), 0.0);
  states_.assign(model_->contacts(), FacetState{});
  for (std::size_t c = 0; c < model_->contacts(); ++c) rate_dependent_ = rate_dependent_ || model_->params(c).rate_c1 > 0;
  if (rate_dependent_ && !setup_.dynamics)
    throw InputError(
        "a facet law's rate dependence (rate_c0, rate_c1; Kveton (8.16)-(8.17)) acts on the cells' "
        "velocities: it needs [rigid_cell.dynamics]");
  build_dynamics();
  build_gauges();
  build_strain_rows();
  if (setup_.dynamics) impose_held_motion(0);
}

// The facets that a plane cuts between cells on its two sides form a surface that parts the specimen there; by the
// divergence theorem their areas projected on the plane, signed by the side of b, sum to the section's area.
template <int D>
void RigidCellSystem<D>::build_sections() {
  for (const SectionPlane& p : setup_.sections) {
    SectionFacets s;
    for (std::size_t c = 0; c < tessellation_.contacts; ++c) {
      const Facet<D>& f = tessellation_.facets[c];
      const double a = tessellation_.cells[f.a].node[p.axis], b = tessellation_.cells[f.b].node[p.axis];
      if ((a < p.at) == (b < p.at)) continue;
      const double sign = b >= p.at ? 1.0 : -1.0;
      s.facets.emplace_back(c, sign);
      s.area += sign * f.area * f.normal[p.axis];
    }
    if (!(s.area > 0)) {
      std::ostringstream m;
      m << "the section plane at " << p.at << " m along axis " << p.axis << " cuts no cell of the specimen";
      throw InputError(m.str());
    }
    sections_.push_back(std::move(s));
  }
}

// The force on the near side's cells from the far side's, along the axis: −(the force on b) when b is beyond.
template <int D>
double RigidCellSystem<D>::section_stress(int section) const {
  const SectionFacets& s = sections_[section];
  const int axis = setup_.sections[section].axis;
  const Eigen::VectorXd u_cells = solver_->cell_displacements(u_);
  double force = 0;
  for (const auto& [c, sign] : s.facets) force -= sign * model_->force(c, u_cells, damage_[c])[axis];
  return (force - section_bridging_force(section)) / s.area;
}

template <int D>
double RigidCellSystem<D>::section_bridging_force(int section) const {
  if (!bridges_) return 0.0;
  const int axis = setup_.sections[section].axis;
  double force = 0;
  for (const auto& [c, sign] : sections_[section].facets) force -= sign * bridges_->contact_force(c)[axis];
  return force;
}

template <int D>
std::vector<FibreState> RigidCellSystem<D>::fibre_states() const {
  std::vector<FibreState> most(fibres_.size(), FibreState::Idle);
  if (!bridges_) return most;
  for (std::size_t i = 0; i < bridges_->sites(); ++i) {
    const BridgeState<D>& s = bridges_->state(i);
    if (s.active == 0) continue;
    const TwoSidedPullout& t = s.bridge.sides;
    FibreState state = FibreState::Idle;
    if (s.bridge.ruptured) state = FibreState::Ruptured;
    else if (pullout_resistance(bridges_->material(i), t.embedment[0], t.pullout[0]) == 0 ||
             pullout_resistance(bridges_->material(i), t.embedment[1], t.pullout[1]) == 0)
      state = FibreState::PulledOut;
    else if (s.force > 0)
      state = FibreState::Bridging;
    FibreState& m = most[bridges_->site(i).fibre];
    m = std::max(m, state);
  }
  return most;
}

template <int D>
std::array<std::size_t, 3> RigidCellSystem<D>::fibre_counts() const {
  std::array<std::size_t, 3> n{0, 0, 0};
  for (const FibreState s : fibre_states())
    if (s != FibreState::Idle) ++n[static_cast<int>(s) - 1];
  return n;
}

// Each fibre as a polyline through its crossings, which come fibre by fibre, each fibre's in order from its end a.
template <int D>
FibreGeometry RigidCellSystem<D>::fibre_geometry() const {
  FibreGeometry g;
  if (!bridges_) return g;
  std::size_t i = 0;
  for (std::size_t k = 0; k < fibres_.size(); ++k) {
    std::vector<std::int64_t> line;
    const auto add = [&](const auto& p) {
      line.push_back(static_cast<std::int64_t>(g.point.size() / 3));
      g.point.insert(g.point.end(), p.data(), p.data() + 3);
    };
    add(fibres_[k].a);
    const std::size_t first = i;
    for (; i < bridges_->sites() && bridges_->site(i).fibre == static_cast<int>(k); ++i) add(bridges_->site(i).point);
    add(fibres_[k].b);
    g.lines.add(line);
    g.family.push_back(family_of_fibre_[k]);
    g.crossings.push_back(static_cast<std::int32_t>(i - first));
  }
  return g;
}

template <int D>
Eigen::VectorXd RigidCellSystem<D>::cell_forces(const Eigen::VectorXd& u_cells) const {
  Eigen::VectorXd f = model_->internal_forces(u_cells, damage_);
  if (bridges_) bridges_->add_forces(f);
  return f;
}

template <int D>
void RigidCellSystem<D>::build_cells() {
  for (std::size_t i = 0; i < setup_.nodes.size(); ++i) {
    if (!setup_.shape->inside(setup_.nodes[i]))
      throw InputError("specimen.nodes: node " + std::to_string(i) + " lies outside the specimen's shape");
    for (std::size_t j = 0; j < i; ++j)
      if (setup_.nodes[i] == setup_.nodes[j])
        throw InputError("specimen.nodes: nodes " + std::to_string(j) + " and " + std::to_string(i) + " coincide");
  }
  const auto nodes = setup_.nodes.empty() ? place_nodes(*setup_.shape, setup_.spacing, setup_.seed, setup_.max_rejections)
                                          : setup_.nodes;
  tessellation_ = tessellate(nodes, *setup_.shape, kReachPerLmin * setup_.spacing.largest());
  if (setup_.facet_integration == FacetIntegration::Discretized) {
    FacetParts<D> p = discretize_facets(tessellation_);
    tessellation_ = std::move(p.parts);
    part_first_ = std::move(p.first);
  }
  polygons_ = std::make_unique<const CellPolygons<D>>(tessellation_);
  for (const auto& c : tessellation_.cells) phase_.push_back(setup_.phase_at ? setup_.phase_at(c.node) : 0);
  std::vector<FacetParams> params;
  for (std::size_t c = 0; c < tessellation_.contacts; ++c)
    params.push_back(setup_.facet(phase_[tessellation_.facets[c].a], phase_[tessellation_.facets[c].b]));
  if (setup_.strength_field) apply_strength_field(params);
  model_ = std::make_unique<CellAssembly<D>>(tessellation_, std::move(params));
}

// The fibres of each family, placed from their own random stream (the same seed, the same fibres, whatever the
// cells), walked through the cells; each crossing of a contact facet a bridge site.
template <int D>
void RigidCellSystem<D>::build_fibres() {
  if (setup_.fibres.empty()) return;
  if constexpr (D == 2) {
    throw InputError("[rigid_cell.fibres]: fibres are straight segments in a volume: they need a 3D specimen");
  } else {
    const auto start = std::chrono::steady_clock::now();
    std::vector<FibreMaterial> materials;
    for (std::size_t k = 0; k < setup_.fibres.size(); ++k) {
      const FibreFamily& family = setup_.fibres[k];
      materials.push_back(family.material);
      std::vector<Fibre> placed = family.given;
      if (placed.empty()) {
        std::uint64_t mix = setup_.seed ^ (0xF1B4E00000000000ULL + k);  // a stream apart from the nodes'
        RandomStream rng(splitmix64(mix));
        placed = place_fibres(*setup_.shape, family.placement, rng);
      }
      fibres_.insert(fibres_.end(), placed.begin(), placed.end());
      family_of_fibre_.insert(family_of_fibre_.end(), placed.size(), static_cast<int>(k));
    }
    const auto placed = std::chrono::steady_clock::now();
    std::vector<FibreCrossing> crossings;
    try {
      crossings = fibre_crossings(tessellation_, fibres_);
    } catch (const std::runtime_error& e) {
      throw InputError(std::string("[rigid_cell.fibres]: ") + e.what());
    }
    // The walk leaves a cell through any part of a facet's plane; a crossing belongs to the part that holds it.
    if (!part_first_.empty())
      for (FibreCrossing& c : crossings) {
        const std::size_t facet = facet_of_part(part_first_, static_cast<std::size_t>(c.facet));
        c.facet = static_cast<int>(part_holding(tessellation_, part_first_, facet, c.point));
      }
    bridges_ = std::make_unique<FibreBridges<3>>(tessellation_, *model_, std::move(materials),
                                                 bridge_sites(fibres_, family_of_fibre_, crossings));
    const auto crossed = std::chrono::steady_clock::now();
    fibre_seconds_[0] = std::chrono::duration<double>(placed - start).count();
    fibre_seconds_[1] = std::chrono::duration<double>(crossed - placed).count();
    double volume = 0;
    for (std::size_t i = 0; i < fibres_.size(); ++i) {
      const double d = setup_.fibres[family_of_fibre_[i]].material.diameter;
      volume += 0.25 * M_PI * d * d * (fibres_[i].b - fibres_[i].a).norm();
    }
    setup_.facts.push_back({"fibres", static_cast<double>(fibres_.size())});
    setup_.facts.push_back({"fibre_crossings", static_cast<double>(bridges_->sites())});
    setup_.facts.push_back({"fibre_bridged_facets", static_cast<double>(bridges_->contacts().size())});
    setup_.facts.push_back({"fibre_volume_fraction", volume / setup_.shape->volume()});
  }
}

// Květoň (3.21): f_t(x) = f̄_t h(x), G_t(x) = Ḡ_t h(x)² at each contact facet's centroid. The crack band's
// f_t² L/G_t stays as it was, so a law that does not snap back (3.20) still does not. The field's modes and the
// range of h over the facets go to the facts.
template <int D>
void RigidCellSystem<D>::apply_strength_field(std::vector<FacetParams>& params) {
  double least = std::numeric_limits<double>::infinity(), most = 0, sum = 0;
  for (std::size_t c = 0; c < params.size(); ++c) {
    const double h = setup_.strength_field->h(tessellation_.facets[c].centroid);
    params[c].tensile_strength *= h;
    params[c].fracture_energy *= h * h;
    least = std::min(least, h), most = std::max(most, h), sum += h;
  }
  setup_.facts.push_back({"random_field_modes", static_cast<double>(setup_.strength_field->modes())});
  setup_.facts.push_back({"random_field_h_min", least});
  setup_.facts.push_back({"random_field_h_max", most});
  setup_.facts.push_back({"random_field_h_mean", sum / static_cast<double>(params.size())});
}

// Each plate takes the cells whose nodes lie in its box and turns about their volume centroid.
template <int D>
void RigidCellSystem<D>::build_plates() {
  std::vector<Vec<D>> nodes;
  for (const auto& c : tessellation_.cells) nodes.push_back(c.node);
  std::vector<Vec<D>> references;
  std::vector<int> plate_of(cells(), -1);
  for (std::size_t p = 0; p < setup_.plates.size(); ++p) {
    const PlateSpec<D>& s = setup_.plates[p];
    Vec<D> moment = Vec<D>::Zero();
    double volume = 0;  // of the plate's cells: none, no plate
    for (int c = 0; c < cells(); ++c) {
      if ((nodes[c].array() < s.lo.array()).any() || (nodes[c].array() > s.hi.array()).any()) continue;
      if (plate_of[c] >= 0)
        throw InputError("plates '" + setup_.plates[plate_of[c]].name + "' and '" + s.name + "' both hold cell " +
                         std::to_string(c) + ": a cell moves with one plate at most; make their boxes disjoint");
      plate_of[c] = static_cast<int>(p);
      const auto& m = tessellation_.cells[c].mass;
      moment += m.volume * (nodes[c] + m.centroid());
      volume += m.volume;
    }
    if (volume == 0) {
      const double l = setup_.spacing.at((s.lo + s.hi) / 2);  // l_min, or the coarser distance there
      throw InputError("plate '" + s.name + "': no cell's node lies in its box " + box_text<D>(s.lo, s.hi) +
                       " (nodes are at least l = " + std::to_string(l) +
                       " m apart there and l/2 inside the surface: widen the box" +
                       (setup_.spacing.uniform() ? "" : " or the fine box, or lower l_max") + ")");
    }
    references.push_back(moment / volume);
  }
  plates_ = std::make_unique<PlateConstraints<D>>(nodes, plate_of, references);
  for (int p = 0; p < plates_->plates(); ++p)
    for (int k = 0; k < kDofs; ++k)
      if (setup_.plates[p].held[k]) prescribed_.push_back(plates_->plate_dof(p, k));
}

// Each gauge's row over the reduced degrees of freedom, and the drive of an opening control: its plate's held
// translations along its unit direction. A drive that does not open its gauge at the start is refused.
// Each component of the box's mean strain is a row over the cells' translations (box_strain.hpp), mapped onto the
// reduced degrees of freedom like a gauge's.
template <int D>
void RigidCellSystem<D>::build_strain_rows() {
  if (!setup_.strain_box) return;
  std::vector<Vec<D>> nodes;
  for (const auto& c : tessellation_.cells) nodes.push_back(c.node);
  const auto& [lo, hi] = *setup_.strain_box;
  for (const Eigen::VectorXd& full : box_strain_rows<D>(nodes, lo, hi, kDofs))
    strain_rows_.push_back(plates_->map().transpose() * full);
}

template <int D>
void RigidCellSystem<D>::build_gauges() {
  const int n = plates_->reduced();
  for (const PlateGauge<D>& g : setup_.gauges) {
    Vec<D> dir = g.direction;
    if (dir.isZero()) dir = plates_->reference(g.plate_b) - plates_->reference(g.plate_a);
    if (dir.isZero())
      throw InputError("gauge '" + g.name + "': its plates' reference points coincide: give its direction");
    dir.normalize();
    Eigen::VectorXd row = Eigen::VectorXd::Zero(n);
    for (int k = 0; k < D; ++k) {
      row[plates_->plate_dof(g.plate_b, k)] += dir[k];
      row[plates_->plate_dof(g.plate_a, k)] -= dir[k];
    }
    gauges_.push_back(row);
  }
  if (!setup_.opening_control) return;
  const OpeningDrive<D>& c = *setup_.opening_control;
  const PlateSpec<D>& plate = setup_.plates[c.plate];
  GaugeControl control{Eigen::VectorXd::Zero(n), gauges_[c.gauge]};
  const Vec<D> dir = c.direction.normalized();
  for (int k = 0; k < D; ++k) {
    if (dir[k] == 0) continue;
    if (!plate.held[k] || plate.velocity[k] != 0)
      throw InputError("plate '" + plate.name + "' is driven by gauge '" + setup_.gauges[c.gauge].name + "' along " +
                       "xyz"[k] + ": it must hold that translation (fix) with no velocity of its own");
    control.drive[plates_->plate_dof(c.plate, k)] = dir[k];
  }
  if (!(solver_->gauge_sensitivity(control, std::vector<double>(model_->contacts(), 0.0)) > 0))
    throw InputError("plate '" + plate.name + "' moving along its direction does not open gauge '" +
                     setup_.gauges[c.gauge].name +
                     "' (it closes it or leaves it): reverse the direction or drive "
                     "another plate");
  control_ = control;
}

// The held degrees of freedom at loading time t: velocity × the smooth rise (9.1).
template <int D>
void RigidCellSystem<D>::prescribe(double t) {
  const Eigen::VectorXd held = held_motion(t).u;
  for (int dof : prescribed_) u_[dof] = held[dof];
  f_ext_ = loads_at(t);
  if (!control_) return;
  // The drive's own part is found by the solve: it starts from zero there.
  const OpeningDrive<D>& c = *setup_.opening_control;
  for (Eigen::Index d = 0; d < u_.size(); ++d)
    if (control_->drive[d] != 0) u_[d] = 0;
  control_->target = c.rate * smooth_rise_displacement(t, c.ramp_time);
}

template <int D>
void RigidCellSystem<D>::step() {
  const std::vector<double> damage_before = damage_;
  const Eigen::VectorXd reactions_before = reactions_, loads_before = loads_at(time_);
  u_before_ = u_;
  ++step_;
  last_ = {};
  cuts_ = 0;
  if (explicit_ || newmark_) {
    explicit_ ? explicit_step() : dynamic_step();
    add_work(reactions_before, loads_before);
    time_ += setup_.load_step;
    log_cracks(damage_before);
    return;
  }
  try {
    advance(time_, time_ + setup_.load_step, 0);
  } catch (const InstabilityError& e) {
    std::ostringstream m;
    m << "step " << step_ << " (t = " << time_ + setup_.load_step << " s; the load step cut " << kMaxCuts
      << " times, and solved as a snap-through): " << e.what();
    throw InstabilityError(m.str());
  }
  time_ += setup_.load_step;
  reactions_ = solver_->reactions(u_, f_ext_, damage_);
  add_work(reactions_before, loads_before);
  log_cracks(damage_before);
}

// The work of the supports and the applied loads over the step, trapezoidal (exact for the secant-linear response
// within it, and for Newmark's average acceleration on an elastic specimen). The loads act from the first step on.
template <int D>
void RigidCellSystem<D>::add_work(const Eigen::VectorXd& reactions_before, const Eigen::VectorXd& loads_before) {
  for (int d : prescribed_) work_ += 0.5 * (reactions_before[d] + reactions_[d]) * (u_[d] - u_before_[d]);
  work_ += 0.5 * (loads_before + f_ext_).dot(u_ - u_before_);  // the loads: zero on held degrees of freedom
}

// The static solve from loading time `from` to `to`; when its secant iteration does not converge, the state goes
// back to `from` and the interval is done in two halves; the smallest halves as a snap-through.
template <int D>
void RigidCellSystem<D>::advance(double from, double to, int cuts) {
  const Eigen::VectorXd u = u_;
  const std::vector<double> damage = damage_;
  const std::vector<FacetState> states = states_;
  if (control_) control_->lambda = control_->drive.dot(u_);  // λ so far (the drive is a unit vector)
  prescribe(to);
  StaticOptions options = setup_.options;
  options.monotone = cuts > kMaxCuts;
  // A crack running through a snap-through may extend by a few facets per iteration: it gets more of them.
  if (options.monotone) options.max_iterations *= kSnapThroughIterations;
  try {
    const StaticResult r = solver_->solve(u_, f_ext_, damage_, states_, options, control_ ? &*control_ : nullptr);
    last_.iterations += r.iterations, last_.factorisations += r.factorisations, last_.residual = r.residual;
    snap_throughs_ += options.monotone;
  } catch (const InstabilityError&) {
    if (options.monotone) throw;
    u_ = u, damage_ = damage, states_ = states;
    cuts_ = std::max(cuts_, cuts + 1);
    if (cuts == kMaxCuts) return advance(from, to, cuts + 1);
    advance(from, 0.5 * (from + to), cuts + 1);
    advance(0.5 * (from + to), to, cuts + 1);
  }
}

// A facet's first damage is a yield, its damage reaching kCracked a break; tensile when it opens, shear when it
// slides under compression.
template <int D>
void RigidCellSystem<D>::log_cracks(const std::vector<double>& before) {
  if (!setup_.crack_log) return;
  const Eigen::VectorXd u_cells = solver_->cell_displacements(u_);
  for (std::size_t c = 0; c < damage_.size(); ++c) {
    const bool yielded = before[c] == 0 && damage_[c] > 0, broke = before[c] < kCracked && damage_[c] >= kCracked;
    if (!yielded && !broke) continue;
    const Facet<D>& f = tessellation_.facets[c];
    const CrackMode mode = model_->strain(c, u_cells)[0] > 0 ? CrackMode::Tensile : CrackMode::Shear;
    for (CrackKind kind : {CrackKind::Yield, CrackKind::Break}) {
      if ((kind == CrackKind::Yield && !yielded) || (kind == CrackKind::Break && !broke)) continue;
      cracks_.push_back({step_, time_, f.a, f.b, f.centroid, f.normal, mode, kind, 0, phase_[f.a], phase_[f.b]});
    }
  }
}

template <int D>
void RigidCellSystem<D>::check_stability() const {
  for (Eigen::Index d = 0; d < u_.size(); ++d)
    if (!std::isfinite(u_[d]) || !std::isfinite(reactions_[d])) {
      std::ostringstream m;
      m << "unstable at step " << step_ << " (t = " << time_ << " s): reduced degree of freedom " << d
        << " is not finite; likely cause: a facet law returned no finite damage";
      throw InstabilityError(m.str());
    }
}

template <int D>
std::size_t RigidCellSystem<D>::facets_damaged() const {
  return static_cast<std::size_t>(std::count_if(damage_.begin(), damage_.end(), [](double d) { return d > 0; }));
}

template <int D>
std::size_t RigidCellSystem<D>::facets_cracked() const {
  return static_cast<std::size_t>(
      std::count_if(damage_.begin(), damage_.end(), [](double d) { return d >= kCracked; }));
}

template <int D>
double RigidCellSystem<D>::max_damage() const {
  return damage_.empty() ? 0.0 : *std::max_element(damage_.begin(), damage_.end());
}

// ½ Σ fᵢ·uᵢ over the cells' internal forces: the elastic energy the (secant) facets hold.
template <int D>
double RigidCellSystem<D>::strain_energy() const {
  const Eigen::VectorXd u_cells = solver_->cell_displacements(u_);
  return 0.5 * model_->internal_forces(u_cells, damage_).dot(u_cells);
}

template <int D>
SpecimenData RigidCellSystem<D>::specimen() const {
  SpecimenData d{D, {}, {}, {}, setup_.phase_names, {}, setup_.facts, setup_.outlines, polygons_->geometry(), fibre_geometry()};
  for (int c = 0; c < cells(); ++c) {
    const auto& cell = tessellation_.cells[c];
    d.x.insert(d.x.end(), cell.node.data(), cell.node.data() + D);
    // The radius of the disc or sphere of the cell's volume (2D: its area, unit thickness).
    const double v = cell.mass.volume;
    d.radius.push_back(D == 2 ? std::sqrt(v / M_PI) : std::cbrt(3 * v / (4 * M_PI)));
    d.phase.push_back(phase_[c]);
    d.id.push_back(c);
  }
  const double shape_volume = setup_.shape->volume();
  d.facts.insert(d.facts.begin(),
                 {{"cells", static_cast<double>(cells())},
                  {"contact_facets",
                   static_cast<double>(part_first_.empty() ? tessellation_.contacts : part_first_.size() - 1)},
                  {"surface_facets", static_cast<double>(tessellation_.facets.size() - tessellation_.contacts)},
                  {"l_min", setup_.spacing.l_min},
                  {"volume_tiled_over_shape", tessellation_.volume() / shape_volume}});
  if (!part_first_.empty())
    d.facts.insert(d.facts.begin() + 2, {"contact_facet_parts", static_cast<double>(tessellation_.contacts)});
  if (explicit_)
    d.facts.insert(d.facts.end(), {{"highest_frequency_rad_per_s", explicit_->highest_frequency()},
                                   {"critical_timestep", explicit_->critical_timestep()},
                                   {"timestep", setup_.load_step}});
  return d;
}

template <int D>
void RigidCellSystem<D>::frame(std::vector<double>& x, std::vector<double>& v, std::vector<double>& force) const {
  const Eigen::VectorXd u = solver_->cell_displacements(u_), before = solver_->cell_displacements(u_before_);
  const Eigen::VectorXd f = cell_forces(u);
  // Dynamics: Newmark's velocities; static solves: the step's travel over its loading time.
  const Eigen::VectorXd velocity = setup_.dynamics ? Eigen::VectorXd(solver_->cell_displacements(v_))
                                                   : Eigen::VectorXd((u - before) / setup_.load_step);
  x.clear(), v.clear(), force.clear();
  for (int c = 0; c < cells(); ++c)
    for (int k = 0; k < D; ++k) {
      const int i = c * kDofs + k;
      x.push_back(tessellation_.cells[c].node[k] + u[i]);
      v.push_back(velocity[i]);
      force.push_back(f[i]);
    }
}

template <int D>
CellFrame RigidCellSystem<D>::cell_frame() const {
  CellFrame f{polygons_->moved(solver_->cell_displacements(u_)), damage_, {}, {}, {}};
  if (!bridges_) return f;
  for (const FibreState s : fibre_states()) f.fibre_state.push_back(static_cast<double>(s));
  f.fibre_force.assign(fibres_.size(), 0.0);
  f.fibre_slip.assign(fibres_.size(), 0.0);
  for (std::size_t i = 0; i < bridges_->sites(); ++i) {
    const BridgeState<D>& s = bridges_->state(i);
    const int k = bridges_->site(i).fibre;
    f.fibre_force[k] = std::max(f.fibre_force[k], s.force);
    f.fibre_slip[k] = std::max({f.fibre_slip[k], s.bridge.sides.pullout[0], s.bridge.sides.pullout[1]});
  }
  return f;
}

template <int D>
std::string RigidCellSystem<D>::cost_report(double wall_seconds) const {
  if (!bridges_ || wall_seconds <= 0) return "";
  std::ostringstream m;
  m << std::fixed << std::setprecision(1) << "the fibres' " << bridges_->sites()
    << (bridges_->sites() == 1 ? " crossing: " : " crossings: ")
    << bridges_->seconds() << " s, " << std::setprecision(0) << 100 * bridges_->seconds() / wall_seconds << " % of it";
  return m.str();
}

template <int D>
std::vector<std::string> RigidCellSystem<D>::crack_models() const {
  if (!setup_.crack_log) return {};
  return {"facet_damage"};
}

template <int D>
CrackRows RigidCellSystem<D>::cracks(std::size_t first) const {
  CrackRows r;
  for (std::size_t k = first; k < cracks_.size(); ++k) {
    const Crack<D>& c = cracks_[k];
    r.add(c, c.a, c.b);
  }
  return r;
}

template <int D>
void RigidCellSystem<D>::save(Archive& a) const {
  a.put_scalar("step", static_cast<double>(step_));
  a.put_scalar("time", time_);
  a.put_scalar("boundary_work", work_);
  a.put_scalar("snap_throughs", static_cast<double>(snap_throughs_));
  auto vec = [](const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); };
  a.reals["u"] = vec(u_);
  a.reals["u_before"] = vec(u_before_);
  a.reals["reactions"] = vec(reactions_);
  a.reals["damage"] = damage_;
  if (setup_.dynamics) a.reals["v"] = vec(v_), a.reals["a"] = vec(a_);
  a.reals["factored_damage"] = solver_->factored_state();
  a.put("D_max", states_);
  a.put("cracks", cracks_);
  if (bridges_) a.put("fibre_bridges", bridges_->converged());
}

template <int D>
void RigidCellSystem<D>::restore(const Archive& a) {
  if (a.reals.at("u").size() != static_cast<std::size_t>(u_.size()) || a.reals.at("damage").size() != damage_.size())
    throw InputError(
        "its checkpoint holds a different rigid-cell specimen than the scene builds; resume with the scene that "
        "wrote it");
  step_ = static_cast<std::int64_t>(a.scalar("step"));
  time_ = a.scalar("time");
  work_ = a.scalar("boundary_work");
  snap_throughs_ = static_cast<std::int64_t>(a.scalar("snap_throughs"));
  auto vec = [&](const std::string& key, Eigen::VectorXd& v) {
    const auto& d = a.reals.at(key);
    v = Eigen::Map<const Eigen::VectorXd>(d.data(), static_cast<Eigen::Index>(d.size()));
  };
  vec("u", u_), vec("u_before", u_before_), vec("reactions", reactions_);
  if (setup_.dynamics) vec("v", v_), vec("a", a_);
  damage_ = a.reals.at("damage");
  // The factor the solves were preconditioned with (absent from checkpoints of older builds: factorised afresh).
  if (const auto f = a.reals.find("factored_damage"); f != a.reals.end() && !f->second.empty())
    solver_->factorise_at(f->second);
  a.get("D_max", states_);
  a.get("cracks", cracks_);
  if (bridges_) {
    std::vector<BridgeState<D>> states;
    a.get("fibre_bridges", states);
    bridges_->restore(std::move(states));
  }
}

template class RigidCellSystem<2>;
template class RigidCellSystem<3>;

}  // namespace mc::rigid_cell
