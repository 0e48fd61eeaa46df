// The contacts of one contact model (ContactSetBase, contact_set_base.hpp): a homogeneous array of pairs with the
// model's history beside them, and the loops over it. The engine holds one set per model in use; dispatch happens
// once per set, never per contact.
#pragma once
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <optional>
#include <type_traits>
#include <vector>

#include "engine/bytes.hpp"
#include "engine/cell_grid.hpp"
#include "engine/contact_geometry.hpp"
#include "engine/contact_model.hpp"
#include "engine/contact_points.hpp"
#include "engine/contact_set_base.hpp"
#include "engine/exact_sum.hpp"
#include "engine/lanes.hpp"
#include "engine/pair_blocks.hpp"
#include "engine/parallel.hpp"
#include "engine/particles.hpp"
#include "engine/random.hpp"
#include "engine/slots.hpp"
#include "engine/state_columns.hpp"
#include "engine/wall.hpp"

namespace mc {

// A model may also give its law for kLanes consecutive contacts at once (engine/lanes.hpp): a specialisation of
// LaneLaw with a static force(params, particles, pairs, histories, properties, slots, first slot, dt) that returns
// false, having written nothing, when any of them needs the one-contact law. Steps without energy tracing use it.
// It never writes the properties (state_columns.hpp): bonds are made outside the force pass (install_bonds), and a
// batch in which one breaks goes back to the one-contact law.
template <class Model, int D>
struct LaneLaw {};

template <class Model, int D>
requires ContactModel<Model, D>
class ContactSet final : public ContactSetBase<D> {
 public:
  using State = typename Model::template State<D>;
  using Columns = StateColumns<Model, D>;
  // States hold plain numbers (fixed-size Eigen vectors, doubles, flags): checkpoints copy them as bytes.
  static_assert(sizeof(State) % sizeof(double) == 0 || sizeof(State) < sizeof(double));

  explicit ContactSet(typename Model::Params params) : params_(params) {}
  const typename Model::Params& params() const { return params_; }
  const char* model() const override { return Model::name; }
  const std::vector<Pair>& pairs() const override { return pairs_; }
  const std::vector<Pair>& wall_pairs() const override { return wall_pairs_; }
  State state(std::size_t c) const { return states_.get(c); }

  void set_pairs(const std::vector<Pair>& c) override { merge(pairs_, states_, dashpot_, c); }

  void partition(const std::vector<int>& group_begin) override {
    blocks_.build(pairs_, group_begin);
    touching_ = 0;
  }
  std::size_t far_count() const override { return blocks_.far_count(); }
  std::vector<std::size_t> far_pairs() const override { return blocks_.far_pairs(pairs_); }
  std::size_t touching() const override { return touching_; }
  void set_wall_pairs(const std::vector<Pair>& c) override { merge(wall_pairs_, wall_states_, wall_dashpot_, c); }

  Dissipated forces(const Particles<D>& p, const std::vector<Wall<D>>& walls, double dt, bool energy, bool zero_sums,
                    Slots<D>& s, const SlotOffsets& at) override {
    return energy ? forces_impl<true>(p, walls, dt, zero_sums, s, at)
                  : forces_impl<false>(p, walls, dt, zero_sums, s, at);
  }

  void stiffness(const Particles<D>& p, const std::vector<Wall<D>>& walls, SlotStiffness<D>& k, const SlotOffsets& at,
                 double margin) const override {
    const std::size_t n = pairs_.size();
    const int blocks = blocks_.count();
#pragma omp parallel for schedule(static) if (n > std::size_t(kParallelMin))
    for (int b = 0; b < blocks; ++b) {
      const int near_end = blocks_.near_end[b];
      std::size_t far = at.far + blocks_.far[b];
      for (std::size_t c = blocks_.first[b]; c < blocks_.first[b + 1]; ++c) {
        const auto [i, j] = pairs_[c];
        const bool is_far = j >= near_end;
        const std::size_t slot = is_far ? far++ : 0;
        const double reach = p.radius[i] + p.radius[j] + margin;
        if ((p.x[j] - p.x[i]).squaredNorm() >= reach * reach && !Model::template persistent<D>(states_.get(c))) {
          if (is_far) k.kt(slot) = k.krb(slot) = 0;
          continue;
        }
        Vec<D> ca, cb;
        const auto g = ball_geometry(p, i, j, 0.0, ca, cb);
        const auto st = Model::template stiffness<D>(Model::template pair<D>(params_, g.r_a, g.r_b, g.k_a, g.k_b), g,
                                                     states_.get(c));
        const double kt = st.normal + st.shear;
        const double kr_b = st.shear * cb.squaredNorm() + st.rotational;
        k.sum_kt(i) += kt;
        k.sum_kr(i) += st.shear * ca.squaredNorm() + st.rotational;
        if (is_far) {
          k.kt(slot) = kt;
          k.krb(slot) = kr_b;
        } else {
          k.sum_kt(j) += kt;
          k.sum_kr(j) += kr_b;
        }
      }
    }
    const int nw = static_cast<int>(wall_pairs_.size());
    for (int c = 0; c < nw; ++c) {
      const auto [w, j] = wall_pairs_[c];
      const std::size_t slot = at.wall + c;
      Vec<D> cw, cb;
      const auto g = wall_geometry(p, walls[w], j, 0.0, cw, cb);
      if (-g.overlap >= margin) {
        k.kt(slot) = k.krb(slot) = 0;
        continue;
      }
      const auto st = Model::template stiffness<D>(Model::template wall<D>(params_, walls[w].material, g.r_b, g.k_b), g,
                                                   wall_states_.get(c));
      k.kt(slot) = st.normal + st.shear;
      k.krb(slot) = st.shear * cb.squaredNorm() + st.rotational;
    }
  }

  ContactStiffness nominal_stiffness(double r) const override {
    ContactGeometry<D> g{};
    g.r_a = g.r_b = r;
    g.overlap = 0;
    return Model::template stiffness<D>(Model::template pair<D>(params_, r, r), g, State{});
  }

  const std::vector<PairEvent<D>>& events() const override { return events_; }
  std::optional<Pair> passing_through() const override { return passing_; }

  std::size_t rewritten_bytes() const override {
    return states_.history_bytes() + wall_states_.history_bytes() +
           (dashpot_.capacity() + wall_dashpot_.capacity()) * sizeof(Vec<D>);
  }
  std::size_t memory_bytes() const override {
    return (pairs_.capacity() + wall_pairs_.capacity()) * sizeof(Pair) + states_.capacity_bytes() +
           wall_states_.capacity_bytes() + (dashpot_.capacity() + wall_dashpot_.capacity()) * sizeof(Vec<D>);
  }

  std::size_t bond_count() const override {
    if constexpr (BondModel<Model, D>) {
      std::size_t n = 0;
      for (std::size_t c = 0; c < states_.size(); ++c) n += Model::template bonded<D>(states_.get(c));
      return n;
    } else {
      return 0;
    }
  }

  std::size_t install_bonds(const Particles<D>& p, const std::vector<Pair>& bond_pairs, std::uint64_t seed) override {
    if constexpr (BondModel<Model, D>) {
      std::size_t n = 0;
      for (const Pair& pr : bond_pairs) {
        const auto it = std::lower_bound(pairs_.begin(), pairs_.end(), pr);
        if (it == pairs_.end() || *it != pr) continue;
        PairRandom rng(seed, pr);
        Vec<D> ca, cb;
        const auto g = ball_geometry(p, pr[0], pr[1], 0.0, ca, cb);
        const std::size_t c = it - pairs_.begin();
        State st = states_.get(c);
        Model::template install<D>(params_, g, st, rng);
        states_.set(c, st);
        ++n;
      }
      return n;
    } else {
      (void)p, (void)bond_pairs, (void)seed;
      return 0;
    }
  }

  double interaction_radius() const override {
    if constexpr (requires { Model::interaction_radius(params_); })
      return Model::interaction_radius(params_);
    else
      return 0.0;
  }

  double damping_ratio() const override { return Model::damping_ratio(params_); }

  ExactSum strain_energy(const Particles<D>& p, const std::vector<Wall<D>>& walls) const override {
    std::vector<ExactSum> part(block_count(pairs_.size()));
#pragma omp parallel for schedule(static) if (pairs_.size() > std::size_t(kParallelMin))
    for (int b = 0; b < static_cast<int>(part.size()); ++b) {
      const std::size_t end = std::min(pairs_.size(), std::size_t(b + 1) * kBlock);
      for (std::size_t c = std::size_t(b) * kBlock; c < end; ++c) {
        if (p.is_ghost(pairs_[c][0])) continue;
        Vec<D> ca, cb;
        const auto g = ball_geometry(p, pairs_[c][0], pairs_[c][1], 0.0, ca, cb);
        part[b].add(Model::template strain_energy<D>(Model::template pair<D>(params_, g.r_a, g.r_b, g.k_a, g.k_b), g,
                                                     states_.get(c)));
      }
    }
    ExactSum e;
    for (const ExactSum& x : part) e += x;
    for (std::size_t c = 0; c < wall_pairs_.size(); ++c) {
      const auto [w, j] = wall_pairs_[c];
      Vec<D> cw, cb;
      const auto g = wall_geometry(p, walls[w], j, 0.0, cw, cb);
      e.add(Model::template strain_energy<D>(Model::template wall<D>(params_, walls[w].material, g.r_b, g.k_b), g,
                                             wall_states_.get(c)));
    }
    return e;
  }

  std::vector<std::uint8_t> save() const override {
    std::vector<std::uint8_t> out;
    put_array(out, pairs_);
    states_.put(out);
    put_array(out, wall_pairs_);
    wall_states_.put(out);
    put_array(out, dashpot_);
    put_array(out, wall_dashpot_);
    return out;
  }
  bool traced(bool wall) const override { return !(wall ? wall_dashpot_ : dashpot_).empty(); }
  // Written straight from the histories, in save()'s layout: a checkpoint's lists are hundreds of megabytes.
  std::vector<std::uint8_t> save_of(const std::vector<Pair>& pairs, const std::vector<const std::uint8_t*>& histories,
                                    bool traced, const std::vector<Pair>& wall_pairs,
                                    const std::vector<const std::uint8_t*>& wall_histories,
                                    bool wall_traced) const override {
    const std::size_t n = pairs.size(), nw = wall_pairs.size();
    std::vector<std::uint8_t> out;
    out.reserve(6 * sizeof(std::uint64_t) + (n + nw) * (sizeof(Pair) + sizeof(State) + sizeof(Vec<D>)));
    auto part = [&](const std::vector<const std::uint8_t*>& from, std::size_t offset, std::size_t size, bool kept) {
      const std::uint64_t count = kept ? from.size() : 0;
      const auto* c = reinterpret_cast<const std::uint8_t*>(&count);
      out.insert(out.end(), c, c + sizeof count);
      if (kept)
        for (const std::uint8_t* h : from) out.insert(out.end(), h + offset, h + offset + size);
    };
    put_array(out, pairs);
    part(histories, 0, sizeof(State), true);
    put_array(out, wall_pairs);
    part(wall_histories, 0, sizeof(State), true);
    part(histories, sizeof(State), sizeof(Vec<D>), traced);
    part(wall_histories, sizeof(State), sizeof(Vec<D>), wall_traced);
    return out;
  }
  void load(const std::vector<std::uint8_t>& in) override {
    std::size_t at = 0;
    take_array(in, at, pairs_);
    states_.take(in, at);
    take_array(in, at, wall_pairs_);
    wall_states_.take(in, at);
    take_array(in, at, dashpot_);
    take_array(in, at, wall_dashpot_);
  }

  bool persistent(std::size_t c) const override { return Model::template persistent<D>(states_.get(c)); }
  std::size_t history_size() const override { return sizeof(State) + sizeof(Vec<D>); }
  void history(std::size_t c, bool wall, std::vector<std::uint8_t>& out) const override {
    (wall ? wall_states_ : states_).append_bytes(c, out);
    const auto& dp = wall ? wall_dashpot_ : dashpot_;
    const Vec<D> d = c < dp.size() ? dp[c] : Vec<D>::Zero();
    const auto* e = reinterpret_cast<const std::uint8_t*>(d.data());
    out.insert(out.end(), e, e + sizeof(Vec<D>));
  }
  void renumber(const std::vector<int>& to, const std::vector<std::uint8_t>& ghost) override {
    auto keep_ball = [&](const Pair& pr, Pair& out) {
      out = {to[pr[0]], to[pr[1]]};
      return out[0] >= 0 && out[1] >= 0 && !(ghost[out[0]] && ghost[out[1]]);
    };
    auto keep_wall = [&](const Pair& pr, Pair& out) {
      out = {pr[0], to[pr[1]]};
      return out[1] >= 0 && !ghost[out[1]];
    };
    renumber_list(pairs_, states_, dashpot_, keep_ball);
    renumber_list(wall_pairs_, wall_states_, wall_dashpot_, keep_wall);
  }
  void add(const std::vector<Pair>& pairs, const std::vector<std::uint8_t>& histories, bool wall) override {
    auto& own = wall ? wall_pairs_ : pairs_;
    auto& states = wall ? wall_states_ : states_;
    auto& dashpot = wall ? wall_dashpot_ : dashpot_;
    const bool traced = !dashpot.empty();
    const std::size_t size = history_size();
    std::vector<Pair> np;
    Columns ns;
    std::vector<Vec<D>> nd;
    std::size_t a = 0, b = 0;
    while (a < own.size() || b < pairs.size()) {
      if (b == pairs.size() || (a < own.size() && own[a] <= pairs[b])) {
        if (b < pairs.size() && own[a] == pairs[b]) ++b;
        np.push_back(own[a]), ns.push_back(states.get(a));
        if (traced) nd.push_back(dashpot[a]);
        ++a;
      } else {
        np.push_back(pairs[b]), ns.push_back(Columns::from_bytes(histories.data() + b * size));
        if (traced) {
          Vec<D> d;
          std::memcpy(d.data(), histories.data() + b * size + sizeof(State), sizeof(Vec<D>));
          nd.push_back(d);
        }
        ++b;
      }
    }
    own.swap(np);
    states.swap(ns);
    dashpot.swap(nd);
  }

 private:
  template <bool Energy>
  Dissipated forces_impl(const Particles<D>& p, const std::vector<Wall<D>>& walls, double dt, bool zero_sums,
                         Slots<D>& s, const SlotOffsets& at) {
    const std::size_t n = pairs_.size();
    // A local copy: the compiler then knows no store in the loop changes it, and hoists what depends on the
    // parameters alone (reciprocals) out of the loop.
    const typename Model::Params prm = params_;
    const int blocks = blocks_.count();
    std::vector<Dissipated> part(Energy ? blocks : 0);
    if (Energy && dashpot_.size() != n) dashpot_.assign(n, Vec<D>::Zero());
    if (Energy && wall_dashpot_.size() != wall_pairs_.size()) wall_dashpot_.assign(wall_pairs_.size(), Vec<D>::Zero());
    // Events go to their block's list, joined in block order afterwards: rare, and deterministic.
    block_events_.resize(blocks);
    events_.clear();
    block_passing_.assign(blocks, kNone);
    block_touching_.assign(blocks, 0);
    const bool kept = !s.pair_force.empty();
    passing_.reset();
    // A split world's pair is computed on both its particles' processes; its energy counts on A's.
    auto counted = [&p](int a) { return !p.is_ghost(a); };
#pragma omp parallel for schedule(static) if (n > std::size_t(kParallelMin))
    for (int b = 0; b < blocks; ++b) {
      const std::size_t end = blocks_.first[b + 1];
      BlockTarget t{blocks_.near_end[b], at.far + blocks_.far[b], 0};
      // Only this block adds to its group's sums (Slots): zeroed here, they are still in the cache when its pairs add
      // to them, where a pass of their own beforehand would stream them from memory twice.
      if (zero_sums)
        for (int i = blocks_.group_first(b); i < t.near_end; ++i) {
          s.sum_force[i].setZero();
          s.sum_moment[i].setZero();
        }
      Dissipated dissipated;
      auto one = [&](std::size_t c) __attribute__((always_inline)) {
        const auto [i, j] = pairs_[c];
        const bool far = j >= t.near_end;
        const std::size_t slot = far ? t.far++ : 0;
        const Vec<D> d = p.x[j] - p.x[i];
        const double reach = p.radius[i] + p.radius[j];
        if (d.squaredNorm() >= reach * reach && !Model::template persistent<D>(states_.get(c))) {
          if constexpr (Energy) {
            if (counted(i))
              dissipated.contacts.add(Model::template released_energy<D>(
                  Model::template pair<D>(prm, p.radius[i], p.radius[j], p.stiffness[i], p.stiffness[j]),
                  states_.get(c)));
            if (dashpot_[c].squaredNorm() > 0) {  // the last step's dashpot force acted as the pair parted
              Vec<D> ca, cb;
              if (counted(i))
                dissipated.contacts.add(-0.5 * dashpot_[c].dot(ball_geometry(p, i, j, dt, ca, cb).v_rel) * dt);
              dashpot_[c].setZero();
            }
          }
          states_.set(c, State{});  // apart and unbonded: no force, no history
          if (kept) s.pair_force[at.pair + c].setZero();
          if (far && s.live[slot]) {
            s.f[slot].setZero();
            s.mb[slot].setZero();
            s.live[slot] = 0;
          }
          return;
        }
        Vec<D> ca, cb;
        const auto g = ball_geometry(p, i, j, dt, ca, cb);
        if (g.overlap > 0.5 * std::min(g.r_a, g.r_b)) [[unlikely]]
          block_passing_[b] = std::min(block_passing_[b], c);
        // The model works on a copy in registers; one store back.
        State local = states_.get(c);
        const auto r =
            Model::template force<D, Energy>(Model::template pair<D>(prm, g.r_a, g.r_b, g.k_a, g.k_b), g, local);
        states_.set(c, local);
        const Rot<D> mb = Dim<D>::cross(cb, r.force) + r.moment;
        s.sum_force[i] -= r.force;
        s.sum_moment[i] += Dim<D>::cross(ca, Vec<D>(-r.force)) - r.moment;
        if (far) {
          s.f[slot] = r.force;
          s.mb[slot] = mb;
          s.live[slot] = 1;
        } else {
          s.sum_force[j] += r.force;
          s.sum_moment[j] += mb;
        }
        if (kept) s.pair_force[at.pair + c] = r.force;
        if (r.force.squaredNorm() > 0 && counted(i)) ++t.touching;
        if (r.event.mode != CrackMode::None) [[unlikely]]
          block_events_[b].push_back({i, j, p.x[i] + ca, g.n, r.event});
        if constexpr (Energy) {
          // Central differences balance ½ m v(t−½)·v(t+½) against ½ F(t)·(v(t−½) + v(t+½)) Δt: half of a
          // dashpot force's work is booked now, half at the next step with the velocity it produced.
          if (counted(i)) {
            dissipated.contacts.add(r.dissipated - 0.5 * (dashpot_[c] + r.dashpot).dot(g.v_rel) * dt);
            dissipated.bonds.add(r.fractured);
          }
          dashpot_[c] = r.dashpot;
        }
      };
      std::size_t c = blocks_.first[b];
      if constexpr (!Energy && requires { LaneLaw<Model, D>::force; }) {
        // Beyond the caches a batch of lanes waits on its far partners B (one pair in fourteen has its B more
        // than 4 096 particles further along the Morton curve). Asking for the B's of the batch after next while
        // this one computes overlaps those misses with its arithmetic: 9–12 % less time per step on bonded blocks
        // of 10^6 and 10^7, none in the cache (benchmarks/results/bonded_scaling_notes.md).
        constexpr std::size_t kAhead = 2 * kLanes;
        for (; c + kLanes <= end; c += kLanes) {
          for (std::size_t k = c + kAhead; k < std::min(end, c + kAhead + kLanes); ++k)
            p.prefetch_contact_fields(pairs_[k][1]);
          if (!LaneLaw<Model, D>::force(prm, p, &pairs_[c], states_.history(c), states_.properties(c), s, t,
                                        at.pair + c, dt))
            for (int l = 0; l < kLanes; ++l) one(c + l);
        }
      }
      for (; c < end; ++c) one(c);
      block_touching_[b] = t.touching;
      if constexpr (Energy) part[b] = dissipated;
    }
    touching_ = 0;
    for (std::size_t k : block_touching_) touching_ += k;
    for (auto& be : block_events_) {
      if (be.empty()) continue;
      events_.insert(events_.end(), be.begin(), be.end());
      be.clear();
    }
    for (std::size_t c : block_passing_)
      if (c != kNone) {
        passing_ = pairs_[c];
        break;
      }
    Dissipated e;
    for (const Dissipated& x : part) e += x;
    // Walls touch few balls; a serial loop keeps the order fixed.
    for (std::size_t c = 0; c < wall_pairs_.size(); ++c) {
      const auto [w, j] = wall_pairs_[c];
      const std::size_t slot = at.wall + c;
      Vec<D> cw, cb;
      const auto g = wall_geometry(p, walls[w], j, dt, cw, cb);
      if (g.overlap > 0.5 * g.r_b && !passing_) [[unlikely]]
        passing_ = Pair{-1 - w, j};
      State st = wall_states_.get(c);
      const auto r =
          Model::template force<D, Energy>(Model::template wall<D>(prm, walls[w].material, g.r_b, g.k_b), g, st);
      wall_states_.set(c, st);
      s.f[slot] = r.force;
      s.wall_moment[at.wall_moment + c] = Dim<D>::cross(cw, Vec<D>(-r.force)) - r.moment;  // about its origin
      s.mb[slot] = Dim<D>::cross(cb, r.force) + r.moment;
      s.live[slot] = 1;
      if constexpr (Energy) {
        e.contacts.add(r.dissipated - 0.5 * (wall_dashpot_[c] + r.dashpot).dot(g.v_rel) * dt);
        e.bonds.add(r.fractured);
        wall_dashpot_[c] = r.dashpot;
      }
    }
    return e;
  }

  // Sorted merge of the old (pair, state) list with the new candidates.
  // The dashpot forces of the last step (energy tracing only) travel with their pairs.
  void merge(std::vector<Pair>& pairs, Columns& states, std::vector<Vec<D>>& dashpot, const std::vector<Pair>& cand) {
    const bool traced = !dashpot.empty();
    std::vector<Pair> np;
    Columns ns;
    std::vector<Vec<D>> nd;
    np.reserve(cand.size());
    ns.reserve(cand.size());
    auto keep = [&](std::size_t a) {
      np.push_back(pairs[a]), ns.push_back(states.get(a));
      if (traced) nd.push_back(dashpot[a]);
    };
    std::size_t a = 0, b = 0;
    while (a < pairs.size() || b < cand.size()) {
      if (b == cand.size() || (a < pairs.size() && pairs[a] < cand[b])) {
        if (Model::template persistent<D>(states.get(a))) keep(a);
        ++a;
      } else if (a < pairs.size() && pairs[a] == cand[b]) {
        keep(a);
        ++a, ++b;
      } else {
        np.push_back(cand[b]), ns.push_back(State{});
        if (traced) nd.push_back(Vec<D>::Zero());
        ++b;
      }
    }
    pairs.swap(np);
    states.swap(ns);
    dashpot.swap(nd);
  }

  // Keeps the pairs that keep(pair, renumbered) accepts, renumbered; the order stays sorted, as the
  // renumbering keeps the particles' order.
  template <class Keep>
  static void renumber_list(std::vector<Pair>& pairs, Columns& states, std::vector<Vec<D>>& dashpot, Keep&& keep) {
    const bool traced = !dashpot.empty();
    std::size_t out = 0;
    for (std::size_t c = 0; c < pairs.size(); ++c) {
      Pair renumbered;
      if (!keep(pairs[c], renumbered)) continue;
      pairs[out] = renumbered;
      states.copy(c, out);
      if (traced) dashpot[out] = dashpot[c];
      ++out;
    }
    pairs.resize(out);
    states.resize(out);
    if (traced) dashpot.resize(out);
  }

  typename Model::Params params_;
  std::vector<Pair> pairs_, wall_pairs_;
  Columns states_, wall_states_;
  std::vector<Vec<D>> dashpot_, wall_dashpot_;  // last step's dashpot forces, only while energy is traced
  std::vector<std::vector<PairEvent<D>>> block_events_;
  std::vector<PairEvent<D>> events_;
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  std::vector<std::size_t> block_passing_;  // per block: its first contact passing through, or kNone
  PairBlocks blocks_;                       // of the force pass (partition)
  std::vector<std::size_t> block_touching_;
  std::size_t touching_ = 0;
  std::optional<Pair> passing_;
};

}  // namespace mc
