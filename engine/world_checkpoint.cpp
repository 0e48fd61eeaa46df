// The world's complete dynamic state as an Archive (checkpoints): restoring it and stepping on gives the same bits
// as never stopping.
#include <cstring>
#include <new>
#include <stdexcept>
#include <utility>

#include "engine/errors.hpp"
#include "engine/world.hpp"

namespace mc {

namespace {

// The crack log's bytes with the padding between members zeroed (a crack made on the stack carries whatever was
// there), so that the same run writes the same checkpoint.
template <int D>
std::vector<std::uint8_t> crack_bytes(const std::vector<Crack<D>>& cracks) {
  std::vector<std::uint8_t> out(cracks.size() * sizeof(Crack<D>), 0);
  for (std::size_t k = 0; k < cracks.size(); ++k) {
    const Crack<D>& from = cracks[k];
    auto* to = new (out.data() + k * sizeof(Crack<D>)) Crack<D>;
    to->step = from.step, to->time = from.time, to->a = from.a, to->b = from.b;
    to->position = from.position, to->normal = from.normal, to->mode = from.mode, to->kind = from.kind;
    to->set = from.set, to->phase_a = from.phase_a, to->phase_b = from.phase_b;
  }
  return out;
}

}  // namespace

template <int D>
void World<D>::save(Archive& a) const {
  if (split_) {
    save_split(a);
    return;
  }
  std::vector<std::vector<std::uint8_t>> set_bytes;
  for (const auto& s : sets) set_bytes.push_back(s->save());
  std::vector<Vec<D>> contact_f;
  for (std::size_t s = 0; s < sets.size(); ++s) {
    if (keep_forces_) {
      const auto first = slots_.pair_force.begin() + static_cast<std::ptrdiff_t>(pair_offset_[s]);
      contact_f.insert(contact_f.end(), first, first + static_cast<std::ptrdiff_t>(sets[s]->pairs().size()));
    }
    const auto first = slots_.f.begin() + static_cast<std::ptrdiff_t>(wall_offset_[s]);
    contact_f.insert(contact_f.end(), first, first + static_cast<std::ptrdiff_t>(sets[s]->wall_pairs().size()));
  }
  write_archive(a, particles, x_at_rebuild_, std::move(set_bytes), contact_f);
}

template <int D>
void World<D>::write_archive(Archive& a, const Particles<D>& p, const std::vector<Vec<D>>& x_at_rebuild,
                             std::vector<std::vector<std::uint8_t>> set_bytes,
                             const std::vector<Vec<D>>& contact_f) const {
  a.put("radius", p.radius);
  a.put("stiffness", p.stiffness);
  a.put("mass", p.mass);
  a.put("inertia", p.inertia);
  a.bytes["fix"] = p.fix;
  a.reals["phase"] = std::vector<double>(p.phase.begin(), p.phase.end());
  a.put("x", p.x);
  a.put("v", p.v);
  a.put("f", p.f);
  a.put("w", p.w);
  a.put("x_at_rebuild", x_at_rebuild);
  a.put("wall_at_rebuild", wall_at_rebuild_);
  std::vector<double> wl;
  for (const auto& w : walls) {
    for (const Vec<D>* v : {&w.origin, &w.velocity, &w.displacement, &w.force})
      wl.insert(wl.end(), v->data(), v->data() + D);
    wl.insert(wl.end(), w.moment.data(), w.moment.data() + Dim<D>::rot);
    wl.push_back(w.contact_kn);
  }
  a.reals["walls"] = wl;
  // The gauges' separations at the start: an opening servo's reading is measured from them.
  if (!gauges.empty()) {
    std::vector<double> g;
    for (const auto& gauge : gauges) g.push_back(gauge.start);
    a.reals["gauges"] = g;
  }
  for (std::size_t s = 0; s < set_bytes.size(); ++s) a.bytes["set" + std::to_string(s)] = std::move(set_bytes[s]);
  // The last step's contact forces, set by set (the ball pairs' only when kept, then the wall contacts'): the servo
  // gain and the timestep refresh read the walls' before the next force pass, the measurements the pairs'.
  a.put("contact_f", contact_f);
  a.bytes["cracks"] = crack_bytes(cracks);
  a.reals["scalars"] = {dt,
                        dt_critical,
                        time,
                        static_cast<double>(step_count),
                        static_cast<double>(rebuilds),
                        moved_,
                        ke_half_,
                        skin,
                        skin_floor_,
                        skin_ceiling_,
                        static_cast<double>(step_at_rebuild_)};
  const EnergyTrace& e = energy;
  a.reals["energy"] = {e.body_work, e.boundary_work, e.dissipated_contacts, e.dissipated_local, e.kinetic,
                       e.strain,    e.initial,       e.dissipated_bonds};
}

template <int D>
void World<D>::restore(const Archive& a) {
  if (split_) throw std::logic_error("World::restore: restore the whole world, then split it");
  auto& p = particles;
  a.get("radius", p.radius);
  a.get("stiffness", p.stiffness);
  a.get("mass", p.mass);
  a.get("inertia", p.inertia);
  p.fix = a.bytes.at("fix");
  const auto& ph = a.reals.at("phase");
  p.phase.assign(ph.begin(), ph.end());
  a.get("x", p.x);
  a.get("v", p.v);
  a.get("f", p.f);
  a.get("w", p.w);
  a.get("x_at_rebuild", x_at_rebuild_);
  a.get("wall_at_rebuild", wall_at_rebuild_);
  const auto& wl = a.reals.at("walls");
  const std::size_t per_wall = 4 * D + Dim<D>::rot + 1;
  std::size_t nsets = 0;
  while (a.bytes.count("set" + std::to_string(nsets))) ++nsets;
  if (wl.size() != walls.size() * per_wall || nsets != sets.size())
    throw InputError("the checkpoint holds " + std::to_string(wl.size() / per_wall) + " walls and " +
                     std::to_string(nsets) + " contact models, the scene builds " + std::to_string(walls.size()) +
                     " and " + std::to_string(sets.size()) + ": resume with the scene that wrote it");
  std::size_t k = 0;
  for (auto& w : walls) {
    for (Vec<D>* v : {&w.origin, &w.velocity, &w.displacement, &w.force})
      for (int d = 0; d < D; ++d) (*v)[d] = wl[k++];
    for (int d = 0; d < Dim<D>::rot; ++d) w.moment[d] = wl[k++];
    w.contact_kn = wl[k++];
  }
  if (!gauges.empty()) {
    std::vector<double> g;
    a.get("gauges", g);
    if (g.size() != gauges.size())
      throw InputError("the checkpoint holds " + std::to_string(g.size()) + " opening gauges, the scene declares " +
                       std::to_string(gauges.size()) + ": resume with the scene that wrote it");
    for (std::size_t k = 0; k < g.size(); ++k) gauges[k].start = g[k];
  }
  for (std::size_t s = 0; s < sets.size(); ++s) sets[s]->load(a.bytes.at("set" + std::to_string(s)));
  const auto& sc = a.reals.at("scalars");
  dt = sc[0], dt_critical = sc[1], time = sc[2];
  step_count = static_cast<std::int64_t>(sc[3]);
  rebuilds = static_cast<std::int64_t>(sc[4]);
  moved_ = sc[5], ke_half_ = sc[6], skin = sc[7];
  if (sc.size() != 11)
    throw InputError("the checkpoint's scalar record has " + std::to_string(sc.size()) +
                     " values, this version writes 11: resume it with the version that wrote it");
  skin_floor_ = sc[8], skin_ceiling_ = sc[9], step_at_rebuild_ = static_cast<std::int64_t>(sc[10]);
  const auto& e = a.reals.at("energy");
  if (e.size() != 8)
    throw InputError("the checkpoint's energy record has " + std::to_string(e.size()) +
                     " terms, this version writes 8: resume it with the version that wrote it");
  energy = EnergyTrace{};
  energy.body_work = e[0], energy.boundary_work = e[1], energy.dissipated_contacts = e[2];
  energy.dissipated_local = e[3], energy.kinetic = e[4], energy.strain = e[5], energy.initial = e[6];
  energy.dissipated_bonds = e[7];
  // Slots, offsets and gather lists follow from the restored pair lists; no contact is re-detected, so the
  // next step sees exactly the lists it would have seen.
  relink();
  std::vector<Vec<D>> contact_f;
  a.get("contact_f", contact_f);
  std::size_t expected = 0;
  for (const auto& s : sets) expected += (keep_forces_ ? s->pairs().size() : 0) + s->wall_pairs().size();
  if (contact_f.size() != expected)
    throw InputError("the checkpoint holds " + std::to_string(contact_f.size()) + " contact forces where this scene " +
                     (keep_forces_ ? "(which measures single contacts)" : "(which measures no single contact)") +
                     " needs " + std::to_string(expected) + ": resume it with the scene that wrote it");
  auto at = contact_f.begin();
  for (std::size_t s = 0; s < sets.size(); ++s) {
    const auto np = static_cast<std::ptrdiff_t>(sets[s]->pairs().size());
    const auto nw = static_cast<std::ptrdiff_t>(sets[s]->wall_pairs().size());
    if (keep_forces_) {
      std::copy(at, at + np, slots_.pair_force.begin() + static_cast<std::ptrdiff_t>(pair_offset_[s]));
      at += np;
    }
    std::copy(at, at + nw, slots_.f.begin() + static_cast<std::ptrdiff_t>(wall_offset_[s]));
    at += nw;
  }
  slots_.mark_all_live();
  // The crack log and its counts.
  const auto& cb = a.bytes.at("cracks");
  cracks.resize(cb.size() / sizeof(Crack<D>));
  std::memcpy(static_cast<void*>(cracks.data()), cb.data(), cb.size());
  const int np = static_cast<int>(model_of.size());
  crack_counts_.assign(2 * 3 * np * np, 0);
  for (const auto& c : cracks)
    ++crack_counts_[((int(c.kind) * 3 + int(c.mode)) * np + std::min(c.phase_a, c.phase_b)) * np +
                    std::max(c.phase_a, c.phase_b)];
}

template void World<2>::write_archive(Archive&, const Particles<2>&, const std::vector<Vec<2>>&,
                                      std::vector<std::vector<std::uint8_t>>, const std::vector<Vec<2>>&) const;
template void World<3>::write_archive(Archive&, const Particles<3>&, const std::vector<Vec<3>>&,
                                      std::vector<std::vector<std::uint8_t>>, const std::vector<Vec<3>>&) const;
template void World<2>::save(Archive&) const;
template void World<3>::save(Archive&) const;
template void World<2>::restore(const Archive&);
template void World<3>::restore(const Archive&);

}  // namespace mc
