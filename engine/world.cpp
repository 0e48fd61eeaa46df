// The explicit cycle in PFC order (Tang Fig. 3.2): contact detection, forces per contact model, gather and law
// of motion, walls; the timestep from the current stiffnesses (Tang 3.21–3.24), bonds, cracks and energy.
#include "engine/world.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iterator>
#include <sstream>
#include <stdexcept>

#include "engine/errors.hpp"
#include "engine/parallel.hpp"

namespace mc {

template <int D>
void World<D>::init() {
  const int n = particles.size();
  double rmin = kInf;
  for (double r : particles.radius) rmin = std::min(rmin, r);
  if (skin <= 0) skin = n > 0 ? 0.1 * rmin : 0.0;
  skin_floor_ = skin;
  skin_ceiling_ = std::max(skin, n > 0 ? rmin : 0.0);
  step_at_rebuild_ = step_count;
  moved_ = kInf;  // force a rebuild before the first force computation
  rebuild();
  refresh_timestep(false);
  // Until the first step, the kinetic energy is that of the initial velocities.
  ke_half_ = 0;
  for (int i = 0; i < n; ++i)
    ke_half_ +=
        0.5 * (particles.mass[i] * particles.v[i].squaredNorm() + particles.inertia[i] * particles.w[i].squaredNorm());
}

template <int D>
void World<D>::adapt_skin() {
  if (rebuild_interval <= 0 || step_count <= step_at_rebuild_ || !std::isfinite(moved_)) return;
  const double per_step = moved_ / static_cast<double>(step_count - step_at_rebuild_);
  skin = std::clamp(2.0 * per_step * rebuild_interval, skin_floor_, skin_ceiling_);
}

template <int D>
void World<D>::rebuild() {
  adapt_skin();
  step_at_rebuild_ = step_count;
  if (split_) redistribute();
  const auto& p = particles;
  const int n = p.size();
  const int nsets = static_cast<int>(sets.size());
  // Ball–ball candidates, each sent to the set of its phase pair (a split world's: those with a particle of its own).
  std::vector<std::vector<Pair>> per_set(nsets);
  for (const Pair& pr : candidate_pairs<D>(p.x, p.radius, skin)) {
    const int s = model_of[p.phase[pr[0]]][p.phase[pr[1]]];
    if (s >= 0 && !(p.is_ghost(pr[0]) && p.is_ghost(pr[1]))) per_set[s].push_back(pr);
  }
  // Ball–wall candidates go to the set of the ball's own phase.
  std::vector<std::vector<Pair>> per_set_wall(nsets);
  for (int w = 0; w < static_cast<int>(walls.size()); ++w)
    for (int j = 0; j < n; ++j) {
      const int s = model_of[p.phase[j]][p.phase[j]];
      if (s >= 0 && !p.is_ghost(j) && (p.x[j] - walls[w].closest(p.x[j])).norm() < p.radius[j] + skin)
        per_set_wall[s].push_back({w, j});
    }
  for (int s = 0; s < nsets; ++s) {
    sets[s]->set_pairs(per_set[s]);
    sets[s]->set_wall_pairs(per_set_wall[s]);
  }
  relink();
  x_at_rebuild_ = p.x;
  wall_at_rebuild_.resize(walls.size());
  for (std::size_t w = 0; w < walls.size(); ++w) wall_at_rebuild_[w] = walls[w].displacement;
  moved_ = 0;
  ++rebuilds;
}

template <int D>
std::vector<int> World<D>::group_begin() const {
  const int n = particles.size();
  std::vector<int> first;
  std::int64_t group = -1;
  for (int i = 0; i < n; ++i) {
    const std::int64_t g = global_index(i) / kGroup;
    if (g != group) first.push_back(i), group = g;
  }
  first.push_back(n);
  return first;
}

template <int D>
void World<D>::relink() {
  const int n = particles.size();
  const int nsets = static_cast<int>(sets.size());
  const std::vector<int> groups = group_begin();
  offset_.assign(nsets, 0);
  wall_offset_.assign(nsets, 0);
  wall_moment_offset_.assign(nsets, 0);
  pair_offset_.assign(nsets, 0);
  std::size_t total = 0, wall_total = 0, pair_total = 0;
  for (int s = 0; s < nsets; ++s) {
    sets[s]->partition(groups);
    offset_[s] = total;
    total += sets[s]->far_count();
    wall_offset_[s] = total;
    total += sets[s]->wall_pairs().size();
    wall_moment_offset_[s] = wall_total;
    wall_total += sets[s]->wall_pairs().size();
    pair_offset_[s] = pair_total;
    pair_total += sets[s]->pairs().size();
  }
  slots_.resize(total, wall_total, n, keep_forces_ ? pair_total : 0);
  // Each particle's items in increasing order, so that its sum is the same on any thread count: built from
  // (particle, item) lists counted first.
  auto build = [n](std::vector<int>& start, std::vector<int>& items, auto&& for_each_item) {
    std::vector<int> count(n, 0);
    for_each_item([&](int i, int) { ++count[i]; });
    start.assign(n + 1, 0);
    for (int i = 0; i < n; ++i) start[i + 1] = start[i] + count[i];
    std::vector<int>(start[n]).swap(items);  // not resize: a list that shrank would keep its old capacity
    std::vector<int> fill(start.begin(), start.end() - 1);
    for_each_item([&](int i, int item) { items[fill[i]++] = item; });
  };
  // Gather lists: each particle's far slots as B and its wall contacts' slots. (Its near pairs the force pass
  // sums: Slots.)
  std::vector<std::vector<std::size_t>> far(nsets);
  for (int s = 0; s < nsets; ++s) far[s] = sets[s]->far_pairs();
  build(gather_start_, gather_items_, [&](auto&& add) {
    for (int s = 0; s < nsets; ++s) {
      const auto& pairs = sets[s]->pairs();
      for (std::size_t k = 0; k < far[s].size(); ++k) add(pairs[far[s][k]][1], static_cast<int>(offset_[s] + k));
      const auto& wp = sets[s]->wall_pairs();
      for (std::size_t c = 0; c < wp.size(); ++c) add(wp[c][1], static_cast<int>(wall_offset_[s] + c));
    }
  });
  if (!keep_forces_) {
    contact_start_.clear(), contact_items_.clear();
    contact_start_.shrink_to_fit(), contact_items_.shrink_to_fit();
    return;
  }
  build(contact_start_, contact_items_, [&](auto&& add) {
    for (int s = 0; s < nsets; ++s) {
      const auto& pairs = sets[s]->pairs();
      for (std::size_t c = 0; c < pairs.size(); ++c) add(pairs[c][1], static_cast<int>(pair_offset_[s] + c));
      const auto& wp = sets[s]->wall_pairs();
      for (std::size_t c = 0; c < wp.size(); ++c) add(wp[c][1], -1 - static_cast<int>(wall_offset_[s] + c));
    }
  });
}

template <int D>
void World<D>::keep_contact_forces() {
  if (keep_forces_) return;
  keep_forces_ = true;
  relink();
}

template <int D>
const Slots<D>& World<D>::kept() const {
  if (!keep_forces_)
    throw std::logic_error("World: single contacts' forces are read but not kept: call keep_contact_forces() first");
  return slots_;
}

template <int D>
std::size_t World<D>::install_bonds(double tolerance, std::uint64_t seed) {
  if (split_) throw std::logic_error("World::install_bonds: bond the whole world before splitting it");
  const auto& p = particles;
  const int nsets = static_cast<int>(sets.size());
  std::vector<std::vector<Pair>> bond(nsets);
  // The search reaches the widest criterion: the gap tolerance, or a model's interaction radius R_I, whose
  // d ≤ R_I (R_A + R_B) is a gap ≤ (R_I − 1)(R_A + R_B) ≤ 2 (R_I − 1) R_max.
  double reach = tolerance * p.max_radius();
  for (const auto& set : sets) reach = std::max(reach, 2.0 * (set->interaction_radius() - 1.0) * p.max_radius());
  for (const Pair& pr : candidate_pairs<D>(p.x, p.radius, reach * (1 + 1e-12))) {
    const auto [i, j] = pr;
    const double dist = (p.x[j] - p.x[i]).norm(), sum = p.radius[i] + p.radius[j];
    const int s = model_of[p.phase[i]][p.phase[j]];
    if (s < 0) continue;
    const double ri = sets[s]->interaction_radius();
    if (ri > 0 ? dist <= ri * sum : dist - sum <= tolerance * std::min(p.radius[i], p.radius[j])) bond[s].push_back(pr);
  }
  std::size_t n = 0;
  for (int s = 0; s < nsets; ++s) {
    // The pairs to bond join the list (they may lie beyond the skin), then get their bonds.
    std::vector<Pair> all;
    std::set_union(sets[s]->pairs().begin(), sets[s]->pairs().end(), bond[s].begin(), bond[s].end(),
                   std::back_inserter(all));
    sets[s]->set_pairs(all);
    n += sets[s]->install_bonds(particles, bond[s], seed);
  }
  relink();
  refresh_timestep(false);
  return n;
}

template <int D>
double World<D>::critical_timestep() {
  const int n = particles.size();
  // The servo gain needs Σk_n of each wall's touching contacts (those with a force in the last pass), refreshed
  // with the timestep: which ones touch is read before the slots are borrowed.
  std::vector<std::uint8_t> wall_touching;
  for (std::size_t s = 0; s < sets.size(); ++s)
    for (std::size_t c = 0; c < sets[s]->wall_pairs().size(); ++c)
      wall_touching.push_back(slots_.f[wall_offset_[s] + c].squaredNorm() > 0);
  std::vector<double> sums(2 * static_cast<std::size_t>(n), 0.0);
  SlotStiffness<D> k{slots_, sums};
  // Every pair in the lists counts (contacts about to close); once the adaptive skin has grown, only those within
  // the skin set at init, so that a wider skin does not shorten the step.
  const double margin = skin > skin_floor_ ? skin_floor_ : kInf;
  for (std::size_t s = 0; s < sets.size(); ++s) sets[s]->stiffness(particles, walls, k, slot_offsets(s), margin);
  std::vector<ExactSum> kn(walls.size());
  for (std::size_t s = 0, at = 0; s < sets.size(); ++s) {
    const auto& wp = sets[s]->wall_pairs();
    for (std::size_t c = 0; c < wp.size(); ++c)
      if (wall_touching[at++]) kn[wp[c][0]].add(k.kt(wall_offset_[s] + c));
  }
  agree_sums(kn);
  for (std::size_t w = 0; w < walls.size(); ++w) walls[w].contact_kn = kn[w].value();
  double tmin = kInf;
#pragma omp parallel for schedule(static) reduction(min : tmin) if (n > kParallelMin)
  for (int i = 0; i < n; ++i) {
    if (particles.is_ghost(i)) continue;  // its own process counts it
    double kt = k.sum_kt(i), kr = k.sum_kr(i);
    for (int c = gather_start_[i]; c < gather_start_[i + 1]; ++c) {
      const std::size_t slot = static_cast<std::size_t>(gather_items_[c]);
      kt += k.kt(slot);
      kr += k.krb(slot);
    }
    if (kt == 0) {  // no neighbour yet: as if it touched an identical particle
      const int s = model_of[particles.phase[i]][particles.phase[i]];
      if (s < 0) continue;
      const ContactStiffness st = sets[s]->nominal_stiffness(particles.radius[i]);
      kt = st.normal + st.shear;
      kr = st.shear * particles.radius[i] * particles.radius[i] + st.rotational;
    }
    double t = std::sqrt(particles.mass[i] / kt);                       // Tang (3.22)
    if (kr > 0) t = std::min(t, std::sqrt(particles.inertia[i] / kr));  // Tang (3.23)
    tmin = std::min(tmin, t);
  }
  if (split_) tmin = agreed_min(tmin);
  // Dashpots lower the limit of central differences from 2/ω to (2/ω)(√(1 + ζ²) − ζ) (Belytschko et al.), ζ the
  // damping ratio of the mode. A dashpot's ζ is declared on the pair's translational mass m_A m_B/(m_A + m_B); the
  // shear dashpot also acts on the spins, and the mode in which the spheres slide and turn together has the
  // mass 1/(1/m_A + 1/m_B + R_A²/I_A + R_B²/I_B) at the contact point, 1/(1 + 1/f) of it for solid particles
  // (I = f m R²): its damping ratio is ζ √(1 + 1/f), √3.5 ζ for spheres and √3 ζ for discs. With the declared ζ
  // for it, a pair at ζ = 0.9 blows up at the reported step (tests/dashpot_timestep.cpp).
  double zeta = 0;
  for (const auto& s : sets) zeta = std::max(zeta, s->damping_ratio());
  zeta *= std::sqrt(1.0 + 1.0 / Dim<D>::inertia_factor);
  return tmin * (std::sqrt(1.0 + zeta * zeta) - zeta);
}

template <int D>
void World<D>::refresh_timestep(bool forces_follow) {
  dt_critical = critical_timestep();
  // The estimate borrowed the slots: unless a force pass overwrites them next, they are given back zeroed, as a
  // relink leaves them (so is a refused step's: they hold stiffnesses, not forces).
  const bool refused = timestep.fixed > 0 && timestep.fixed > dt_critical;
  if (!forces_follow || refused)
    slots_.clear();
  else
    slots_.mark_all_live();  // stiffnesses in every slot until the force pass writes or zeroes it
  if (timestep.fixed > 0) {
    if (refused) {
      std::ostringstream m;
      m << "the fixed timestep " << timestep.fixed << " s is above the critical timestep " << dt_critical
        << " s estimated from the current stiffnesses (Tang 3.24) at step " << step_count;
      throw TimestepError(m.str());
    }
    dt = timestep.fixed;
  } else {
    dt = timestep.safety * dt_critical;
  }
  if (!std::isfinite(dt)) dt = 0;
}

template <int D>
void World<D>::compute_forces() {
  // Each set's pass adds to the sums, set after set; the first zeroes them, group by group. A split world's ghosts get
  // partial sums, which nothing reads: their owners send them whole.
  slots_.sum_force = particles.f.data();
  if (sets.empty())
    for (int i = 0; i < particles.size(); ++i) particles.f[i].setZero(), slots_.sum_moment[i].setZero();
  Dissipated e;
  for (std::size_t s = 0; s < sets.size(); ++s) {
    e += sets[s]->forces(particles, walls, dt, trace_energy, s == 0, slots_, slot_offsets(s));
    if (const auto pr = sets[s]->passing_through()) [[unlikely]] {
      if (!split_) throw InstabilityError(passing_message(*pr));
      // A split world fails at the end of the step, on every process together (agree_on_step).
      if (split_->passing.empty()) {
        const auto [a, b] = *pr;
        split_->passing_key = {static_cast<std::int64_t>(s), a < 0 ? a : global_index(a), global_index(b)};
        split_->passing = passing_message(*pr);
      }
    }
  }
  if (trace_energy) step_sums_[0] = e.contacts, step_sums_[1] = e.bonds;
  log_cracks();
}

template <int D>
void World<D>::log_cracks() {
  const int np = static_cast<int>(model_of.size());
  if (crack_counts_.size() != std::size_t(2 * 3 * np * np)) crack_counts_.assign(2 * 3 * np * np, 0);
  for (std::size_t s = 0; s < sets.size(); ++s) {
    for (const PairEvent<D>& e : sets[s]->events()) {
      if (particles.is_ghost(e.a)) continue;  // logged by A's own process
      // The step being taken (step_count counts completed steps) and the time of its force evaluation.
      const Crack<D> c{step_count + 1,
                       time,
                       static_cast<int>(global_index(e.a)),
                       static_cast<int>(global_index(e.b)),
                       e.position,
                       e.normal,
                       e.event.mode,
                       e.event.kind,
                       static_cast<int>(s),
                       particles.phase[e.a],
                       particles.phase[e.b]};
      // A split world's join the log at the end of the step, merged in this order (agree_on_step).
      if (split_)
        split_->cracks.push_back(c);
      else
        count_crack(c);
    }
  }
}

template <int D>
void World<D>::count_crack(const Crack<D>& c) {
  const int np = static_cast<int>(model_of.size());
  cracks.push_back(c);
  const int lo = std::min(c.phase_a, c.phase_b), hi = std::max(c.phase_a, c.phase_b);
  ++crack_counts_[((int(c.kind) * 3 + int(c.mode)) * np + lo) * np + hi];
}

template <int D>
std::int64_t World<D>::crack_count(CrackKind kind, CrackMode mode, int phase_a, int phase_b) const {
  const int np = static_cast<int>(model_of.size());
  if (crack_counts_.empty()) return 0;
  std::int64_t n = 0;
  for (int a = 0; a < np; ++a)
    for (int b = a; b < np; ++b) {
      const bool match =
          (phase_a < 0 && phase_b < 0) || (std::min(phase_a, phase_b) == a && std::max(phase_a, phase_b) == b);
      if (match) n += crack_counts_[((int(kind) * 3 + int(mode)) * np + a) * np + b];
    }
  return n;
}

template <int D>
std::size_t World<D>::whole_count(std::size_t n) const {
  if (!split_) return n;
  std::vector<std::int64_t> total{static_cast<std::int64_t>(n)};
  split_->exchange->sum(total);
  return static_cast<std::size_t>(total[0]);
}

template <int D>
std::size_t World<D>::bond_count() const {
  std::size_t n = 0;
  if (!split_) {
    for (const auto& s : sets) n += s->bond_count();
    return n;
  }
  // An intact bond is what keeps a pair in the lists (ContactSetBase::persistent).
  for (const auto& s : sets)
    for (std::size_t c = 0; c < s->pairs().size(); ++c) n += !particles.is_ghost(s->pairs()[c][0]) && s->persistent(c);
  return whole_count(n);
}

// Gather and law of motion for every particle (Tang 3.11–3.20), with PFC local damping: a force
// −α|F| sign(v) per degree of freedom, which removes energy without a viscous time scale.
template <int D>
template <bool Damp, bool Gravity, bool Applied, bool Energy>
typename World<D>::Motion World<D>::move_particles() {
  auto& p = particles;
  const int n = p.size();
  const double h = dt, alpha = local_damping;
  const Vec<D> g = Gravity ? *gravity : Vec<D>::Zero();
  const int blocks = block_count(n);
  // Energy terms per block, summed exactly: the same bits on any number of threads or processes.
  std::vector<ExactSum> body(Energy ? blocks : 0), local(Energy ? blocks : 0), kin(Energy ? blocks : 0),
      held(Energy ? blocks : 0);
  double moved2 = 0;
  int too_far = n;  // the first particle that moved more than half its radius in this step, or went non-finite
  const std::uint8_t* ghost = p.ghost.empty() ? nullptr : p.ghost.data();  // moved by their own processes
#pragma omp parallel for schedule(static) reduction(max : moved2) reduction(min : too_far) if (n > kParallelMin)
  for (int b = 0; b < blocks; ++b) {
    const int end = std::min(n, (b + 1) * kBlock);
    for (int i = b * kBlock; i < end; ++i) {
      if (ghost && ghost[i]) continue;
      Vec<D> f = p.f[i];  // summed by the force pass
      Rot<D> m = slots_.sum_moment[i];
      for (int c = gather_start_[i]; c < gather_start_[i + 1]; ++c) {  // far pairs as B, wall contacts
        const std::size_t slot = static_cast<std::size_t>(gather_items_[c]);
        if (!slots_.live[slot]) continue;
        f += slots_.f[slot];
        m += slots_.mb[slot];
      }
      Vec<D> fext = Vec<D>::Zero();
      Rot<D> mext = Rot<D>::Zero();
      if constexpr (Gravity) fext += p.mass[i] * g;
      if constexpr (Applied) fext += p.f_applied[i], mext += p.m_applied[i];
      f += fext;
      m += mext;
      p.f[i] = f;
      const Vec<D> v0 = p.v[i];
      const Rot<D> w0 = p.w[i];
      const FixMask fix = p.fix[i];
      Vec<D> fd = Vec<D>::Zero();
      Rot<D> md = Rot<D>::Zero();
      // A held degree of freedom keeps its velocity: the support supplies −F, and does work −F·v Δt on the
      // specimen (booked as boundary work, like a wall's).
      double held_work = 0;
      for (int k = 0; k < D; ++k) {
        if (fix & (1u << k)) {
          if constexpr (Energy) held_work -= f[k] * v0[k] * h;
          continue;
        }
        if constexpr (Damp) fd[k] = -alpha * std::abs(f[k]) * (v0[k] > 0 ? 1.0 : (v0[k] < 0 ? -1.0 : 0.0));
        p.v[i][k] += (f[k] + fd[k]) / p.mass[i] * h;  // Tang (3.18)
      }
      for (int k = 0; k < Dim<D>::rot; ++k) {
        if (fix & (1u << (D + k))) {
          if constexpr (Energy) held_work -= m[k] * w0[k] * h;
          continue;
        }
        if constexpr (Damp) md[k] = -alpha * std::abs(m[k]) * (w0[k] > 0 ? 1.0 : (w0[k] < 0 ? -1.0 : 0.0));
        p.w[i][k] += (m[k] + md[k]) / p.inertia[i] * h;  // Tang (3.19), spheres
      }
      const Vec<D> dx = p.v[i] * h;
      p.x[i] += dx;  // Tang (3.20)
      moved2 = std::max(moved2, (p.x[i] - x_at_rebuild_[i]).squaredNorm());
      // The stability guard's every-step part, one comparison per particle (written so that NaN fails it too).
      if (!(dx.squaredNorm() <= 0.25 * p.radius[i] * p.radius[i])) [[unlikely]]
        too_far = std::min(too_far, i);
      if constexpr (Energy) {
        // Forces act at t, between the half-step velocities they change: their power is F·v(t), with
        // v(t) = ½(v(t−Δt/2) + v(t+Δt/2)), which is what central differences take out of ½ m v(t−Δt/2)·v(t+Δt/2).
        body[b].add(0.5 * h * (fext.dot(v0 + p.v[i]) + mext.dot(w0 + p.w[i])));  // Tang (3.74)
        held[b].add(held_work);
        local[b].add(-0.5 * h * (fd.dot(v0 + p.v[i]) + md.dot(w0 + p.w[i])));
        // ½ m v(t−Δt/2)·v(t+Δt/2) is the kinetic energy at t for which central differences conserve
        // energy exactly in a linear system.
        kin[b].add(0.5 * (p.mass[i] * v0.dot(p.v[i]) + p.inertia[i] * w0.dot(p.w[i])));  // Tang (3.79)
      }
    }
  }
  if constexpr (Energy) {
    for (int b = 0; b < blocks; ++b)
      step_sums_[2] += body[b], step_sums_[3] += local[b], step_sums_[4] += kin[b], step_sums_[5] += held[b];
  }
  return {std::sqrt(moved2), too_far < n ? too_far : -1};
}

template <int D>
void World<D>::move_walls() {
  double wall_moved = 0;
  for (std::size_t w = 0; w < walls.size(); ++w) {
    Wall<D>& wl = walls[w];
    wl.force.setZero();
    wl.moment.setZero();
  }
  // The step's sums, exact (the same bits on any number of processes, which share them here, once a step): the
  // energy terms of the force pass and the law of motion, each wall's force and moment, the gauges' readings.
  constexpr int kWallTerms = D + Dim<D>::rot;
  const std::size_t energy_terms = trace_energy ? step_sums_.size() : 0;
  std::vector<ExactSum> sums(energy_terms + walls.size() * kWallTerms + gauges.size() * 2 * D);
  std::copy_n(step_sums_.begin(), energy_terms, sums.begin());
  ExactSum* wall_sums = sums.data() + energy_terms;
  ExactSum* gauge_sums = wall_sums + walls.size() * kWallTerms;
  for (std::size_t s = 0; s < sets.size(); ++s) {
    const auto& wp = sets[s]->wall_pairs();
    for (std::size_t c = 0; c < wp.size(); ++c) {
      const std::size_t slot = wall_offset_[s] + c;
      ExactSum* w = wall_sums + wp[c][0] * kWallTerms;
      for (int k = 0; k < D; ++k) w[k].add(-slots_.f[slot][k]);
      for (int k = 0; k < Dim<D>::rot; ++k) w[D + k].add(slots_.wall_moment[wall_moment_offset_[s] + c][k]);
    }
  }
  for (std::size_t g = 0; g < gauges.size(); ++g) gauges[g].add_sums(particles, gauge_sums + g * 2 * D);
  agree_sums(sums);
  if (trace_energy) {
    energy.dissipated_contacts += sums[0].value();
    energy.dissipated_bonds += sums[1].value();
    energy.body_work += sums[2].value();
    energy.dissipated_local += sums[3].value();
    ke_half_ = sums[4].value();
    energy.boundary_work += sums[5].value();
    step_sums_.fill(ExactSum{});
  }
  for (std::size_t w = 0; w < walls.size(); ++w) {
    for (int k = 0; k < D; ++k) walls[w].force[k] = wall_sums[w * kWallTerms + k].value();
    for (int k = 0; k < Dim<D>::rot; ++k) walls[w].moment[k] = wall_sums[w * kWallTerms + D + k].value();
  }
  for (std::size_t g = 0; g < gauges.size(); ++g) gauges[g].read(gauge_sums + g * 2 * D);
  for (auto& wl : walls) {
    if (wl.area_between.empty()) continue;
    double a = 1;
    for (const auto& [lo, hi] : wl.area_between)
      a *= std::abs((walls[hi].origin - walls[lo].origin).dot(walls[lo].normal));
    wl.servo_area = a;
  }
  for (std::size_t w = 0; w < walls.size(); ++w) {
    Wall<D>& wl = walls[w];
    wl.control_velocity(time, dt, wl.gauge >= 0 ? gauges[wl.gauge].reading() : 0.0);
    const Vec<D> du = wl.velocity * dt;
    if (trace_energy) energy.boundary_work -= wl.force.dot(du);  // Tang (3.76): work done on the balls
    wl.origin += du;
    wl.displacement += du;
    wall_moved = std::max(wall_moved, (wl.displacement - wall_at_rebuild_[w]).norm());
  }
  moved_ += wall_moved;
}

template <int D>
void World<D>::step() {
  if (moved_ > 0.5 * skin) {
    rebuild();
    refresh_timestep(true);
  } else if (timestep.every > 0 && step_count % timestep.every == 0) {
    refresh_timestep(true);
  }
  compute_forces();
  for (const DrivenGroup<D>& g : driven) g.drive(particles, time);
  const bool damp = local_damping > 0, grav = gravity.has_value();
  Motion motion;
  // One instantiation per combination of declared effects: an effect the scene leaves out is not in the loop.
  const int key = (damp ? 1 : 0) | (grav ? 2 : 0) | (applied_loads ? 4 : 0) | (trace_energy ? 8 : 0);
  [&]<int... K>(std::integer_sequence<int, K...>) {
    ((key == K ? (motion = move_particles<bool(K & 1), bool(K & 2), bool(K & 4), bool(K & 8)>(), 0) : 0), ...);
  }
  (std::make_integer_sequence<int, 16>{});
  if (split_) {
    share_motion();
    agree_on_step(motion);
  } else {
    if (motion.too_far >= 0) [[unlikely]]
      throw InstabilityError(too_far_message(motion.too_far));
    moved_ = motion.moved;
  }
  move_walls();
  time += dt;
  ++step_count;
  if (trace_energy) energy.kinetic = ke_half_;
}

template <int D>
void World<D>::update_energy() {
  // Central differences conserve ½ m v(t−Δt/2)·v(t+Δt/2) + U(x(t)) exactly for linear springs. The kinetic term
  // of the last step (ke_half_) and the shear springs it updated belong to the time of its force pass, one step
  // before the current positions, so the strain must be taken at those positions too (else the sum is off by
  // F·v Δt, a fraction ~ωΔt of the vibrating energy). They are x − v Δt, with v = v(t−Δt/2) the velocity that
  // moved them; the walls likewise.
  const bool back = step_count > 0;
  std::vector<Vec<D>> x_now;
  std::vector<Vec<D>> wall_now(walls.size());
  if (back) {
    x_now = particles.x;
    for (int i = 0; i < particles.size(); ++i) particles.x[i] -= particles.v[i] * dt;
    for (std::size_t w = 0; w < walls.size(); ++w) {
      wall_now[w] = walls[w].origin;
      walls[w].origin -= walls[w].velocity * dt;
    }
  }
  std::vector<ExactSum> e(1);
  for (const auto& s : sets) e[0] += s->strain_energy(particles, walls);
  agree_sums(e);
  if (back) {
    particles.x.swap(x_now);
    for (std::size_t w = 0; w < walls.size(); ++w) walls[w].origin = wall_now[w];
  }
  energy.strain = e[0].value();
  energy.kinetic = ke_half_;
}

template <int D>
std::size_t World<D>::contact_count() const {
  std::size_t n = 0;
  for (const auto& s : sets) n += s->touching();
  return whole_count(n);
}

template <int D>
std::size_t World<D>::candidate_count() const {
  std::size_t n = 0;
  for (const auto& s : sets) n += s->pairs().size();
  return n;
}

template class World<2>;
template class World<3>;

}  // namespace mc
