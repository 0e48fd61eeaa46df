#include "scene/explicit_system.hpp"

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <sstream>

#include "engine/errors.hpp"

namespace mc {

namespace {

// A fixed timestep the engine refuses, worded as the scene said it, naming the key.
std::string timestep_message(const Scene& s, const TimestepError& e) {
  std::ostringstream m;
  m << s.file << ": key 'timestep.fixed' = " << s.timestep.fixed << " s: " << e.what()
    << "; use a value below it, or leave timestep.fixed unset to let the engine choose";
  return m.str();
}

// Runs f, before the run: a refused fixed timestep is bad input.
template <class F>
void with_scene_timestep(const Scene& s, F&& f) {
  try {
    f();
  } catch (const TimestepError& e) {
    throw InputError(timestep_message(s, e));
  }
}

}  // namespace

template <int D>
ExplicitSystem<D>::ExplicitSystem(const Scene& scene, const Exchange* exchange, double imbalance_limit)
    : scene_(scene), exchange_(exchange), world_(build_world<D>(scene, info_)), obs_(scene) {
  world_.imbalance_limit = imbalance_limit;
  world_.ids = info_.ids;  // the engine's messages name particles as the specimen does
  check_probes();
  if (splits()) view_ = world_.particles, view_gauges_ = world_.gauges;
  const Observed<D> view = splits() ? Observed<D>{&view_, &info_.groups, &world_.walls, &view_gauges_}
                                    : Observed<D>{&world_.particles, &info_.groups, &world_.walls, &world_.gauges};
  series_ = make_series<D>(scene, &world_, view, &info_, &obs_);
}

template <int D>
void ExplicitSystem<D>::split() {
  if (!splits()) return;
  specimen_ = specimen();
  view_ = world_.particles;
  view_gauges_ = world_.gauges;
  world_.split(*exchange_);
  split_counts_ = own_counts();
}

// The particles each process owns now, by process (collective).
template <int D>
std::vector<std::int64_t> ExplicitSystem<D>::own_counts() const {
  Bytes mine;
  put_bytes(mine, static_cast<std::int64_t>(world_.own_count()));
  std::vector<std::int64_t> counts;
  for (const Bytes& b : exchange_->all_gather(mine)) {
    std::size_t at = 0;
    counts.push_back(take_bytes<std::int64_t>(b, at));
  }
  return counts;
}

template <int D>
std::string ExplicitSystem<D>::balance_report() const {
  if (!splits()) return "";
  const auto range = [](const std::vector<std::int64_t>& c) {
    const auto [lo, hi] = std::minmax_element(c.begin(), c.end());
    const double mean = static_cast<double>(std::accumulate(c.begin(), c.end(), std::int64_t{0})) / c.size();
    char text[96];
    std::snprintf(text, sizeof text, "%lld-%lld (most %.1f %% over the mean)", static_cast<long long>(*lo),
                  static_cast<long long>(*hi), 100 * (*hi / mean - 1));
    return std::string(text);
  };
  const std::int64_t n = world_.rebalances();
  return "particles owned per rank " + range(split_counts_) + " when split, " + range(own_counts()) + " at the end; " +
         std::to_string(n) + (n == 1 ? " rebalance" : " rebalances");
}

// Every process sends every other the motion and forces of the particles it owns: the whole view is then the
// whole world's, on each process alike.
template <int D>
void ExplicitSystem<D>::before_row() {
  // Only groups, probes and analyses read the view.
  const bool viewed = !scene_.groups.empty() || !scene_.probes.empty() || !scene_.analyses.empty();
  if (!splits() || !viewed) return;
  const auto& p = world_.particles;
  Bytes mine;
  for (int i = 0; i < p.size(); ++i) {
    if (p.is_ghost(i)) continue;
    put_bytes(mine, world_.global_index(i));
    put_bytes(mine, p.x[i]), put_bytes(mine, p.v[i]), put_bytes(mine, p.f[i]), put_bytes(mine, p.w[i]);
  }
  for (const Bytes& b : exchange_->all_gather(mine))
    for (std::size_t at = 0; at < b.size();) {
      const auto g = take_bytes<std::int64_t>(b, at);
      view_.x[g] = take_bytes<Vec<D>>(b, at), view_.v[g] = take_bytes<Vec<D>>(b, at);
      view_.f[g] = take_bytes<Vec<D>>(b, at), view_.w[g] = take_bytes<Rot<D>>(b, at);
    }
}

template <int D>
void ExplicitSystem<D>::check_probes() const {
  for (const auto& p : scene_.probes)
    for (std::int64_t id : p.particles)
      if (std::find(info_.ids.begin(), info_.ids.end(), id) == info_.ids.end())
        throw InputError(scene_.file + ": probe '" + p.name + "': particle " + std::to_string(id) +
                         " does not exist (the specimen has " + std::to_string(world_.particles.size()) +
                         " particles; probes name them by their specimen ids)");
}

template <int D>
void ExplicitSystem<D>::start() {
  with_scene_timestep(scene_, [&] { world_.init(); });
  if (scene_.bond_tolerance >= 0) install_bonds();
  if (scene_.energy) {
    world_.update_energy();
    world_.energy.initial = world_.energy.kinetic + world_.energy.strain;
  }
  split();
}

// Bonds, and how many each phase pair got (mortar, aggregate, ITZ …): written with the specimen.
template <int D>
void ExplicitSystem<D>::install_bonds() {
  with_scene_timestep(scene_, [&] { world_.install_bonds(scene_.bond_tolerance, scene_.seed); });
  std::size_t bonds = 0;
  bool bonding = false;
  for (std::size_t c = 0; c < scene_.contacts.size(); ++c)
    if (scene_.contacts[c].model.bonds) {
      bonding = true;
      bonds += world_.sets[c]->bond_count();
      info_.facts.push_back({"bonds_" + scene_.phases[scene_.contacts[c].phase_a].name + "-" +
                                 scene_.phases[scene_.contacts[c].phase_b].name,
                             static_cast<double>(world_.sets[c]->bond_count())});
    }
  // Bonded coordination number: bonds per particle, each bond counted at both ends (2 N_b / N).
  if (bonding) info_.facts.push_back({"bonded_coordination", 2.0 * bonds / world_.particles.size()});
}

template <int D>
void ExplicitSystem<D>::step() {
  try {
    world_.step();
  } catch (const TimestepError& e) {
    // Refused mid-run (the contacts stiffened since the start): an in-run failure like any instability.
    throw InstabilityError(timestep_message(scene_, e));
  }
  if (!scene_.regions.empty()) obs_.every_step(world_, scene_);
}

template <int D>
SpecimenData ExplicitSystem<D>::specimen() const {
  if (world_.is_split()) return specimen_;
  const auto& p = world_.particles;
  SpecimenData d{D, {}, p.radius, {}, {}, info_.ids, info_.facts, info_.outlines, {}, {}};
  for (const auto& x : p.x) d.x.insert(d.x.end(), x.data(), x.data() + D);
  d.phase.assign(p.phase.begin(), p.phase.end());
  for (const auto& ph : scene_.phases) d.phase_names.push_back(ph.name);
  return d;
}

template <int D>
void ExplicitSystem<D>::frame(std::vector<double>& x, std::vector<double>& v, std::vector<double>& f) const {
  const auto& p = world_.particles;
  x.clear(), v.clear(), f.clear();
  // A split world's frame is gathered on process 0 (the others get none); a whole world's is read in place.
  const bool split = world_.is_split();
  const auto gathered = split ? world_.gather_whole({&p.x, &p.v, &p.f}) : std::vector<std::vector<Vec<D>>>{};
  const auto &xs = split ? gathered[0] : p.x, &vs = split ? gathered[1] : p.v, &fs = split ? gathered[2] : p.f;
  for (std::size_t i = 0; i < xs.size(); ++i)
    for (int k = 0; k < D; ++k) x.push_back(xs[i][k]), v.push_back(vs[i][k]), f.push_back(fs[i][k]);
}

// Each contact's force on B split along the branch vector n = (x_B − x_A)/|x_B − x_A|: F·n > 0 pushes B away from A
// (compression), and the rest is the shear force.
template <int D>
ContactFrame ExplicitSystem<D>::contact_frame() const {
  ContactFrame c;
  if (!scene_.frame_contacts) return c;
  c.recorded = true;
  for (const ContactRow<D>& r : world_.gather_contacts()) {
    const double length = r.branch.norm();
    const double normal = length > 0 ? r.force.dot(r.branch) / length : 0.0;
    const Vec<D> shear = length > 0 ? Vec<D>(r.force - normal * r.branch / length) : r.force;
    c.pair.insert(c.pair.end(), {r.a, r.b});
    c.bonded.push_back(r.bonded);
    c.normal_force.push_back(normal);
    c.shear_force.push_back(shear.norm());
    c.branch.insert(c.branch.end(), r.branch.data(), r.branch.data() + D);
  }
  return c;
}

template <int D>
std::vector<std::string> ExplicitSystem<D>::crack_models() const {
  std::vector<std::string> models;
  if (scene_.crack_log)
    for (const auto& s : world_.sets) models.push_back(s->model());
  return models;
}

template <int D>
CrackRows ExplicitSystem<D>::cracks(std::size_t first) const {
  CrackRows r;
  for (std::size_t k = first; k < world_.cracks.size(); ++k) {
    const Crack<D>& c = world_.cracks[k];
    r.add(c, info_.ids[c.a], info_.ids[c.b]);
  }
  return r;
}

// The world's state, and the strains its measurement regions have integrated so far.
template <int D>
void ExplicitSystem<D>::save(Archive& a) const {
  world_.save(a);
  std::vector<double> strains;
  for (const auto& si : obs_.strain) strains.insert(strains.end(), si.strain.data(), si.strain.data() + D * D);
  a.reals["region_strains"] = strains;
}

template <int D>
void ExplicitSystem<D>::restore(const Archive& a) {
  if (a.reals.at("x").size() != static_cast<std::size_t>(world_.particles.size() * D))
    throw InputError(
        "its checkpoint holds a different specimen than the scene builds; resume with the scene that wrote it");
  world_.restore(a);
  std::vector<double> strains;
  a.get("region_strains", strains);
  if (strains.size() != obs_.strain.size() * D * D)
    throw InputError("its checkpoint holds " + std::to_string(strains.size() / (D * D)) +
                     " measurement regions, the "
                     "scene declares " +
                     std::to_string(obs_.strain.size()) + "; resume with the scene that wrote it");
  std::size_t k = 0;
  for (auto& si : obs_.strain)
    for (int i = 0; i < D * D; ++i) si.strain.data()[i] = strains[k++];
  split();
}

template class ExplicitSystem<2>;
template class ExplicitSystem<3>;

}  // namespace mc
