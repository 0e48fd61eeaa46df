#include "scene/build_world.hpp"

#include <algorithm>
#include <sstream>

#include "engine/cell_grid.hpp"
#include "engine/errors.hpp"
#include "engine/random.hpp"
#include "scene/specimen_build.hpp"

namespace mc {

namespace {

template <int D>
Wall<D> make_wall(const WallSpec& w) {
  Wall<D> out;
  if (w.kind == WallSpec::Kind::Plane) {
    out = Wall<D>::plane(vec_of<D>(w.point), vec_of<D>(w.normal));
  } else if (w.kind == WallSpec::Kind::Segment) {
    if constexpr (D == 2) out = Wall<2>::segment(vec_of<2>(w.a), vec_of<2>(w.b), vec_of<2>(w.inside));
  } else {
    if constexpr (D == 3)
      out = Wall<3>::rectangle(vec_of<3>(w.point), vec_of<3>(w.normal), vec_of<3>(w.axis), w.size0, w.size1);
  }
  out.name = w.name;
  out.material = w.material;
  out.control = w.control;
  if (!w.velocity.empty()) out.target_velocity = vec_of<D>(w.velocity);
  out.ramp_time = w.ramp_time;
  out.target_stress = w.stress;
  out.servo_area = w.servo_area;
  out.servo_gain = w.gain;
  out.servo_max_speed = w.max_speed;
  out.retreat_speed = w.retreat_speed;
  out.opening_rate = w.opening_rate;
  out.opening_gain = w.opening_gain;
  return out;
}

// A wall strain is the change of the gap between two walls over the gap at the start, along the first wall's
// normal: the second wall must stand in front of the first, else that gap is zero or negative and the strain
// meaningless.
template <int D>
void check_wall_strains(const Scene& s, const World<D>& w) {
  for (const WallStrainSpec& g : s.wall_strains) {
    const auto& a = w.walls[g.walls[0]];
    const auto& b = w.walls[g.walls[1]];
    const double gap = (b.origin - a.origin).dot(a.normal);
    if (!(gap > 0)) {
      std::ostringstream m;
      m << s.file << ": wall_strains '" << g.name << "': wall '" << b.name << "' is " << gap << " m in front of wall '"
        << a.name << "' along its normal; the walls must face each other across a gap";
      throw InputError(m.str());
    }
  }
}

template <int D>
void add_walls(const Scene& s, World<D>& w) {
  for (const WallSpec& ws : s.walls) {
    w.walls.push_back(make_wall<D>(ws));
    if (ws.control == WallControl::Opening) w.walls.back().gauge = s.opening_gauge(ws.probe);
  }
  auto wall_index = [&](const std::string& name) {
    for (std::size_t k = 0; k < s.walls.size(); ++k)
      if (s.walls[k].name == name) return static_cast<int>(k);
    return -1;  // unreachable: read_scene checked the names
  };
  for (std::size_t k = 0; k < s.walls.size(); ++k)
    for (std::size_t j = 0; j + 1 < s.walls[k].area_between.size(); j += 2)
      w.walls[k].area_between.push_back(
          {wall_index(s.walls[k].area_between[j]), wall_index(s.walls[k].area_between[j + 1])});
  check_wall_strains(s, w);
}

template <int D>
bool in_group(const GroupSpec& g, const Particles<D>& p, const std::vector<int>& tags,
              const std::vector<std::int64_t>& ids, int i) {
  if (std::find(g.tags.begin(), g.tags.end(), tags[i]) != g.tags.end()) return true;
  if (std::find(g.ids.begin(), g.ids.end(), ids[i]) != g.ids.end()) return true;
  return !g.box_lo.empty() && in_box<D>(p.x[i], g.box_lo, g.box_hi);
}

// Each group's members, fixities, initial velocities and applied loads.
template <int D>
void apply_groups(const Scene& s, World<D>& w, const std::vector<int>& tags, SpecimenInfo& info) {
  auto& p = w.particles;
  for (const GroupSpec& g : s.groups) {
    for (std::int64_t id : g.ids)
      if (std::find(info.ids.begin(), info.ids.end(), id) == info.ids.end())
        throw InputError(s.file + ": group '" + g.name + "': particle id " + std::to_string(id) +
                         " does not exist (the specimen has " + std::to_string(p.size()) + " particles)");
    std::vector<int>& members = info.groups.emplace_back();
    for (int i = 0; i < p.size(); ++i) {
      if (!in_group(g, p, tags, info.ids, i)) continue;
      members.push_back(i);
      p.fix[i] |= g.fix;
      if (!g.velocity.empty()) p.v[i] = vec_of<D>(g.velocity);
      if (!g.angular_velocity.empty()) p.w[i] = rot_of<D>(g.angular_velocity);
      if (!g.force.empty() || !g.moment.empty()) {
        w.applied_loads = true;
        p.f_applied.resize(p.size(), Vec<D>::Zero());
        p.m_applied.resize(p.size(), Rot<D>::Zero());
        if (!g.force.empty()) p.f_applied[i] += vec_of<D>(g.force);
        if (!g.moment.empty()) p.m_applied[i] += rot_of<D>(g.moment);
      }
    }
    if (members.empty()) throw InputError(s.file + ": group '" + g.name + "' selects no particle");
    if (g.ramp_time) {
      DrivenGroup<D>& dg = w.driven.emplace_back();
      dg.members = members, dg.velocity = vec_of<D>(g.velocity), dg.ramp_time = *g.ramp_time;
      for (int i : members) p.v[i] = dg.velocity_at(0);  // the ramp starts from rest
    }
  }
}

// One opening gauge per opening probe, in their order: its sides (two particles by id, or two groups), its
// direction (given, or from the first side to the second) and its separation at the start.
template <int D>
void add_gauges(const Scene& s, World<D>& w, const SpecimenInfo& info) {
  for (const ProbeSpec& p : s.probes) {
    if (p.kind != ProbeSpec::Kind::Opening) continue;
    OpeningGauge<D> g;
    if (p.groups[0] >= 0) {
      g.a = info.groups[p.groups[0]], g.b = info.groups[p.groups[1]];
    } else {
      for (int k = 0; k < 2; ++k) {
        const auto it = std::find(info.ids.begin(), info.ids.end(), p.particles[k]);
        if (it == info.ids.end())
          throw InputError(s.file + ": probe '" + p.name + "': particle " + std::to_string(p.particles[k]) +
                           " does not exist (the specimen has " + std::to_string(w.particles.size()) +
                           " particles; probes name them by their specimen ids)");
        (k == 0 ? g.a : g.b).push_back(static_cast<int>(it - info.ids.begin()));
      }
    }
    const Vec<D> dir = p.direction.empty() ? g.span(w.particles) : vec_of<D>(p.direction);
    if (!(dir.norm() > 0))
      throw InputError(s.file + ": probe '" + p.name +
                       "': its two sides have the same centre at the start, so the "
                       "opening has no direction; give 'direction'");
    g.direction = dir.normalized();
    g.start = g.separation(w.particles);
    w.gauges.push_back(std::move(g));
  }
}

// Particles with the same centre have no contact normal, and particles placed deeper than half the smaller radius
// inside each other are pushed through rather than apart (the engine stops such a run): both are refused here,
// naming the particles by the specimen's ids.
template <int D>
void check_spacing(const Scene& s, const Particles<D>& p, const SpecimenInfo& info) {
  for (const Pair& pr : candidate_pairs<D>(p.x, p.radius, 0.0)) {
    const auto [i, j] = pr;
    const double d = (p.x[j] - p.x[i]).norm(), rmin = std::min(p.radius[i], p.radius[j]);
    const std::string both = "particles " + std::to_string(info.ids[i]) + " and " + std::to_string(info.ids[j]);
    if (d <= 1e-9 * rmin)  // of the smaller: beside a huge particle a small one is inside it, not at its centre
      throw InputError(s.file + ": " + both + " of the specimen have the same centre; move one of them");
    const double overlap = p.radius[i] + p.radius[j] - d;
    if (overlap > 0.5 * rmin) {
      std::ostringstream m;
      m << s.file << ": " << both << " of the specimen overlap by " << overlap / rmin
        << " of the smaller radius at the start; no contact law holds particles that deep inside each other apart: "
           "place them at most half the smaller radius into each other";
      throw InputError(m.str());
    }
  }
}

// Heterogeneity of the particles' stiffness, per phase (Tang §8.1.2), after the mesostructure has set the
// phases. Drawn from the seed and the particle's index (the order is fixed for a scene): any thread count sees
// the same.
template <int D>
void draw_stiffness_factors(const Scene& s, Particles<D>& p) {
  for (int i = 0; i < p.size(); ++i) {
    const PhaseSpec& ph = s.phases[p.phase[i]];
    if (ph.stiffness_std == 0 && ph.stiffness_weibull_shape == 0) continue;
    PairRandom rng(s.seed ^ 0x73746966ULL, Pair{i, i});
    p.stiffness[i] = rng(1.0, ph.stiffness_std, ph.stiffness_weibull_shape);
  }
}

// The contact-model table: one contact set per [[contacts]] entry, and the set of each pair of phases. Every
// pair of phases present must have one: a missing one would let particles pass through each other silently.
template <int D>
void add_contact_sets(const Scene& s, World<D>& w) {
  const int np = static_cast<int>(s.phases.size());
  w.model_of.assign(np, std::vector<int>(np, -1));
  for (const ContactSpec& c : s.contacts) {
    if constexpr (D == 2)
      w.sets.push_back(c.model.make2());
    else
      w.sets.push_back(c.model.make3());
    w.model_of[c.phase_a][c.phase_b] = w.model_of[c.phase_b][c.phase_a] = static_cast<int>(w.sets.size()) - 1;
  }
  std::vector<bool> present(np, false);
  for (int ph : w.particles.phase) present[ph] = true;
  for (int a = 0; a < np; ++a)
    for (int b = a; b < np; ++b)
      if (present[a] && present[b] && w.model_of[a][b] < 0)
        throw InputError(s.file + ": no [[contacts]] entry for phases '" + s.phases[a].name + "' and '" +
                         s.phases[b].name + "', both present in the specimen");
}

// A declared domain holds the whole specimen at the start: a particle outside it would stop the run at the
// first check, blamed on an instability that never happened.
template <int D>
void check_inside_domain(const Scene& s, const World<D>& w, const SpecimenInfo& info) {
  const auto& p = w.particles;
  for (int i = 0; i < p.size(); ++i)
    for (int k = 0; k < D; ++k)
      if (!(p.x[i][k] >= w.domain_lo[k] && p.x[i][k] <= w.domain_hi[k])) {
        std::ostringstream m;
        m << s.file << ": [physics] domain_lo/domain_hi: particle " << info.ids[i] << " lies outside ("
          << "coordinate "
          << "xyz"[k] << " = " << p.x[i][k] << " m, domain " << w.domain_lo[k] << " .. " << w.domain_hi[k]
          << " m); the domain must hold the whole specimen";
        throw InputError(m.str());
      }
}

template <int D>
void set_domain(const Scene& s, World<D>& w, const SpecimenInfo& info) {
  if (!s.domain_lo.empty()) {
    w.domain_lo = vec_of<D>(s.domain_lo);
    w.domain_hi = vec_of<D>(s.domain_hi);
    check_inside_domain(s, w, info);
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

// The effects the scene declares, and nothing else.
template <int D>
void set_physics(const Scene& s, World<D>& w) {
  if (s.gravity) w.gravity = vec_of<D>(*s.gravity);
  w.local_damping = s.local_damping;
  // PFC density scaling: every particle's inertia (translational and rotational) times one factor F, so the
  // critical step (3.22)–(3.23) grows by √F. Uniform, so the particles keep their relative inertia: a run at
  // strain rate ε̇ with F behaves dynamically like one at ε̇√F without it (the ratio of loading time to wave
  // transit time is what changes), which is what the accuracy benchmark measures.
  auto& p = w.particles;
  for (int i = 0; i < p.size(); ++i) p.mass[i] *= s.density_scaling, p.inertia[i] *= s.density_scaling;
  w.trace_energy = s.energy;
  w.timestep = s.timestep;
  w.skin = s.skin;
  w.rebuild_interval = s.rebuild_interval;
}

}  // namespace

template <int D>
World<D> build_world(const Scene& s, SpecimenInfo& info) {
  World<D> w;
  std::vector<int> tags;
  add_specimen<D>(s, w.particles, tags, info);
  check_spacing<D>(s, w.particles, info);
  if (s.mesostructure.present) apply_mesostructure<D>(s, w.particles, info);
  draw_stiffness_factors<D>(s, w.particles);
  add_contact_sets<D>(s, w);
  add_walls<D>(s, w);
  apply_groups<D>(s, w, tags, info);
  add_gauges<D>(s, w, info);
  set_physics<D>(s, w);
  set_domain<D>(s, w, info);
  // Stress and coordination read every contact of a region, and frames may record the contacts: only then are the
  // pairs' forces kept.
  for (const RegionSpec& r : s.regions)
    if (r.stress || r.coordination) w.keep_contact_forces();
  if (s.frame_contacts) w.keep_contact_forces();
  return w;
}

template World<2> build_world<2>(const Scene&, SpecimenInfo&);
template World<3> build_world<3>(const Scene&, SpecimenInfo&);

}  // namespace mc
