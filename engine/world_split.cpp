// One specimen split across processes (World::split). Each process owns the particles of its region and holds,
// as ghosts, the others' that its contacts reach: every particle within the ghost layer (2 R_max + skin) of its
// region, and the far partners of its intact bonds. A contact is computed on each process that holds one of its
// particles, so no force ever travels back, and each own particle sums its contacts in the whole world's order
// (held particles keep their whole-world order, so the pair lists keep it too): the bits are the serial ones.
// Particles change hands at neighbour-list rebuilds, each with the histories of its pairs.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <tuple>

#include "engine/errors.hpp"
#include "engine/particle_fields.hpp"
#include "engine/world.hpp"

namespace mc {

namespace {

template <int D>
void put_record(Bytes& out, std::int64_t global, Particles<D>& p, std::vector<std::int64_t>& ids, bool applied, int i) {
  put_bytes(out, global);
  std::apply([&](auto&... v) { (put_bytes(out, v[i]), ...); }, particle_fields(p));
  if (applied) put_bytes(out, p.f_applied[i]), put_bytes(out, p.m_applied[i]);
  if (!ids.empty()) put_bytes(out, ids[i]);
}

template <int D>
std::size_t record_size(Particles<D>& p, bool applied, bool with_ids) {
  std::size_t n = sizeof(std::int64_t);
  std::apply([&](auto&... v) { ((n += sizeof(typename std::decay_t<decltype(v)>::value_type)), ...); },
             particle_fields(p));
  if (applied) n += sizeof(Vec<D>) + sizeof(Rot<D>);
  if (with_ids) n += sizeof(std::int64_t);
  return n;
}

// The position of `value` in a sorted list, or −1.
inline int index_in(const std::vector<std::int64_t>& sorted, std::int64_t value) {
  const auto it = std::lower_bound(sorted.begin(), sorted.end(), value);
  return it != sorted.end() && *it == value ? static_cast<int>(it - sorted.begin()) : -1;
}

// The most particles any region owns.
template <int D>
double most_owned(const Decomposition<D>& regions, const std::vector<Vec<D>>& x) {
  std::vector<double> count(regions.size(), 0);
  for (const auto& p : x) ++count[regions.owner(p)];
  return *std::max_element(count.begin(), count.end());
}

// Reads the records of a message: how many, then each one's global index and the offset of its data.
struct RecordList {
  std::vector<std::pair<std::int64_t, std::size_t>> items;  // global index, byte offset of the record
  std::size_t end = 0;                                      // the byte after the last record
};
inline RecordList read_records(const Bytes& in, std::size_t at, std::size_t size) {
  RecordList r;
  const auto n = take_bytes<std::uint64_t>(in, at);
  for (std::uint64_t k = 0; k < n; ++k) {
    std::size_t peek = at;
    r.items.push_back({take_bytes<std::int64_t>(in, peek), at});
    at += size;
  }
  r.end = at;
  return r;
}

}  // namespace

template <int D>
int World<D>::own_count() const {
  int n = 0;
  for (int i = 0; i < particles.size(); ++i) n += !particles.is_ghost(i);
  return n;
}

template <int D>
int World<D>::held_index(std::int64_t global) const {
  if (!split_) return global >= 0 && global < particles.size() ? static_cast<int>(global) : -1;
  return index_in(split_->global, global);
}

template <int D>
void World<D>::hold(const std::vector<Source>& sources, const std::vector<Bytes>& received) {
  auto& p = particles;
  const bool applied = applied_loads, with_ids = !ids.empty();
  Particles<D> np;
  std::vector<std::int64_t> nids, nglobal;
  std::vector<Vec<D>> nx_rebuild;
  for (const Source& s : sources) {
    nglobal.push_back(s.global);
    np.ghost.push_back(s.ghost);
    if (s.local >= 0) {
      const int i = s.local;
      std::apply(
          [&](auto&... dst) { std::apply([&](auto&... src) { (dst.push_back(src[i]), ...); }, particle_fields(p)); },
          particle_fields(np));
      if (applied) np.f_applied.push_back(p.f_applied[i]), np.m_applied.push_back(p.m_applied[i]);
      if (with_ids) nids.push_back(ids[i]);
      nx_rebuild.push_back(x_at_rebuild_[i]);
    } else {
      const Bytes& in = received[s.rank];
      std::size_t at = s.at + sizeof(std::int64_t);
      std::apply(
          [&](auto&... dst) {
            ((dst.push_back(take_bytes<typename std::decay_t<decltype(dst)>::value_type>(in, at))), ...);
          },
          particle_fields(np));
      if (applied) {
        np.f_applied.push_back(take_bytes<Vec<D>>(in, at));
        np.m_applied.push_back(take_bytes<Rot<D>>(in, at));
      }
      if (with_ids) nids.push_back(take_bytes<std::int64_t>(in, at));
      nx_rebuild.push_back(np.x.back());
    }
  }
  // A pair keeps its particles whatever copy of them is held now (a ghost's comes afresh from its owner).
  std::vector<int> to(p.size());
  for (int i = 0; i < p.size(); ++i) to[i] = index_in(nglobal, split_->global[i]);
  p = std::move(np);
  ids = std::move(nids);
  x_at_rebuild_ = std::move(nx_rebuild);
  split_->global = std::move(nglobal);
  for (auto& s : sets) s->renumber(to, p.ghost);
}

template <int D>
void World<D>::own_members() {
  auto own = [&](const std::vector<std::int64_t>& whole, std::vector<int>& members) {
    members.clear();
    for (std::int64_t m : whole) {
      const int i = held_index(m);
      if (i >= 0 && !particles.is_ghost(i)) members.push_back(i);
    }
  };
  for (std::size_t g = 0; g < driven.size(); ++g) own(split_->driven[g], driven[g].members);
  for (std::size_t g = 0; g < gauges.size(); ++g) {
    own(split_->gauges[g][0], gauges[g].a);
    own(split_->gauges[g][1], gauges[g].b);
  }
}

// Exact sums add as integers, in any order; their non-finite parts (infinities, NaN) are counted beside them.
template <int D>
void World<D>::agree_sums(std::vector<ExactSum>& sums) const {
  if (!split_ || sums.empty()) return;
  constexpr int kL = ExactSum::kLimbs, kEach = kL + 3;
  std::vector<std::int64_t> limbs(sums.size() * kEach);
  for (std::size_t k = 0; k < sums.size(); ++k) {
    const auto& l = sums[k].limbs();
    std::copy(l.begin(), l.end(), limbs.begin() + k * kEach);
    const double s = sums[k].special();
    limbs[k * kEach + kL] = std::isnan(s), limbs[k * kEach + kL + 1] = s == kInf,
                      limbs[k * kEach + kL + 2] = s == -kInf;
  }
  split_->exchange->sum(limbs);
  for (std::size_t k = 0; k < sums.size(); ++k) {
    auto& l = sums[k].limbs();
    const auto* mine = limbs.data() + k * kEach;
    std::copy(mine, mine + kL, l.begin());
    const bool nan = mine[kL] > 0 || (mine[kL + 1] > 0 && mine[kL + 2] > 0);
    sums[k].special() = nan ? kNaN : mine[kL + 1] > 0 ? kInf : mine[kL + 2] > 0 ? -kInf : 0.0;
  }
}

template <int D>
void World<D>::split(const Exchange& exchange) {
  if (split_) throw std::logic_error("World::split: the world is split already");
  const int n = particles.size();
  SplitState st;
  st.exchange = &exchange;
  st.regions = Decomposition<D>::bisect(particles.x, exchange.size());
  st.balanced_most = most_owned(st.regions, particles.x);
  st.reach = 2 * particles.max_radius();
  st.global.resize(n);
  std::iota(st.global.begin(), st.global.end(), std::int64_t(0));
  for (const auto& g : driven) st.driven.emplace_back(g.members.begin(), g.members.end());
  for (auto& g : gauges) {
    st.gauges.push_back(
        {std::vector<std::int64_t>(g.a.begin(), g.a.end()), std::vector<std::int64_t>(g.b.begin(), g.b.end())});
    g.whole_a = g.a.size(), g.whole_b = g.b.size();
  }
  st.send.resize(exchange.size());
  st.fill.resize(exchange.size());
  split_ = std::move(st);
  // The last step's contact forces of a restored world (the timestep refresh and the servos read the walls', the
  // measurements the pairs' kept) stay with their pairs through the relink.
  std::vector<std::vector<Pair>> whole_pairs;
  std::vector<std::vector<Vec<D>>> whole_f;
  for (std::size_t s = 0; s < sets.size(); ++s) {
    whole_pairs.push_back(sets[s]->pairs()), whole_pairs.push_back(sets[s]->wall_pairs());
    const auto np = static_cast<std::ptrdiff_t>(sets[s]->pairs().size());
    const auto nw = static_cast<std::ptrdiff_t>(sets[s]->wall_pairs().size());
    const auto pf = slots_.pair_force.begin() + static_cast<std::ptrdiff_t>(pair_offset_[s]);
    const auto wf = slots_.f.begin() + static_cast<std::ptrdiff_t>(wall_offset_[s]);
    whole_f.push_back(keep_forces_ ? std::vector<Vec<D>>(pf, pf + np) : std::vector<Vec<D>>{});
    whole_f.push_back(std::vector<Vec<D>>(wf, wf + nw));
  }
  // Every process holds the whole world: its own particles are those of its region, the rest are ghosts until
  // the owners say which ones it needs.
  std::vector<Source> all;
  for (int i = 0; i < n; ++i) all.push_back({i, i, -1, 0, split_->regions.owner(particles.x[i]) != exchange.rank()});
  hold(all, {});
  send_ghosts();
  relink();
  auto force_of = [&](std::size_t list, const Pair& pair) {
    const auto it = std::lower_bound(whole_pairs[list].begin(), whole_pairs[list].end(), pair);
    return whole_f[list][static_cast<std::size_t>(it - whole_pairs[list].begin())];
  };
  const auto& global = split_->global;
  for (std::size_t s = 0; s < sets.size(); ++s) {
    const auto& pairs = sets[s]->pairs();
    if (keep_forces_)
      for (std::size_t c = 0; c < pairs.size(); ++c)
        slots_.pair_force[pair_offset_[s] + c] =
            force_of(2 * s, {static_cast<int>(global[pairs[c][0]]), static_cast<int>(global[pairs[c][1]])});
    const auto& walls_of = sets[s]->wall_pairs();
    for (std::size_t c = 0; c < walls_of.size(); ++c)
      slots_.f[wall_offset_[s] + c] = force_of(2 * s + 1, {walls_of[c][0], static_cast<int>(global[walls_of[c][1]])});
  }
  slots_.mark_all_live();
}

// The own particles other processes need as ghosts, per rank: those within the ghost layer of its region, and
// the partners of intact bonds with a particle it owns.
template <int D>
std::vector<std::vector<int>> World<D>::wanted_ghosts() const {
  const auto& p = particles;
  const auto& regions = split_->regions;
  const int me = split_->exchange->rank(), ranks = split_->exchange->size();
  // The layer is widened by a relative 1e-9: a pair just within reach must never miss its ghost to rounding.
  const double layer = (split_->reach + skin) * (1 + 1e-9);
  std::vector<std::vector<int>> wanted(ranks);
  // Own particles lie in this region (they were placed at this rebuild): only the regions within the layer of
  // it can want them.
  const std::vector<int> close = regions.neighbours(me, layer);
  for (int i = 0; i < p.size(); ++i) {
    if (p.is_ghost(i)) continue;
    for (int r : close)
      if (regions.near(r, p.x[i], layer)) wanted[r].push_back(i);
  }
  for (const auto& s : sets) {
    const auto& pairs = s->pairs();
    for (std::size_t c = 0; c < pairs.size(); ++c) {
      if (!s->persistent(c)) continue;
      for (int e = 0; e < 2; ++e) {
        const int mine = pairs[c][e], other = pairs[c][1 - e];
        if (p.is_ghost(mine)) continue;
        const int r = regions.owner(p.x[other]);
        if (r != me) wanted[r].push_back(mine);
      }
    }
  }
  for (auto& w : wanted) {
    std::sort(w.begin(), w.end());
    w.erase(std::unique(w.begin(), w.end()), w.end());
  }
  return wanted;
}

// Sends each process the ghosts it needs and keeps, of what is held, the own particles and the ghosts received.
template <int D>
void World<D>::send_ghosts() {
  auto& p = particles;
  const Exchange& ex = *split_->exchange;
  const int ranks = ex.size();
  const auto wanted = wanted_ghosts();
  std::vector<Bytes> out(ranks);
  std::vector<std::vector<std::int64_t>> sent(ranks);
  for (int r = 0; r < ranks; ++r) {
    put_bytes(out[r], static_cast<std::uint64_t>(wanted[r].size()));
    for (int i : wanted[r]) {
      put_record(out[r], split_->global[i], p, ids, applied_loads, i);
      sent[r].push_back(split_->global[i]);
    }
  }
  const std::vector<Bytes> in = ex.all_to_all(out);
  const std::size_t size = record_size(p, applied_loads, !ids.empty());
  std::vector<Source> keep;
  for (int i = 0; i < p.size(); ++i)
    if (!p.is_ghost(i)) keep.push_back({split_->global[i], i, -1, 0, false});
  for (int r = 0; r < ranks; ++r)
    for (const auto& [global, at] : read_records(in[r], 0, size).items) keep.push_back({global, -1, r, at, true});
  std::sort(keep.begin(), keep.end(), [](const Source& a, const Source& b) { return a.global < b.global; });
  hold(keep, in);
  for (int r = 0; r < ranks; ++r) {
    split_->send[r].clear();
    for (std::int64_t g : sent[r]) split_->send[r].push_back(held_index(g));
    split_->fill[r].clear();
  }
  // Held particle k came from keep[k]: a ghost is filled by the rank that sent it.
  for (std::size_t k = 0; k < keep.size(); ++k)
    if (keep[k].ghost) split_->fill[keep[k].rank].push_back(static_cast<int>(k));
  own_members();
}

// The own counts of all processes; past the limit, every process gathers every own particle's position and
// bisects them in whole-world order, so all draw the same regions.
template <int D>
void World<D>::rebalance() {
  if (imbalance_limit <= 0) return;
  const Exchange& ex = *split_->exchange;
  Bytes mine;
  for (int i = 0; i < particles.size(); ++i)
    if (!particles.is_ghost(i)) put_bytes(mine, split_->global[i]), put_bytes(mine, particles.x[i]);
  const std::size_t each = sizeof(std::int64_t) + sizeof(Vec<D>);
  Bytes count;
  put_bytes(count, static_cast<double>(mine.size() / each));
  double most = 0, total = 0;
  for (const Bytes& b : ex.all_gather(count)) {
    std::size_t at = 0;
    const double c = take_bytes<double>(b, at);
    most = std::max(most, c), total += c;
  }
  // Measured against the mean, or against what the last bisection achieved if that was more (a region holds
  // whole lattice rows, say): a fresh bisection could not do better.
  if (most <= (1 + imbalance_limit) * std::max(total / ex.size(), split_->balanced_most)) return;
  std::vector<std::pair<std::int64_t, Vec<D>>> everyone;
  for (const Bytes& b : ex.all_gather(mine))
    for (std::size_t at = 0; at < b.size();) {
      const auto g = take_bytes<std::int64_t>(b, at);
      everyone.push_back({g, take_bytes<Vec<D>>(b, at)});
    }
  std::sort(everyone.begin(), everyone.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Vec<D>> x;
  x.reserve(everyone.size());
  for (const auto& e : everyone) x.push_back(e.second);
  split_->regions = Decomposition<D>::bisect(x, ex.size());
  split_->balanced_most = most_owned(split_->regions, x);
  ++split_->rebalances;
}

// At a rebuild: each own particle that left its region goes to its new owner, with the histories of its pairs
// and the particles at their other ends; then the ghosts are sent afresh.
template <int D>
void World<D>::redistribute() {
  auto& p = particles;
  const Exchange& ex = *split_->exchange;
  const int me = ex.rank(), ranks = ex.size();
  rebalance();
  const auto& regions = split_->regions;
  std::vector<int> owner(p.size());
  for (int i = 0; i < p.size(); ++i) owner[i] = regions.owner(p.x[i]);
  // Per destination: the particles (leaving ones and their pairs' other ends, once each) and the pair records.
  std::vector<std::vector<int>> carried(ranks);
  std::vector<Bytes> pair_records(ranks);
  std::vector<std::uint64_t> pair_count(ranks, 0);
  for (int i = 0; i < p.size(); ++i)
    if (!p.is_ghost(i) && owner[i] != me) carried[owner[i]].push_back(i);
  for (std::size_t s = 0; s < sets.size(); ++s) {
    const auto& pairs = sets[s]->pairs();
    for (std::size_t c = 0; c < pairs.size(); ++c) {
      const auto [a, b] = pairs[c];
      for (int e = 0; e < 2; ++e) {
        const int i = pairs[c][e];
        const int r = owner[i];
        if (p.is_ghost(i) || r == me) continue;
        if (e == 1 && !p.is_ghost(a) && owner[a] == r) continue;  // sent already with A
        put_bytes(pair_records[r], static_cast<std::int32_t>(s));
        put_bytes(pair_records[r], split_->global[a]);
        put_bytes(pair_records[r], split_->global[b]);
        sets[s]->history(c, false, pair_records[r]);
        ++pair_count[r];
        carried[r].push_back(pairs[c][1 - e]);
      }
    }
  }
  // Ball–wall pairs (only own particles have them) go with their particle; a wall is known everywhere.
  for (std::size_t s = 0; s < sets.size(); ++s) {
    const auto& pairs = sets[s]->wall_pairs();
    for (std::size_t c = 0; c < pairs.size(); ++c) {
      const auto [w, j] = pairs[c];
      const int r = owner[j];
      if (r == me) continue;
      put_bytes(pair_records[r], -1 - static_cast<std::int32_t>(s));
      put_bytes(pair_records[r], static_cast<std::int64_t>(w));
      put_bytes(pair_records[r], split_->global[j]);
      sets[s]->history(c, true, pair_records[r]);
      ++pair_count[r];
    }
  }
  std::vector<Bytes> out(ranks);
  for (int r = 0; r < ranks; ++r) {
    auto& list = carried[r];
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    put_bytes(out[r], static_cast<std::uint64_t>(list.size()));
    for (int i : list) put_record(out[r], split_->global[i], p, ids, applied_loads, i);
    put_bytes(out[r], pair_count[r]);
    out[r].insert(out[r].end(), pair_records[r].begin(), pair_records[r].end());
  }
  const std::vector<Bytes> in = ex.all_to_all(out);
  // Hold what was held and what arrived; own now: whatever lies in this region.
  const std::size_t size = record_size(p, applied_loads, !ids.empty());
  std::vector<Source> all;
  for (int i = 0; i < p.size(); ++i) all.push_back({split_->global[i], i, -1, 0, owner[i] != me});
  std::vector<std::size_t> pairs_at(ranks);
  for (int r = 0; r < ranks; ++r) {
    const RecordList list = read_records(in[r], 0, size);
    pairs_at[r] = list.end;
    for (const auto& [global, at] : list.items) {
      std::size_t peek = at + sizeof(std::int64_t);
      const auto x = take_bytes<Vec<D>>(in[r], peek);
      all.push_back({global, -1, r, at, regions.owner(x) != me});
    }
  }
  // Sorted by whole-world index; a particle both held and received keeps the held copy (the same numbers).
  std::stable_sort(all.begin(), all.end(), [](const Source& a, const Source& b) { return a.global < b.global; });
  all.erase(std::unique(all.begin(), all.end(), [](const Source& a, const Source& b) { return a.global == b.global; }),
            all.end());
  hold(all, in);
  // The pairs that arrived, with their histories, per set in pair order.
  struct Arrived {
    Pair pair;
    int rank;
    std::size_t at;  // its history's offset in what the rank sent
  };
  // Per set, ball pairs then wall pairs (a wall pair's record names its set −1 − s).
  std::vector<std::vector<Arrived>> arrived(2 * sets.size());
  for (int r = 0; r < ranks; ++r) {
    std::size_t at = pairs_at[r];
    const auto n = take_bytes<std::uint64_t>(in[r], at);
    for (std::uint64_t k = 0; k < n; ++k) {
      const auto code = take_bytes<std::int32_t>(in[r], at);
      const bool wall = code < 0;
      const int s = wall ? -1 - code : code;
      const auto first = take_bytes<std::int64_t>(in[r], at);
      const int a = wall ? static_cast<int>(first) : held_index(first);
      const int b = held_index(take_bytes<std::int64_t>(in[r], at));
      if (a < 0 || b < 0) throw std::logic_error("World::redistribute: a pair arrived without its particles");
      arrived[2 * s + wall].push_back({{a, b}, r, at});
      at += sets[s]->history_size();
    }
  }
  for (std::size_t list_index = 0; list_index < arrived.size(); ++list_index) {
    const std::size_t s = list_index / 2;
    const bool wall = list_index % 2;
    auto& list = arrived[list_index];
    if (list.empty()) continue;
    // A pair may arrive from two processes (its particles left both): the copies are the same.
    std::stable_sort(list.begin(), list.end(), [](const Arrived& x, const Arrived& y) { return x.pair < y.pair; });
    list.erase(
        std::unique(list.begin(), list.end(), [](const Arrived& x, const Arrived& y) { return x.pair == y.pair; }),
        list.end());
    std::vector<Pair> pairs;
    Bytes histories;
    const std::size_t size = sets[s]->history_size();
    for (const Arrived& a : list) {
      pairs.push_back(a.pair);
      histories.insert(histories.end(), in[a.rank].begin() + a.at, in[a.rank].begin() + a.at + size);
    }
    sets[s]->add(pairs, histories, wall);
  }
  send_ghosts();
}

// After the law of motion: the own particles' new positions, velocities and orientations to the processes that
// hold them as ghosts.
template <int D>
void World<D>::share_motion() {
  auto& p = particles;
  const Exchange& ex = *split_->exchange;
  std::vector<Bytes> out(ex.size());
  for (int r = 0; r < ex.size(); ++r)
    for (int i : split_->send[r]) {
      put_bytes(out[r], p.x[i]);
      put_bytes(out[r], p.v[i]);
      put_bytes(out[r], p.w[i]);
    }
  constexpr std::size_t kEach = 2 * sizeof(Vec<D>) + sizeof(Rot<D>);
  std::vector<std::size_t> sizes(ex.size());
  for (int r = 0; r < ex.size(); ++r) sizes[r] = split_->fill[r].size() * kEach;
  const std::vector<Bytes> in = ex.swap(out, sizes);
  for (int r = 0; r < ex.size(); ++r) {
    std::size_t at = 0;
    for (int i : split_->fill[r]) {
      p.x[i] = take_bytes<Vec<D>>(in[r], at);
      p.v[i] = take_bytes<Vec<D>>(in[r], at);
      p.w[i] = take_bytes<Rot<D>>(in[r], at);
    }
  }
}

template <int D>
std::string World<D>::first_failure(const std::array<std::int64_t, 3>& key, const std::string& message) const {
  Bytes mine;
  if (!message.empty()) {
    put_bytes(mine, key);
    mine.insert(mine.end(), message.begin(), message.end());
  }
  std::string first;
  std::array<std::int64_t, 3> lowest{};
  for (const Bytes& b : split_->exchange->all_gather(mine)) {
    if (b.empty()) continue;
    std::size_t at = 0;
    const auto k = take_bytes<std::array<std::int64_t, 3>>(b, at);
    if (first.empty() || k < lowest) lowest = k, first.assign(b.begin() + static_cast<std::ptrdiff_t>(at), b.end());
  }
  return first;
}

template <int D>
double World<D>::agreed_min(double x) const {
  std::vector<double> v{-x};
  split_->exchange->max(v);
  return -v[0];
}

// The end of a step on every process alike: the largest displacement since the rebuild, and whether any
// process found a particle moving too far, a pair passing through, or bonds breaking. A failure is thrown on
// every process with the message of the one that found it (the first in the whole world's order); the breaks
// join the crack log in the serial order (set, then pair).
template <int D>
void World<D>::agree_on_step(const Motion& motion) {
  const Exchange& ex = *split_->exchange;
  const double too_far = motion.too_far >= 0 ? -static_cast<double>(global_index(motion.too_far)) : -kInf;
  std::vector<double> v{motion.moved, too_far, split_->passing.empty() ? 0.0 : 1.0, split_->cracks.empty() ? 0.0 : 1.0};
  ex.max(v);
  moved_ = v[0];
  if (v[2] > 0) throw InstabilityError(first_failure(split_->passing_key, split_->passing));
  // The step's breaks join the log before a particle moving too far stops the run, as in the whole world (whose
  // law of motion follows the crack log; a pair passing through stops it before).
  if (v[3] > 0) {
    Bytes b;
    for (const Crack<D>& c : split_->cracks) put_bytes(b, c);
    std::vector<Crack<D>> merged;
    for (const Bytes& m : ex.all_gather(b)) {
      std::size_t at = 0;
      while (at < m.size()) merged.push_back(take_bytes<Crack<D>>(m, at));
    }
    std::sort(merged.begin(), merged.end(), [](const Crack<D>& x, const Crack<D>& y) {
      return std::tie(x.set, x.a, x.b) < std::tie(y.set, y.a, y.b);
    });
    for (const Crack<D>& c : merged) count_crack(c);
  }
  split_->cracks.clear();
  if (v[1] > -kInf) {
    const bool mine = motion.too_far >= 0 && too_far == v[1];
    throw InstabilityError(
        first_failure({-static_cast<std::int64_t>(v[1]), 0, 0}, mine ? too_far_message(motion.too_far) : ""));
  }
}

template int World<2>::own_count() const;
template int World<2>::held_index(std::int64_t) const;
template void World<2>::hold(const std::vector<Source>&, const std::vector<Bytes>&);
template void World<2>::own_members();
template void World<2>::agree_sums(std::vector<ExactSum>&) const;
template void World<2>::split(const Exchange&);
template std::vector<std::vector<int>> World<2>::wanted_ghosts() const;
template void World<2>::send_ghosts();
template void World<2>::redistribute();
template void World<2>::rebalance();
template void World<2>::share_motion();
template double World<2>::agreed_min(double) const;
template std::string World<2>::first_failure(const std::array<std::int64_t, 3>&, const std::string&) const;
template void World<2>::agree_on_step(const Motion&);
template int World<3>::own_count() const;
template int World<3>::held_index(std::int64_t) const;
template void World<3>::hold(const std::vector<Source>&, const std::vector<Bytes>&);
template void World<3>::own_members();
template void World<3>::agree_sums(std::vector<ExactSum>&) const;
template void World<3>::split(const Exchange&);
template std::vector<std::vector<int>> World<3>::wanted_ghosts() const;
template void World<3>::send_ghosts();
template void World<3>::redistribute();
template void World<3>::rebalance();
template void World<3>::share_motion();
template double World<3>::agreed_min(double) const;
template std::string World<3>::first_failure(const std::array<std::int64_t, 3>&, const std::string&) const;
template void World<3>::agree_on_step(const Motion&);

}  // namespace mc
