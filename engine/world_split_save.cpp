// What leaves a split world whole: its checkpoint, the whole world's state gathered into process 0's archive, and
// per-particle values and contacts gathered for frames. Each particle comes from its owner and each pair from the
// owner of its particle A (every pair is held there), so process 0 sees the whole world's lists in its order.
#include <algorithm>
#include <tuple>
#include <utility>

#include "engine/particle_fields.hpp"
#include "engine/world.hpp"

namespace mc {

namespace {

// A pair as it arrives: its particles in whole-world indices (a wall pair: the wall, then the ball), where its
// history lies in what its process sent, and its last contact force.
template <int D>
struct GatheredPair {
  Pair pair;
  const std::uint8_t* history;
  Vec<D> force;
};

template <int D>
void put_pairs(Bytes& out, const ContactSetBase<D>& set, bool wall, const Particles<D>& p,
               const std::vector<std::int64_t>& global, const Vec<D>* forces) {
  const auto& pairs = wall ? set.wall_pairs() : set.pairs();
  std::vector<std::size_t> sent;
  for (std::size_t c = 0; c < pairs.size(); ++c)
    if (wall || !p.is_ghost(pairs[c][0])) sent.push_back(c);
  put_bytes(out, static_cast<std::uint64_t>(sent.size()));
  for (std::size_t c : sent) {
    put_bytes(out, wall ? std::int64_t(pairs[c][0]) : global[pairs[c][0]]);
    put_bytes(out, global[pairs[c][1]]);
    set.history(c, wall, out);
    put_bytes(out, forces ? forces[c] : Vec<D>(Vec<D>::Zero()));
  }
}

template <int D>
void take_pairs(const Bytes& in, std::size_t& at, std::size_t history_size, std::vector<GatheredPair<D>>& list) {
  const auto n = take_bytes<std::uint64_t>(in, at);
  for (std::uint64_t k = 0; k < n; ++k) {
    GatheredPair<D> g;
    g.pair[0] = static_cast<int>(take_bytes<std::int64_t>(in, at));
    g.pair[1] = static_cast<int>(take_bytes<std::int64_t>(in, at));
    g.history = in.data() + at;
    at += history_size;
    g.force = take_bytes<Vec<D>>(in, at);
    list.push_back(g);
  }
}

}  // namespace

template <int D>
std::vector<std::vector<Vec<D>>> World<D>::gather_whole(const std::vector<const std::vector<Vec<D>>*>& held) const {
  std::vector<std::vector<Vec<D>>> whole(held.size());
  if (!split_) {
    for (std::size_t k = 0; k < held.size(); ++k) whole[k] = *held[k];
    return whole;
  }
  const Exchange& ex = *split_->exchange;
  std::vector<Bytes> out(ex.size());
  for (int i = 0; i < particles.size(); ++i) {
    if (particles.is_ghost(i)) continue;
    put_bytes(out[0], split_->global[i]);
    for (const auto* values : held) put_bytes(out[0], (*values)[i]);
  }
  const std::vector<Bytes> in = ex.all_to_all(out);
  if (ex.rank() != 0) return whole;
  const std::size_t each = sizeof(std::int64_t) + held.size() * sizeof(Vec<D>);
  std::size_t n = 0;
  for (const Bytes& b : in) n += b.size() / each;
  for (auto& w : whole) w.resize(n);
  for (const Bytes& b : in)
    for (std::size_t at = 0; at < b.size();) {
      const auto g = take_bytes<std::int64_t>(b, at);
      for (auto& w : whole) w[g] = take_bytes<Vec<D>>(b, at);
    }
  return whole;
}

// Every process sends process 0 its own particles (with their neighbour-list positions) and, per set, the pairs
// whose A it owns and its wall pairs, each with its history and last contact force. Process 0 lays them out as
// the whole world holds them: particles by index, pairs sorted as the lists keep them, contact forces in save()'s
// order.
template <int D>
void World<D>::save_split(Archive& a) const {
  const Exchange& ex = *split_->exchange;
  const auto& p = particles;
  Bytes mine;
  std::size_t size =
      sizeof(std::uint64_t) + static_cast<std::size_t>(own_count()) * (sizeof(std::int64_t) + sizeof(Vec<D>));
  std::apply([&](const auto&... v) { ((size += v.size() * sizeof(v[0])), ...); }, particle_fields(p));
  for (const auto& set : sets)
    size += 2 + 2 * sizeof(std::uint64_t) +
            (set->pairs().size() + set->wall_pairs().size()) *
                (2 * sizeof(std::int64_t) + set->history_size() + sizeof(Vec<D>));
  mine.reserve(size);
  put_bytes(mine, static_cast<std::uint64_t>(own_count()));
  for (int i = 0; i < p.size(); ++i) {
    if (p.is_ghost(i)) continue;
    put_bytes(mine, split_->global[i]);
    std::apply([&](const auto&... v) { (put_bytes(mine, v[i]), ...); }, particle_fields(p));
    put_bytes(mine, x_at_rebuild_[i]);
  }
  for (std::size_t s = 0; s < sets.size(); ++s) {
    put_bytes(mine, std::array<std::uint8_t, 2>{sets[s]->traced(false), sets[s]->traced(true)});
    put_pairs(mine, *sets[s], false, p, split_->global,
              keep_forces_ ? slots_.pair_force.data() + pair_offset_[s] : nullptr);
    put_pairs(mine, *sets[s], true, p, split_->global, slots_.f.data() + wall_offset_[s]);
  }
  // Process 0 reads its own part where it is; the others' come over (hundreds of megabytes each at 10^6 particles).
  std::vector<Bytes> out(ex.size());
  if (ex.rank() != 0) out[0] = std::move(mine);
  std::vector<Bytes> in = ex.all_to_all(out);
  if (ex.rank() != 0) return;
  in[0] = std::move(mine);

  std::vector<std::size_t> at(in.size(), 0);
  std::size_t n = 0;
  for (std::size_t r = 0; r < in.size(); ++r) {
    std::size_t peek = 0;
    n += take_bytes<std::uint64_t>(in[r], peek);
  }
  Particles<D> whole;
  std::apply([&](auto&... v) { (v.resize(n), ...); }, particle_fields(whole));
  std::vector<Vec<D>> x_at_rebuild(n);
  for (std::size_t r = 0; r < in.size(); ++r) {
    const auto count = take_bytes<std::uint64_t>(in[r], at[r]);
    for (std::uint64_t k = 0; k < count; ++k) {
      const auto g = take_bytes<std::int64_t>(in[r], at[r]);
      std::apply(
          [&](auto&... v) { ((v[g] = take_bytes<typename std::decay_t<decltype(v)>::value_type>(in[r], at[r])), ...); },
          particle_fields(whole));
      x_at_rebuild[g] = take_bytes<Vec<D>>(in[r], at[r]);
    }
  }
  std::vector<std::vector<std::uint8_t>> set_bytes;
  std::vector<Vec<D>> contact_f;
  for (std::size_t s = 0; s < sets.size(); ++s) {
    std::array<bool, 2> traced{false, false};
    std::array<std::vector<GatheredPair<D>>, 2> lists;
    for (std::size_t r = 0; r < in.size(); ++r) {
      const auto flags = take_bytes<std::array<std::uint8_t, 2>>(in[r], at[r]);
      for (int wall = 0; wall < 2; ++wall) {
        traced[wall] = traced[wall] || flags[wall];
        take_pairs(in[r], at[r], sets[s]->history_size(), lists[wall]);
      }
    }
    std::array<std::vector<Pair>, 2> pairs;
    std::array<std::vector<const std::uint8_t*>, 2> histories;
    for (int wall = 0; wall < 2; ++wall) {
      auto& list = lists[wall];
      std::sort(list.begin(), list.end(), [](const auto& x, const auto& y) { return x.pair < y.pair; });
      pairs[wall].reserve(list.size());
      histories[wall].reserve(list.size());
      for (const auto& g : list) {
        pairs[wall].push_back(g.pair);
        histories[wall].push_back(g.history);
        if (wall || keep_forces_) contact_f.push_back(g.force);
      }
    }
    set_bytes.push_back(sets[s]->save_of(pairs[0], histories[0], traced[0], pairs[1], histories[1], traced[1]));
  }
  write_archive(a, whole, x_at_rebuild, std::move(set_bytes), contact_f);
}

template <int D>
std::vector<ContactRow<D>> World<D>::gather_contacts() const {
  const Slots<D>& s = kept();
  const auto& x = particles.x;
  std::vector<ContactRow<D>> rows;
  for (std::size_t k = 0; k < sets.size(); ++k) {
    const auto& pairs = sets[k]->pairs();
    for (std::size_t c = 0; c < pairs.size(); ++c) {
      const auto [a, b] = pairs[c];
      const Vec<D>& f = s.pair_force[pair_offset_[k] + c];
      const bool bonded = sets[k]->persistent(c);
      if (particles.is_ghost(a) || (!bonded && f.squaredNorm() == 0)) continue;
      // The force pass ran at the positions before the step's motion, x − v Δt (Tang (3.20)): the branch there.
      const Vec<D> branch = (x[b] - x[a]) - (particles.v[b] - particles.v[a]) * dt;
      rows.push_back({static_cast<std::int64_t>(k), global_index(a), global_index(b), f, branch, bonded ? 1 : 0});
    }
  }
  if (!split_) return rows;
  const Exchange& ex = *split_->exchange;
  std::vector<Bytes> out(ex.size());
  for (const ContactRow<D>& r : rows) put_bytes(out[0], r);
  const std::vector<Bytes> in = ex.all_to_all(out);
  rows.clear();
  if (ex.rank() != 0) return rows;
  for (const Bytes& b : in)
    for (std::size_t at = 0; at < b.size();) rows.push_back(take_bytes<ContactRow<D>>(b, at));
  // The lists' order: set by set, pairs sorted by A then B (held particles keep their whole-world order).
  std::sort(rows.begin(), rows.end(), [](const ContactRow<D>& p, const ContactRow<D>& q) {
    return std::tie(p.set, p.a, p.b) < std::tie(q.set, q.a, q.b);
  });
  return rows;
}

template std::vector<std::vector<Vec<2>>> World<2>::gather_whole(const std::vector<const std::vector<Vec<2>>*>&) const;
template std::vector<std::vector<Vec<3>>> World<3>::gather_whole(const std::vector<const std::vector<Vec<3>>*>&) const;
template std::vector<ContactRow<2>> World<2>::gather_contacts() const;
template std::vector<ContactRow<3>> World<3>::gather_contacts() const;
template void World<2>::save_split(Archive&) const;
template void World<3>::save_split(Archive&) const;

}  // namespace mc
