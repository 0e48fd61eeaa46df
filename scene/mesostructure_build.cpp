// Tang §4.2–4.3.1 in a scene: the coarse aggregate laid over the specimen gives its mortar particles the
// aggregate phase (and so the aggregate, mortar and ITZ contact models of the phase-pair table).
#include <algorithm>

#include "engine/errors.hpp"
#include "preprocess/aggregate_placement.hpp"
#include "scene/specimen_build.hpp"

namespace mc {

namespace {

template <int D>
PlacementSpec<D> placement_spec(const Scene& s, const Particles<D>& p) {
  const MesostructureSpec& m = s.mesostructure;
  PlacementSpec<D> spec;
  if (!m.lo.empty()) {
    spec.lo = vec_of<D>(m.lo), spec.hi = vec_of<D>(m.hi);
  } else {  // the specimen's bounding box
    spec.lo = spec.hi = p.x[0];
    for (int i = 0; i < p.size(); ++i)
      spec.lo = spec.lo.cwiseMin(p.x[i] - Vec<D>::Constant(p.radius[i])),
      spec.hi = spec.hi.cwiseMax(p.x[i] + Vec<D>::Constant(p.radius[i]));
  }
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
// fractions achieved, by the aggregates and by the particles (Tang Fig. 4.14), go to the facts.
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
  f.push_back({"aggregate_fraction_target", layout.target_fraction});
  f.push_back({"aggregate_fraction_achieved", layout.achieved_fraction});
  f.push_back({"aggregate_target_reached", layout.reached ? 1.0 : 0.0});
  f.push_back({"aggregates", static_cast<double>(layout.aggregates.size())});
  f.push_back({"aggregate_particles", static_cast<double>(n_agg)});
  f.push_back({"aggregate_particle_fraction", volume_agg / volume_all});
  for (std::size_t r = 0; r < layout.ranges.size(); ++r) {
    f.push_back({"aggregate_range" + std::to_string(r) + "_share_target", layout.ranges[r].target_share});
    f.push_back({"aggregate_range" + std::to_string(r) + "_share_achieved", layout.ranges[r].achieved_share});
  }
}

// Outlines for pictures: 2D polygons; 3D sections at the middle of the specimen along y, as (x, z).
template <int D>
std::vector<std::vector<std::array<double, 2>>> outlines(const AggregateLayout<D>& layout, const Particles<D>& p) {
  double yc = 0;
  if constexpr (D == 3) {
    double lo = kInf, hi = -kInf;
    for (int i = 0; i < p.size(); ++i)
      lo = std::min(lo, p.x[i][1] - p.radius[i]), hi = std::max(hi, p.x[i][1] + p.radius[i]);
    yc = 0.5 * (lo + hi);
  }
  std::vector<std::vector<std::array<double, 2>>> out;
  for (const auto& a : layout.aggregates) {
    std::vector<std::array<double, 2>> o;
    if constexpr (D == 2) {
      for (const auto& v : a.shape.v) o.push_back({v[0], v[1]});
    } else {
      for (const auto& v : section(a.shape, 1, yc).v) o.push_back({v[1], v[0]});  // section gives (z, x)
    }
    if (!o.empty()) out.push_back(std::move(o));
  }
  return out;
}

}  // namespace

template <int D>
void apply_mesostructure(const Scene& s, Particles<D>& p, SpecimenInfo& info) {
  if (s.mesostructure.fraction == 0) {
    info.facts.push_back({"aggregate_fraction_target", 0.0});
    return;
  }
  AggregateLayout<D> layout;
  try {
    layout = place_aggregates<D>(placement_spec<D>(s, p));
  } catch (const InputError& e) {
    throw InputError(s.file + ": [mesostructure]: " + e.what());
  }
  assign_phases<D>(s, layout, p, info.facts);
  info.outlines = outlines<D>(layout, p);
}

template void apply_mesostructure<2>(const Scene&, Particles<2>&, SpecimenInfo&);
template void apply_mesostructure<3>(const Scene&, Particles<3>&, SpecimenInfo&);

}  // namespace mc
