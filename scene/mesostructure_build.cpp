// Tang §4.2–4.3.1 in a scene: the coarse aggregate laid over the specimen gives its mortar particles the
// aggregate phase (and so the aggregate, mortar and ITZ contact models of the phase-pair table).
#include <algorithm>

#include "engine/errors.hpp"
#include "preprocess/aggregate_placement.hpp"
#include "scene/specimen_build.hpp"

namespace mc {

namespace {

// The domain is the scene's, or else the specimen's bounding box [lo, hi].
template <int D>
PlacementSpec<D> placement_spec(const Scene& s, const Vec<D>& lo, const Vec<D>& hi) {
  const MesostructureSpec& m = s.mesostructure;
  PlacementSpec<D> spec;
  spec.lo = m.lo.empty() ? lo : vec_of<D>(m.lo);
  spec.hi = m.hi.empty() ? hi : vec_of<D>(m.hi);
  spec.grading.ranges.clear();
  for (const auto& r : m.ranges) spec.grading.ranges.push_back({r[0], r[1], r[2]});
  spec.fraction = m.fraction;
  for (std::size_t k = 0; k < m.keep_out_lo.size(); ++k)
    spec.keep_out_boxes.push_back({vec_of<D>(m.keep_out_lo[k]), vec_of<D>(m.keep_out_hi[k])});
  for (std::size_t k = 0; k < m.keep_out_centre.size(); ++k)
    spec.keep_out_balls.push_back({vec_of<D>(m.keep_out_centre[k]), m.keep_out_radius[k]});
  spec.cells_per_dmin = m.cells_per_dmin;
  spec.seed = s.seed ^ 0x6d65736fULL;  // its own stream: the packing and the aggregates do not share draws
  return spec;
}

// Mortar particles whose centres fall in an aggregate become aggregate (mass and inertia of its density); the
// fraction of the particles' volume that did (Tang Fig. 4.14) goes to the facts.
template <int D>
void assign_phases(const Scene& s, const AggregateLayout<D>& layout, Particles<D>& p,
                   std::vector<std::pair<std::string, double>>& f) {
  const MesostructureSpec& m = s.mesostructure;
  const double rho = s.phases[m.aggregate_phase].density;
  double volume_all = 0, volume_agg = 0;
  std::int64_t n_agg = 0;
  for (int i = 0; i < p.size(); ++i) {
    volume_all += Dim<D>::volume(p.radius[i]);
    if (p.phase[i] != m.mortar_phase || layout.aggregate_at(p.x[i]) == 0) continue;
    p.phase[i] = m.aggregate_phase;
    p.set_density(i, rho);
    volume_agg += Dim<D>::volume(p.radius[i]);
    ++n_agg;
  }
  f.push_back({"aggregate_particles", static_cast<double>(n_agg)});
  f.push_back({"aggregate_particle_fraction", volume_agg / volume_all});
}

}  // namespace

template <int D>
AggregateLayout<D> lay_aggregates(const Scene& s, const Vec<D>& lo, const Vec<D>& hi) {
  try {
    return place_aggregates<D>(placement_spec<D>(s, lo, hi));
  } catch (const InputError& e) {
    throw InputError(s.file + ": [mesostructure]: " + e.what());
  }
}

template <int D>
void add_aggregate_facts(const AggregateLayout<D>& layout, std::vector<std::pair<std::string, double>>& f) {
  f.push_back({"aggregate_fraction_target", layout.target_fraction});
  f.push_back({"aggregate_fraction_achieved", layout.achieved_fraction});
  f.push_back({"aggregate_target_reached", layout.reached ? 1.0 : 0.0});
  f.push_back({"aggregates", static_cast<double>(layout.aggregates.size())});
  for (std::size_t r = 0; r < layout.ranges.size(); ++r) {
    f.push_back({"aggregate_range" + std::to_string(r) + "_share_target", layout.ranges[r].target_share});
    f.push_back({"aggregate_range" + std::to_string(r) + "_share_achieved", layout.ranges[r].achieved_share});
  }
}

// Outlines for pictures: 2D polygons; 3D sections at y = y_section, as (x, z).
template <int D>
std::vector<std::vector<std::array<double, 2>>> aggregate_outlines(const AggregateLayout<D>& layout, double y_section) {
  std::vector<std::vector<std::array<double, 2>>> out;
  for (const auto& a : layout.aggregates) {
    std::vector<std::array<double, 2>> o;
    if constexpr (D == 2) {
      for (const auto& v : a.shape.v) o.push_back({v[0], v[1]});
    } else {
      for (const auto& v : section(a.shape, 1, y_section).v) o.push_back({v[1], v[0]});  // section gives (z, x)
    }
    if (!o.empty()) out.push_back(std::move(o));
  }
  return out;
}

template <int D>
void apply_mesostructure(const Scene& s, Particles<D>& p, SpecimenInfo& info) {
  if (s.mesostructure.fraction == 0) {
    info.facts.push_back({"aggregate_fraction_target", 0.0});
    return;
  }
  Vec<D> lo = p.x[0], hi = p.x[0];  // the specimen's bounding box
  for (int i = 0; i < p.size(); ++i)
    lo = lo.cwiseMin(p.x[i] - Vec<D>::Constant(p.radius[i])), hi = hi.cwiseMax(p.x[i] + Vec<D>::Constant(p.radius[i]));
  const AggregateLayout<D> layout = lay_aggregates<D>(s, lo, hi);
  add_aggregate_facts<D>(layout, info.facts);
  assign_phases<D>(s, layout, p, info.facts);
  info.outlines = aggregate_outlines<D>(layout, D == 3 ? 0.5 * (lo[1] + hi[1]) : 0.0);
}

template AggregateLayout<2> lay_aggregates<2>(const Scene&, const Vec<2>&, const Vec<2>&);
template AggregateLayout<3> lay_aggregates<3>(const Scene&, const Vec<3>&, const Vec<3>&);
template void add_aggregate_facts<2>(const AggregateLayout<2>&, std::vector<std::pair<std::string, double>>&);
template void add_aggregate_facts<3>(const AggregateLayout<3>&, std::vector<std::pair<std::string, double>>&);
template std::vector<std::vector<std::array<double, 2>>> aggregate_outlines<2>(const AggregateLayout<2>&, double);
template std::vector<std::vector<std::array<double, 2>>> aggregate_outlines<3>(const AggregateLayout<3>&, double);
template void apply_mesostructure<2>(const Scene&, Particles<2>&, SpecimenInfo&);
template void apply_mesostructure<3>(const Scene&, Particles<3>&, SpecimenInfo&);

}  // namespace mc
