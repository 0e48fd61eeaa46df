#include "scene/rigid_cell/rigid_cell_build.hpp"

#include <cstdio>
#include <optional>

#include "engine/errors.hpp"
#include "rigid_cell/rigid_cell_system.hpp"
#include "scene/rigid_cell_histories.hpp"
#include "scene/specimen_build.hpp"

namespace mc {

namespace {

using namespace rigid_cell;

template <int D>
std::shared_ptr<const SpecimenShape<D>> shape_of(const CellSpecimenSpec& c) {
  using S = CellSpecimenSpec::Shape;
  if (c.shape == S::Box) return std::make_shared<SpecimenShape<D>>(SpecimenShape<D>::box(vec_of<D>(c.size)));
  if (c.shape == S::Disc)
    return std::make_shared<SpecimenShape<D>>(
        SpecimenShape<D>::circle(Eigen::Vector2d(c.centre[0], c.centre[1]), c.radius, c.thickness));
  std::vector<Eigen::Vector2d> v;
  for (const auto& p : c.vertices) v.emplace_back(p[0], p[1]);
  return std::make_shared<SpecimenShape<D>>(SpecimenShape<D>::polygon(std::move(v), c.thickness));
}

// The facet law of each phase pair that has one: E₀ and α as given or from E and ν by (3.8).
template <int D>
std::vector<std::vector<std::optional<FacetParams>>> facet_table(const Scene& s) {
  const std::size_t n = s.phases.size();
  std::vector<std::vector<std::optional<FacetParams>>> table(n, std::vector<std::optional<FacetParams>>(n));
  for (const FacetLawSpec& f : s.rigid_cell->facets) {
    FacetParams p{f.E0, f.alpha, f.tensile_strength, f.fracture_energy, f.rate_c0, f.rate_c1};
    if (f.E0 == 0) {
      try {
        const FacetParams m = mesoscopic(D, f.modulus, f.poisson_ratio);
        p.E0 = m.E0, p.alpha = m.alpha;
      } catch (const InputError& e) {
        throw InputError(f.where + ": modulus and poisson_ratio: " + e.what());
      }
    }
    table[f.phase_a][f.phase_b] = table[f.phase_b][f.phase_a] = p;
  }
  return table;
}

// Květoň §3.4: the field over the specimen's box, drawn from the scene's seed plus the field's offset.
template <int D>
std::shared_ptr<const RandomField<D>> strength_field(const Scene& s, const SpecimenShape<D>& shape) {
  const RandomFieldSpec& f = *s.rigid_cell->random_field;
  RandomFieldParams p;
  p.correlation_length = f.correlation_length;
  p.deviation = f.std;
  p.grid_spacing = f.grid_spacing;
  p.variance_kept = f.variance_kept;
  p.tail = {f.weibull_modulus, f.grafting_probability};
  p.seed = s.seed + f.seed_offset;
  try {
    return std::make_shared<const RandomField<D>>(shape.lo(), shape.hi(), p);
  } catch (const InputError& e) {
    throw InputError(s.file + ": rigid_cell.random_field: " + e.what());
  }
}

template <int D>
PlateSpec<D> plate_of(const GroupSpec& g) {
  constexpr int kDofs = D + Dim<D>::rot;
  PlateSpec<D> p;
  p.name = g.name;
  p.lo = vec_of<D>(g.box_lo), p.hi = vec_of<D>(g.box_hi);
  for (int k = 0; k < kDofs; ++k) p.held[k] = (g.fix >> k) & 1u;
  for (int k = 0; k < D && !g.velocity.empty(); ++k) p.velocity[k] = g.velocity[k];
  for (int k = 0; k < Dim<D>::rot && !g.angular_velocity.empty(); ++k) p.velocity[D + k] = g.angular_velocity[k];
  p.ramp_time = g.ramp_time.value_or(0.0);
  for (int k = 0; k < D && !g.force.empty(); ++k) p.load[k] = g.force[k];
  for (int k = 0; k < Dim<D>::rot && !g.moment.empty(); ++k) p.load[D + k] = g.moment[k];
  return p;
}

FibreFamily fibre_family(const FibreFamilySpec& f) {
  FibreFamily family{f.name, f.material, {}, {}};
  FibrePlacement& p = family.placement;
  p.volume_fraction = f.volume_fraction;
  p.count = static_cast<long>(f.count);
  p.length = f.length;
  p.diameter = f.material.diameter;
  using O = FibreFamilySpec::Orientation;
  p.orientation = f.orientation == O::Aligned        ? FibreOrientation::Aligned
                  : f.orientation == O::Preferential ? FibreOrientation::Preferential
                                                     : FibreOrientation::Isotropic;
  if (!f.direction.empty()) p.direction = Vec<3>(f.direction[0], f.direction[1], f.direction[2]).normalized();
  p.concentration = f.concentration;
  p.boundary = f.cut ? FibreBoundary::Cut : FibreBoundary::Redraw;
  for (std::size_t i = 0; i + 6 <= f.ends.size(); i += 6)
    family.given.push_back({Vec<3>(f.ends[i], f.ends[i + 1], f.ends[i + 2]),
                            Vec<3>(f.ends[i + 3], f.ends[i + 4], f.ends[i + 5])});
  return family;
}

template <int D>
RigidCellSetup<D> setup_of(const Scene& s) {
  const RigidCellSpec& r = *s.rigid_cell;
  RigidCellSetup<D> setup;
  setup.shape = shape_of<D>(r.specimen);
  const CellSpecimenSpec& c = r.specimen;
  setup.spacing = {.l_min = c.l_min, .l_max = c.l_max, .grading = c.grading};
  if (c.l_max > 0)
    for (int i = 0; i < D; ++i) setup.spacing.fine_lo[i] = c.fine_lo[i], setup.spacing.fine_hi[i] = c.fine_hi[i];
  setup.seed = s.seed;
  setup.max_rejections = r.specimen.max_rejections;
  for (const auto& p : s.phases) setup.phase_names.push_back(p.name), setup.phase_density.push_back(p.density);
  // Without a mesostructure every cell is of the first phase; with one, a cell whose node lies in an aggregate
  // is aggregate, the others mortar (Tang §4.3.1, as the explicit engine's particles).
  if (s.mesostructure.fraction > 0) {
    const Vec<D> lo = setup.shape->lo(), hi = setup.shape->hi();
    auto layout = std::make_shared<const AggregateLayout<D>>(lay_aggregates<D>(s, lo, hi));
    add_aggregate_facts<D>(*layout, setup.facts);
    setup.outlines = aggregate_outlines<D>(*layout, D == 3 ? 0.5 * (lo[1] + hi[1]) : 0.0);
    const int mortar = s.mesostructure.mortar_phase, aggregate = s.mesostructure.aggregate_phase;
    setup.phase_at = [layout, mortar, aggregate](const Vec<D>& x) {
      return layout->aggregate_at(x) == 0 ? mortar : aggregate;
    };
  }
  auto table = facet_table<D>(s);
  setup.facet = [table, &s](int a, int b) {
    if (!table[a][b])
      throw InputError(s.file + ": cells of phases '" + s.phases[a].name + "' and '" + s.phases[b].name +
                       "' meet at a facet, and [[contacts]] gives no facet law between them");
    return *table[a][b];
  };
  if (r.random_field) setup.strength_field = strength_field<D>(s, *setup.shape);
  for (const GroupSpec& g : s.groups) setup.plates.push_back(plate_of<D>(g));
  for (const ProbeSpec& p : s.probes) {
    PlateGauge<D> g{p.name, p.groups[0], p.groups[1]};
    if (!p.direction.empty()) g.direction = vec_of<D>(p.direction);
    setup.gauges.push_back(g);
  }
  if (const auto& c = r.opening_control)
    setup.opening_control = OpeningDrive<D>{c->probe, c->plate, vec_of<D>(c->direction), c->rate, c->ramp_time};
  setup.load_step = s.timestep.fixed;
  setup.timestep_safety = s.timestep.safety;
  if (const auto& w = r.stress_wave)
    setup.stress_wave =
        StressWave<D>{vec_of<D>(w->box_lo), vec_of<D>(w->box_hi), w->pressure, w->duration, w->times, w->pressures};
  if (const auto& d = r.dynamics)
    setup.dynamics =
        DynamicsSpec{d->central_difference ? DynamicsSpec::Scheme::CentralDifference : DynamicsSpec::Scheme::Newmark,
                     d->beta, d->gamma, d->mass_damping, d->stiffness_damping};
  for (const SectionSpec& x : r.sections) setup.sections.push_back({x.axis, x.at});
  if (const auto& b = r.strain) setup.strain_box = {{vec_of<D>(b->box_lo), vec_of<D>(b->box_hi)}};
  setup.options = {r.damage_tolerance, r.force_tolerance, r.max_iterations};
  for (std::size_t i = 0; i + D <= r.specimen.nodes.size(); i += D)
    setup.nodes.push_back(vec_of<D>(std::vector<double>(r.specimen.nodes.begin() + static_cast<std::ptrdiff_t>(i),
                                                        r.specimen.nodes.begin() + static_cast<std::ptrdiff_t>(i + D))));
  for (const FibreFamilySpec& f : r.fibres) setup.fibres.push_back(fibre_family(f));
  setup.crack_log = r.crack_log;
  setup.facet_integration = r.facet_integration;
  return setup;
}

template <int D>
std::vector<Series> series_of(const Scene& s, const RigidCellSystem<D>* sys) {
  using W = CellSeries::What;
  std::vector<Series> out;
  for (const CellSeries& c : rigid_cell_series(s)) {
    std::function<double()> f;
    const int p = c.plate, k = c.dof;
    switch (c.what) {
      case W::Time: f = [sys] { return sys->time(); }; break;
      case W::Step: f = [sys] { return static_cast<double>(sys->step_count()); }; break;
      case W::Iterations: f = [sys] { return static_cast<double>(sys->last_iterations()); }; break;
      case W::Residual: f = [sys] { return sys->last_residual(); }; break;
      case W::Cuts: f = [sys] { return static_cast<double>(sys->last_cuts()); }; break;
      case W::SnapThroughs: f = [sys] { return static_cast<double>(sys->snap_throughs()); }; break;
      case W::FacetsDamaged: f = [sys] { return static_cast<double>(sys->facets_damaged()); }; break;
      case W::FacetsCracked: f = [sys] { return static_cast<double>(sys->facets_cracked()); }; break;
      case W::MaxDamage: f = [sys] { return sys->max_damage(); }; break;
      case W::PlateReaction: f = [sys, p, k] { return sys->plate_reaction(p, k); }; break;
      case W::PlateDisplacement: f = [sys, p, k] { return sys->plate_displacement(p, k); }; break;
      case W::PlateVelocity: f = [sys, p, k] { return sys->plate_velocity(p, k); }; break;
      case W::Opening: f = [sys, p] { return sys->opening(p); }; break;
      case W::SectionStress: f = [sys, p] { return sys->section_stress(p); }; break;
      case W::Strain: f = [sys, k] { return sys->mean_strain(k); }; break;
      case W::SectionBridging: f = [sys, p] { return sys->section_bridging_force(p); }; break;
      case W::FibresBridging: f = [sys] { return static_cast<double>(sys->fibre_counts()[0]); }; break;
      case W::FibresPulledOut: f = [sys] { return static_cast<double>(sys->fibre_counts()[1]); }; break;
      case W::FibresRuptured: f = [sys] { return static_cast<double>(sys->fibre_counts()[2]); }; break;
      case W::BoundaryWork: f = [sys] { return sys->boundary_work(); }; break;
      case W::StrainEnergy: f = [sys] { return sys->strain_energy(); }; break;
      case W::KineticEnergy: f = [sys] { return sys->kinetic_energy(); }; break;
      case W::Dissipated:
        f = [sys] { return sys->boundary_work() - sys->strain_energy() - sys->kinetic_energy(); };
        break;
    }
    out.push_back({c.name, c.unit, std::move(f)});
  }
  return out;
}

template <int D>
std::unique_ptr<System> build(const Scene& s) {
  std::unique_ptr<RigidCellSystem<D>> sys;
  try {
    sys = std::make_unique<RigidCellSystem<D>>(setup_of<D>(s));
  } catch (const InputError& e) {
    const std::string what = e.what();
    throw InputError(what.rfind(s.file, 0) == 0 ? what : s.file + ": " + what);
  }
  sys->set_histories(series_of<D>(s, sys.get()));
  if (!sys->fibres().empty())
    std::fprintf(stderr, "%s: %zu fibres placed in %.3f s, %zu crossings found in %.3f s\n", s.file.c_str(),
                 sys->fibres().size(), sys->fibre_placement_seconds(),
                 sys->bridges() ? sys->bridges()->sites() : std::size_t{0}, sys->fibre_crossing_seconds());
  return sys;
}

}  // namespace

std::unique_ptr<System> make_rigid_cell_system(const Scene& scene) {
  if (scene.dimension == 2) return build<2>(scene);
  return build<3>(scene);
}

}  // namespace mc
