#include "scene/build_world.hpp"

#include <algorithm>
#include <sstream>

#include "engine/errors.hpp"
#include "io/h5_file.hpp"
#include "preprocess/dense_packing.hpp"
#include "preprocess/aggregate_placement.hpp"
#include "preprocess/random_box.hpp"
#include "preprocess/regular_packing.hpp"
#include "preprocess/spatial_order.hpp"
#include "io/sphere_list.hpp"

namespace mc {

namespace {

template <int D>
Vec<D> v_of(const std::vector<double>& v) {
  Vec<D> out;
  for (int k = 0; k < D; ++k) out[k] = v[k];
  return out;
}
template <int D>
Rot<D> r_of(const std::vector<double>& v) {
  Rot<D> out;
  for (int k = 0; k < Dim<D>::rot; ++k) out[k] = v[k];
  return out;
}

template <int D>
void add_specimen(const Scene& s, Particles<D>& p, std::vector<int>& tags, std::vector<std::int64_t>& ids,
                  std::vector<std::pair<std::string, double>>& facts) {
  const SpecimenSpec& sp = s.specimen;
  auto density = [&](int phase) { return s.phases[phase].density; };
  switch (sp.kind) {
    case SpecimenSpec::Kind::Particles:
      for (const auto& ip : sp.particles) {
        const int i = p.add(v_of<D>(ip.x), ip.radius, density(ip.phase), ip.phase);
        p.v[i] = v_of<D>(ip.v);
        p.w[i] = r_of<D>(ip.w);
        tags.push_back(0);
      }
      break;
    case SpecimenSpec::Kind::SphereList: {
      SphereList<D> list;
      try {
        list = read_sphere_list<D>(sp.file);
      } catch (const IoError& e) {  // name the scene and its key, not only the resolved path
        throw IoError(s.file + ": key 'specimen.file': " + e.what());
      }
      for (int i = 0; i < list.size(); ++i) {
        const int tag = list.tag[i];
        int phase = 0;
        if (!sp.tag_phase.empty()) {
          if (tag < 0 || tag >= static_cast<int>(sp.tag_phase.size())) {
            std::ostringstream m;
            m << sp.file << ": particle id " << list.id[i] << " has tag " << tag << ", but specimen.tag_phases names "
              << sp.tag_phase.size() << " tags (0.." << sp.tag_phase.size() - 1 << ")";
            throw InputError(m.str());
          }
          phase = sp.tag_phase[tag];
        }
        p.add(list.x[i], list.radius[i], density(phase), phase);
        tags.push_back(tag);
        ids.push_back(list.id[i]);
      }
      break;
    }
    case SpecimenSpec::Kind::Output: {
      // The last frame of an earlier run (its final state), at rest.
      std::vector<double> radius, x;
      std::vector<std::int64_t> phase;
      try {
        const H5File f(sp.file, H5File::Mode::ReadOnly);
        radius = f.read_doubles("/specimen/radius");
        phase = f.read_ints("/specimen/phase");
        if (f.exists("/frames/x") && f.rows("/frames/x") > 0) {
          std::vector<hsize_t> dims;
          const auto all = f.read_doubles("/frames/x", &dims);
          x.assign(all.end() - static_cast<std::ptrdiff_t>(dims[1]), all.end());
        } else {
          x = f.read_doubles("/specimen/x");
        }
      } catch (const IoError& e) {  // name the scene and its key, not only the resolved path
        throw IoError(s.file + ": key 'specimen.file': " + e.what());
      }
      if (x.size() != radius.size() * D)
        throw InputError(sp.file + ": the specimen has dimension other than the scene's (" + std::to_string(D) + ")");
      for (std::size_t i = 0; i < radius.size(); ++i) {
        const int ph = static_cast<int>(phase[i]);
        if (ph < 0 || ph >= static_cast<int>(s.phases.size()))
          throw InputError(sp.file + ": particle " + std::to_string(i) + " has phase " + std::to_string(ph) +
                           ", but the scene declares " + std::to_string(s.phases.size()) + " phases");
        p.add(Vec<D>(Eigen::Map<const Vec<D>>(x.data() + D * i)), radius[i], density(ph), ph);
        tags.push_back(0);
      }
      break;
    }
    case SpecimenSpec::Kind::RandomBox: {
      Packing<D> pk;
      try {
        pk = random_box_packing<D>(v_of<D>(sp.box_lo), v_of<D>(sp.box_hi), sp.count, sp.radius_min, sp.radius_max, s.seed);
      } catch (const InputError& e) {
        throw InputError(s.file + ": key 'specimen.count' = " + std::to_string(sp.count) + ": " + e.what());
      }
      for (std::size_t i = 0; i < pk.x.size(); ++i) p.add(pk.x[i], pk.radius[i], density(sp.phase), sp.phase), tags.push_back(0);
      break;
    }
    case SpecimenSpec::Kind::Packing: {
      DensePackingSpec<D> g;
      g.shape = sp.cylinder ? DensePackingSpec<D>::Shape::Cylinder : DensePackingSpec<D>::Shape::Box;
      g.lo = v_of<D>(sp.box_lo), g.hi = v_of<D>(sp.box_hi);
      g.radius_min = sp.radius_min, g.radius_ratio = sp.radius_ratio, g.porosity = sp.porosity;
      g.stress = sp.stress, g.modulus = sp.modulus, g.density = density(sp.phase), g.seed = s.seed;
      PackingReport rep;
      Packing<D> pk;
      try {
        pk = dense_packing<D>(g, &rep);
      } catch (const InputError& e) {
        throw InputError(s.file + ": [specimen] kind = \"packing\": " + e.what());
      }
      for (std::size_t i = 0; i < pk.x.size(); ++i) p.add(pk.x[i], pk.radius[i], density(sp.phase), sp.phase), tags.push_back(0);
      facts = {{"packing_porosity_grown", rep.porosity_grown}, {"packing_porosity_final", rep.porosity_final},
               {"packing_stress_final", rep.stress_final}, {"packing_floaters", double(rep.floaters)},
               {"packing_steps", double(rep.steps)}};
      break;
    }
    case SpecimenSpec::Kind::Lattice: {
      // Row by row (2D) or layer by layer (3D): already local, no renumbering needed.
      Packing<D> pk;
      if constexpr (D == 2) pk = hexagonal_packing(v_of<2>(sp.box_lo), v_of<2>(sp.box_hi), sp.radius_min);
      else pk = fcc_packing(v_of<3>(sp.box_lo), v_of<3>(sp.box_hi), sp.radius_min);
      for (std::size_t i = 0; i < pk.x.size(); ++i) p.add(pk.x[i], pk.radius[i], density(sp.phase), sp.phase), tags.push_back(0);
      break;
    }
  }
}

template <int D>
Wall<D> make_wall(const WallSpec& w) {
  Wall<D> out;
  if (w.kind == WallSpec::Kind::Plane) {
    out = Wall<D>::plane(v_of<D>(w.point), v_of<D>(w.normal));
  } else if (w.kind == WallSpec::Kind::Segment) {
    if constexpr (D == 2) out = Wall<2>::segment(v_of<2>(w.a), v_of<2>(w.b), v_of<2>(w.inside));
  } else {
    if constexpr (D == 3) out = Wall<3>::rectangle(v_of<3>(w.point), v_of<3>(w.normal), v_of<3>(w.axis), w.size0, w.size1);
  }
  out.name = w.name;
  out.material = w.material;
  out.control = w.control;
  if (!w.velocity.empty()) out.target_velocity = v_of<D>(w.velocity);
  out.ramp_time = w.ramp_time;
  out.target_stress = w.stress;
  out.servo_area = w.servo_area;
  out.servo_gain = w.gain;
  out.servo_max_speed = w.max_speed;
  return out;
}

// Renumbers the particles of a sphere list or a generated packing along a Morton curve (cache locality);
// tags and ids travel with them. Inline particles keep the order the scene gives them.
template <int D>
void spatial_sort(Particles<D>& p, std::vector<int>& tags, std::vector<std::int64_t>& ids) {
  const std::vector<int> order = morton_order<D>(p.x);
  auto permute = [&](auto& v) {
    auto old = v;
    for (std::size_t k = 0; k < order.size(); ++k) v[k] = old[order[k]];
  };
  permute(p.x), permute(p.v), permute(p.f), permute(p.w), permute(p.m), permute(p.q);
  permute(p.radius), permute(p.mass), permute(p.inertia), permute(p.phase), permute(p.fix), permute(p.stiffness);
  permute(tags), permute(ids);
}

template <int D>
bool in_group(const GroupSpec& g, const Particles<D>& p, const std::vector<int>& tags,
              const std::vector<std::int64_t>& ids, int i) {
  if (std::find(g.tags.begin(), g.tags.end(), tags[i]) != g.tags.end()) return true;
  if (std::find(g.ids.begin(), g.ids.end(), ids[i]) != g.ids.end()) return true;
  if (!g.box_lo.empty()) {
    for (int k = 0; k < D; ++k)
      if (p.x[i][k] < g.box_lo[k] || p.x[i][k] > g.box_hi[k]) return false;
    return true;
  }
  return false;
}

template <int D>
void apply_groups(const Scene& s, World<D>& w, const std::vector<int>& tags) {
  auto& p = w.particles;
  for (const GroupSpec& g : s.groups) {
    for (std::int64_t id : g.ids)
      if (std::find(w.ids.begin(), w.ids.end(), id) == w.ids.end())
        throw InputError(s.file + ": group '" + g.name + "': particle id " + std::to_string(id) +
                         " does not exist (the specimen has " + std::to_string(p.size()) + " particles)");
    std::vector<int>& members = w.groups.emplace_back();
    for (int i = 0; i < p.size(); ++i) {
      if (!in_group(g, p, tags, w.ids, i)) continue;
      members.push_back(i);
      p.fix[i] |= g.fix;
      if (!g.velocity.empty()) p.v[i] = v_of<D>(g.velocity);
      if (!g.angular_velocity.empty()) p.w[i] = r_of<D>(g.angular_velocity);
      if (!g.force.empty() || !g.moment.empty()) {
        w.applied_loads = true;
        p.f_applied.resize(p.size(), Vec<D>::Zero());
        p.m_applied.resize(p.size(), Rot<D>::Zero());
        if (!g.force.empty()) p.f_applied[i] += v_of<D>(g.force);
        if (!g.moment.empty()) p.m_applied[i] += r_of<D>(g.moment);
      }
    }
    if (members.empty()) throw InputError(s.file + ": group '" + g.name + "' selects no particle");
  }
}

// Tang §4.2–4.3.1: aggregates laid over the specimen; mortar particles whose centres fall in one become aggregate.
template <int D>
void apply_mesostructure(const Scene& s, World<D>& w) {
  const MesostructureSpec& m = s.mesostructure;
  auto& p = w.particles;
  PlacementSpec<D> spec;
  if (!m.lo.empty()) {
    spec.lo = v_of<D>(m.lo), spec.hi = v_of<D>(m.hi);
  } else {
    spec.lo = spec.hi = p.x[0];
    for (int i = 0; i < p.size(); ++i)
      spec.lo = spec.lo.cwiseMin(p.x[i] - Vec<D>::Constant(p.radius[i])), spec.hi = spec.hi.cwiseMax(p.x[i] + Vec<D>::Constant(p.radius[i]));
  }
  spec.grading.ranges.clear();
  for (const auto& r : m.ranges) spec.grading.ranges.push_back({r[0], r[1], r[2]});
  spec.fraction = m.fraction;
  for (std::size_t k = 0; k < m.keep_out_lo.size(); ++k)
    spec.keep_out_boxes.push_back({v_of<D>(m.keep_out_lo[k]), v_of<D>(m.keep_out_hi[k])});
  for (std::size_t k = 0; k < m.keep_out_centre.size(); ++k)
    spec.keep_out_balls.push_back({v_of<D>(m.keep_out_centre[k]), m.keep_out_radius[k]});
  spec.cells_per_dmin = m.cells_per_dmin;
  spec.seed = s.seed ^ 0x6d65736fULL;  // its own stream: the packing and the aggregates do not share draws
  AggregateLayout<D> layout;
  try {
    layout = place_aggregates<D>(spec);
  } catch (const InputError& e) {
    throw InputError(s.file + ": [mesostructure]: " + e.what());
  }
  const double rho = s.phases[m.aggregate_phase].density;
  double volume_all = 0, volume_agg = 0;
  std::int64_t n_agg = 0;
  for (int i = 0; i < p.size(); ++i) {
    volume_all += Dim<D>::volume(p.radius[i]);
    if (p.phase[i] != m.mortar_phase || layout.aggregate_at(p.x[i]) == 0) continue;
    p.phase[i] = m.aggregate_phase;
    p.mass[i] = rho * Dim<D>::volume(p.radius[i]);
    p.inertia[i] = Dim<D>::inertia_factor * p.mass[i] * p.radius[i] * p.radius[i];
    volume_agg += Dim<D>::volume(p.radius[i]);
    ++n_agg;
  }
  auto& f = w.specimen_facts;
  f.push_back({"aggregate_fraction_target", layout.target_fraction});
  f.push_back({"aggregate_fraction_achieved", layout.achieved_fraction});
  f.push_back({"aggregate_target_reached", layout.reached ? 1.0 : 0.0});
  f.push_back({"aggregates", static_cast<double>(layout.aggregates.size())});
  f.push_back({"aggregate_particles", static_cast<double>(n_agg)});
  f.push_back({"aggregate_particle_fraction", volume_agg / volume_all});  // by particle area / volume (Fig. 4.14)
  for (std::size_t r = 0; r < layout.ranges.size(); ++r) {
    f.push_back({"aggregate_range" + std::to_string(r) + "_share_target", layout.ranges[r].target_share});
    f.push_back({"aggregate_range" + std::to_string(r) + "_share_achieved", layout.ranges[r].achieved_share});
  }
  // Outlines for pictures: 2D polygons; 3D sections at the middle of the specimen along y, as (x, z).
  double yc = 0;
  if constexpr (D == 3) {
    double lo = kInf, hi = -kInf;
    for (int i = 0; i < p.size(); ++i) lo = std::min(lo, p.x[i][1] - p.radius[i]), hi = std::max(hi, p.x[i][1] + p.radius[i]);
    yc = 0.5 * (lo + hi);
  }
  for (const auto& a : layout.aggregates) {
    std::vector<std::array<double, 2>> o;
    if constexpr (D == 2) {
      for (const auto& v : a.shape.v) o.push_back({v[0], v[1]});
    } else {
      for (const auto& v : section(a.shape, 1, yc).v) o.push_back({v[1], v[0]});  // section gives (z, x)
    }
    if (!o.empty()) w.outlines.push_back(std::move(o));
  }
}

template <int D>
void set_domain(const Scene& s, World<D>& w) {
  if (!s.domain_lo.empty()) {
    w.domain_lo = v_of<D>(s.domain_lo);
    w.domain_hi = v_of<D>(s.domain_hi);
    return;
  }
  // The specimen's bounding box widened by its own size (at least 100 R_max) on every side: room for any
  // sensible motion, small enough that an exploding run stops early.
  const auto& p = w.particles;
  Vec<D> lo = p.x[0], hi = p.x[0];
  for (const auto& x : p.x) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
  for (const auto& wl : w.walls)
    if (std::isfinite(wl.half[0])) lo = lo.cwiseMin(wl.origin), hi = hi.cwiseMax(wl.origin);
  const double margin = std::max((hi - lo).maxCoeff(), 100.0 * p.max_radius());
  w.domain_lo = lo.array() - margin;
  w.domain_hi = hi.array() + margin;
}

}  // namespace

template <int D>
World<D> build_world(const Scene& s) {
  World<D> w;
  std::vector<int> tags;
  add_specimen<D>(s, w.particles, tags, w.ids, w.specimen_facts);
  if (w.particles.size() == 0) throw InputError(s.file + ": the specimen holds no particle");
  if (w.ids.empty()) {
    w.ids.resize(w.particles.size());
    for (int i = 0; i < w.particles.size(); ++i) w.ids[i] = i;
  }
  using K = SpecimenSpec::Kind;
  if (s.specimen.kind == K::SphereList || s.specimen.kind == K::RandomBox || s.specimen.kind == K::Packing)
    spatial_sort<D>(w.particles, tags, w.ids);
  if (s.mesostructure.present) apply_mesostructure<D>(s, w);
  // Heterogeneity of the particles' stiffness, per phase (after the mesostructure has set the phases). Drawn
  // from the seed and the particle's index (the order is fixed for a scene), so any thread count sees the same.
  for (int i = 0; i < w.particles.size(); ++i) {
    const PhaseSpec& ph = s.phases[w.particles.phase[i]];
    if (ph.stiffness_std == 0 && ph.stiffness_weibull == 0) continue;
    PairRandom rng(s.seed ^ 0x73746966ULL, Pair{i, i});
    w.particles.stiffness[i] = rng(1.0, ph.stiffness_std, ph.stiffness_weibull);
  }
  const int np = static_cast<int>(s.phases.size());
  w.model_of.assign(np, std::vector<int>(np, -1));
  for (const ContactSpec& c : s.contacts) {
    if constexpr (D == 2) w.sets.push_back(c.model.make2());
    else w.sets.push_back(c.model.make3());
    w.model_of[c.phase_a][c.phase_b] = w.model_of[c.phase_b][c.phase_a] = static_cast<int>(w.sets.size()) - 1;
  }
  // Every pair of phases present must have a contact model: a missing one would let particles pass
  // through each other silently.
  std::vector<bool> present(np, false);
  for (int ph : w.particles.phase) present[ph] = true;
  for (int a = 0; a < np; ++a)
    for (int b = a; b < np; ++b)
      if (present[a] && present[b] && w.model_of[a][b] < 0)
        throw InputError(s.file + ": no [[contacts]] entry for phases '" + s.phases[a].name + "' and '" +
                         s.phases[b].name + "', both present in the specimen");
  for (const WallSpec& ws : s.walls) w.walls.push_back(make_wall<D>(ws));
  auto wall_index = [&](const std::string& name) {
    for (std::size_t k = 0; k < s.walls.size(); ++k)
      if (s.walls[k].name == name) return static_cast<int>(k);
    return -1;  // unreachable: read_scene checked the names
  };
  for (std::size_t k = 0; k < s.walls.size(); ++k)
    for (std::size_t j = 0; j + 1 < s.walls[k].area_between.size(); j += 2)
      w.walls[k].area_between.push_back({wall_index(s.walls[k].area_between[j]), wall_index(s.walls[k].area_between[j + 1])});
  apply_groups<D>(s, w, tags);
  if (s.gravity) w.gravity = v_of<D>(*s.gravity);
  w.local_damping = s.local_damping;
  // PFC density scaling: every particle's inertia (translational and rotational) times one factor F, so the
  // critical step (3.22)–(3.23) grows by √F. Uniform, so the particles keep their relative inertia: a run at
  // strain rate ε̇ with F behaves dynamically like one at ε̇√F without it (the ratio of loading time to wave
  // transit time is what changes), which is what the accuracy benchmark measures.
  for (int i = 0; i < w.particles.size(); ++i) w.particles.mass[i] *= s.density_scaling, w.particles.inertia[i] *= s.density_scaling;
  w.trace_energy = s.energy;
  w.timestep = s.timestep;
  w.skin = s.skin;
  set_domain<D>(s, w);
  return w;
}

template World<2> build_world<2>(const Scene&);
template World<3> build_world<3>(const Scene&);

}  // namespace mc
