// The explicit engine: the state of one simulation and its cycle in PFC order (Tang 2013, Fig. 3.2):
// contact detection → force–displacement per contact model → gather per particle → law of motion →
// walls. What the scene observes (histories, frames, measurements) is driven from outside, by the runner.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/archive.hpp"
#include "engine/contact_set_base.hpp"
#include "engine/decomposition.hpp"
#include "engine/driven_group.hpp"
#include "engine/exchange.hpp"
#include "engine/opening_gauge.hpp"
#include "engine/particles.hpp"
#include "engine/wall.hpp"

namespace mc {

// Energy terms, Tang (3.74)–(3.80) plus the work of local damping. Traced only when the scene asks.
struct EnergyTrace {
  double body_work = 0;            // gravity and applied loads, (3.74)
  double boundary_work = 0;        // walls, (3.76)
  double dissipated_contacts = 0;  // friction slip (3.77), plastic flow, contact dashpots, viscosity
  double dissipated_bonds = 0;     // bond breakage, softening and damage: the work of fracture
  double dissipated_local = 0;     // PFC local damping
  double kinetic = 0;              // (3.79), at the current time
  double strain = 0;               // (3.80) and the models' own, at the current time (updated by World::update_energy)
  double initial = 0;              // kinetic + strain when tracing started
  // Work put in minus what is stored and dissipated; zero for an exact integrator.
  double residual() const {
    return initial + body_work + boundary_work - kinetic - strain - dissipated_contacts - dissipated_bonds -
           dissipated_local;
  }
};

struct TimestepControl {
  double safety = 0.8;  // fraction of the critical step, Tang (3.24)
  double fixed = 0;     // > 0: use this step (refused if above the critical estimate)
  int every = 10;       // re-estimate every N steps (and at every neighbour-list rebuild)
};

// One ball pair's contact as a frame records it (World::gather_contacts).
template <int D>
struct ContactRow {
  std::int64_t set, a, b;  // its contact set, and its particles A < B in whole-world indices
  Vec<D> force, branch;    // the force on B [N]; x_B − x_A [m] where the force pass found them, before the motion
  std::int64_t bonded;     // 1: a persistent pair (an intact bond), else 0
};

template <int D>
class World {
 public:
  Particles<D> particles;
  std::vector<Wall<D>> walls;
  std::vector<OpeningGauge<D>> gauges;  // read by walls under opening control (and by the scene's probes)
  std::vector<DrivenGroup<D>> driven;   // particle groups moved at a ramped velocity
  std::vector<std::unique_ptr<ContactSetBase<D>>> sets;
  std::vector<std::vector<int>> model_of;  // [phase_a][phase_b] → index in sets; −1: no interaction

  double skin = 0;  // Verlet skin [m]; 0 → 0.1 R_min at init. With an adaptive skin, the current one.
  // Adaptive skin: rebuilds aimed this many steps apart. At each rebuild the skin becomes 2 × (the largest
  // displacement per step since the last one) × this, between the skin set at init and R_min, so a flow that
  // would rebuild every few steps gets a wider skin, and a quiet specimen keeps its own (Yade's collider adapts
  // its Verlet distance likewise). 0: the skin stays as set (the default here; scenes default to 30).
  int rebuild_interval = 0;
  double local_damping = 0;  // PFC local damping coefficient α
  std::optional<Vec<D>> gravity;
  bool applied_loads = false;
  bool trace_energy = false;
  TimestepControl timestep;
  Vec<D> domain_lo, domain_hi;  // leaving this box stops the run

  double dt = 0, dt_critical = 0, time = 0;
  std::int64_t step_count = 0;
  std::int64_t rebuilds = 0;
  EnergyTrace energy;

  // Call once the particles, walls and sets are in place (and after loading a checkpoint). Throws TimestepError
  // when a fixed timestep is above the critical one (so can step(), when the stiffnesses grow).
  void init();
  void step();
  // Bonds every pair whose gap is at most tolerance·min(R_A, R_B), with the model of its phase pair (models
  // without bonds ignore it); strengths drawn per pair from `seed`. A model with an interaction radius R_I
  // (cpm) bonds its pairs with centre distance ≤ R_I (R_A + R_B) instead. Call after init(). Returns the count.
  std::size_t install_bonds(double tolerance, std::uint64_t seed);
  void update_energy();  // kinetic and strain energy at the current time into `energy`
  // Stability guard. Every step (in step()): a particle that moves more than half its radius in one step or goes
  // non-finite, and two particles (or a particle and a wall) overlapping by more than half the smaller radius,
  // which the contact law can no longer hold apart. Here, as often as the caller likes and at the end of a run:
  // walls (and their opening servos), the domain and the energy balance. Each throws InstabilityError naming
  // the step, the particle or wall and the likely cause.
  void check_stability() const;
  // The specimen's particle ids, used to name particles in messages (empty: their indices).
  std::vector<std::int64_t> ids;
  std::string particle_name(int i) const {
    return "particle " + std::to_string(ids.empty() ? global_index(i) : ids[i]);
  }

  // The crack log: every bond break and first yield since the start, in step order then pair order.
  std::vector<Crack<D>> cracks;
  // Cracks of a kind and mode; phases −1 count any phase (the pair is unordered).
  std::int64_t crack_count(CrackKind kind, CrackMode mode, int phase_a = -1, int phase_b = -1) const;
  // The whole world's counts; a split world's processes call them together (each pair counts on A's process).
  std::size_t bond_count() const;     // intact bonds of all models
  std::size_t contact_count() const;  // ball–ball contacts that gave a force in the last step (0 before one)
  // This process's lists (a split world's: pairs with an own particle, those across a cut on both sides).
  std::size_t candidate_count() const;  // pairs in the neighbour lists
  // Measurements of single contacts (stress, coordination, contact forces) need each ball pair's force, which the
  // force pass otherwise sums into its particles without keeping it: ask for it once (a scene does when it measures
  // them), and from the next force pass on it is kept, 24 bytes per pair (16 in 2D) and 4 for a list per contact.
  void keep_contact_forces();
  // The force on B of pair c of set s in the last force pass; all sets' pairs one after another (kept forces only).
  Vec<D> contact_force(int set, std::size_t c) const { return kept().pair_force[pair_offset_[set] + c]; }
  // Every contact's force in the last force pass, set by set: the ball pairs' on B, then the wall contacts' on the
  // ball (kept forces only).
  template <class F>
  void for_each_contact_force(F&& fn) const;
  // Each contact of particle p: fn(force on p, vector from p's centre to the contact point) (kept forces only).
  template <class F>
  void for_each_contact_of(int p, F&& fn) const;
  std::size_t slot_count() const { return slots_.f.size(); }  // far pairs' and wall contacts'
  std::size_t slot_bytes() const { return slots_.bytes(); }
  std::size_t gather_bytes() const {
    return (gather_start_.capacity() + gather_items_.capacity() + contact_start_.capacity() +
            contact_items_.capacity()) *
           sizeof(int);
  }

  // The complete dynamic state (checkpoints): restoring it and stepping on gives the same bits as never stopping.
  // A split world's processes save together: the whole world's state is gathered into process 0's archive (the
  // others' stay empty). Restore a whole world, then split it (on any number of processes).
  void save(Archive& a) const;
  void restore(const Archive& a);

  // Splits the specimen across the processes of `exchange` by recursive coordinate bisection of the current
  // positions: this process keeps the particles of its region, and as ghosts the others' that its contacts reach.
  // Every contact is computed on each process that holds one of its particles, and each particle sums its own
  // contacts in the serial order, so any number of processes gives the bits of the whole world. Call on every
  // process with the same world, after init() and install_bonds(). Sums over particles or contacts (energy
  // terms, wall forces, gauge readings) are exact (engine/exact_sum.hpp) and shared, so they are the serial bits
  // too.
  void split(const Exchange& exchange);
  bool is_split() const { return split_.has_value(); }
  // A split world's load balance: at a rebuild, when the process that owns the most particles owns more than
  // (1 + imbalance_limit) times the mean, the regions are bisected afresh from the current positions (the bits do
  // not change: only who computes what). 0: the regions stay as split() drew them.
  double imbalance_limit = 0;
  std::int64_t rebalances() const { return split_ ? split_->rebalances : 0; }
  // The particle's index in the whole world (its own index when the world is whole).
  std::int64_t global_index(int i) const { return split_ ? split_->global[i] : i; }
  // The particles this process holds, its own and ghosts, and its own alone.
  int held_count() const { return particles.size(); }
  int own_count() const;
  // Where the particle of whole-world index `global` is held here (−1: not held).
  int held_index(std::int64_t global) const;
  // What observers need of a split world; its processes call these together, in the same order.
  // Sums taken on each process made the whole world's (nothing to do when the world is whole).
  void agree_sums(std::vector<ExactSum>& sums) const;
  // A count taken on each process made the whole world's.
  std::size_t whole_count(std::size_t n) const;
  // Per-particle values of the held particles (`held[k][i]`: array k, particle i), gathered on process 0 in the
  // whole world's order from their owners; the other processes get nothing. A whole world returns them as given.
  std::vector<std::vector<Vec<D>>> gather_whole(const std::vector<const std::vector<Vec<D>>*>& held) const;
  // Every ball pair that touched or held a bond in the last force pass (kept forces only), set by set in the lists'
  // order: its particles in whole-world indices, its force on B and B's centre less A's where that pass found them
  // (before the step's motion). A split world's are gathered
  // on process 0 from their A's owners (the others get none): its processes call it together.
  std::vector<ContactRow<D>> gather_contacts() const;

 private:
  void rebuild();
  void adapt_skin();
  void relink();  // slots and gather lists from the sets' current pair lists
  void compute_forces();
  void log_cracks();
  struct Motion {
    double moved = 0;  // the largest displacement since the last rebuild [m]
    int too_far = -1;  // the first particle that moved more than half its radius in the step (or went non-finite)
  };
  template <bool Damp, bool Gravity, bool Applied, bool Energy>
  Motion move_particles();
  // The stability guard's every-step part: the messages (for InstabilityError) naming the particle(s) and the cause.
  std::string too_far_message(int i) const;
  std::string passing_message(const Pair& pair) const;
  void check_energy() const;
  void check_opening_control() const;
  void move_walls();
  // dt_critical and dt from the current stiffnesses. The estimate borrows the slots (SlotStiffness): when no
  // force pass follows (`forces_follow` false), they are zeroed afterwards, as a relink leaves them.
  void refresh_timestep(bool forces_follow);
  // Critical timestep from the current stiffnesses, Tang (3.22)–(3.24), without the safety factor. It leaves
  // the slots holding the stiffnesses (SlotStiffness); refresh_timestep gives them back.
  double critical_timestep();

  // A specimen split across processes (engine/world_split.cpp).
  struct SplitState {
    const Exchange* exchange = nullptr;
    Decomposition<D> regions;
    double reach = 0;                               // 2 R_max of the whole specimen: the ghost layer is this + skin
    std::vector<std::int64_t> global;               // held particle → index in the whole world, increasing
    std::vector<std::vector<int>> send, fill;       // per rank: own particles whose motion goes there, ghosts it fills
    std::vector<std::vector<std::int64_t>> driven;  // the driven groups' members, whole-world indices
    std::vector<std::array<std::vector<std::int64_t>, 2>> gauges;  // the gauges' sides, whole-world indices
    std::vector<Crack<D>> cracks;               // this step's breaks of pairs whose A is its own, not yet merged
    std::array<std::int64_t, 3> passing_key{};  // this step's first pair passing through: set, A, B (whole world)
    std::string passing;                        // and the message that names it (empty: none)
    std::int64_t rebalances = 0;
    double balanced_most = 0;  // the most particles a region owned when the regions were drawn
  };
  std::optional<SplitState> split_;
  void redistribute();  // particles to their regions' processes with their pairs; ghosts refreshed
  void rebalance();     // new regions when the own counts are out of balance (imbalance_limit)
  std::vector<std::vector<int>> wanted_ghosts() const;
  void send_ghosts();
  void share_motion();  // the own particles' new motion to the processes that hold them as ghosts
  void agree_on_step(const Motion& motion);
  double agreed_min(double x) const;
  // Of the failures the processes found (an empty message: none here), the message of the one with the lowest
  // key (whole-world order), on every process; "" when none found any.
  std::string first_failure(const std::array<std::int64_t, 3>& key, const std::string& message) const;
  // Where a held particle comes from when the held set changes: the held arrays (local ≥ 0), or a record at byte
  // `at` of what rank `rank` sent.
  struct Source {
    std::int64_t global;
    int local, rank;
    std::size_t at;
    bool ghost;
  };
  // The held particles become `sources` (in whole-world order); pairs are renumbered, those that lose a
  // particle or hold only ghosts leave.
  void hold(const std::vector<Source>& sources, const std::vector<Bytes>& received);
  void own_members();  // the driven groups' and gauges' members held as own
  // Process 0's archive of a split world: the whole world's state gathered (world_split_save.cpp).
  void save_split(Archive& a) const;
  // save()'s archive from the whole world's particles, neighbour-list positions, sets' bytes and contact forces;
  // the rest (walls, gauges, crack log, scalars, energy) is the same on every process.
  void write_archive(Archive& a, const Particles<D>& p, const std::vector<Vec<D>>& x_at_rebuild,
                     std::vector<std::vector<std::uint8_t>> set_bytes, const std::vector<Vec<D>>& contact_f) const;
  void count_crack(const Crack<D>& c);

  Slots<D> slots_;
  // Per set: its far slots, wall slots, wall moments and kept pair forces start there.
  std::vector<std::size_t> offset_, wall_offset_, wall_moment_offset_, pair_offset_;
  SlotOffsets slot_offsets(std::size_t s) const {
    return {offset_[s], wall_offset_[s], wall_moment_offset_[s], pair_offset_[s]};
  }
  std::vector<int> gather_start_, gather_items_;  // items: each particle's slots as B
  // Kept forces only: each particle's contacts as B, ball pairs by their kept force (≥ 0) and wall contacts by
  // their slot (−1 − slot), set by set: what for_each_contact_of visits after the pairs as A.
  bool keep_forces_ = false;
  std::vector<int> contact_start_, contact_items_;
  const Slots<D>& kept() const;          // the slots, or logic_error when the forces are not kept
  std::vector<int> group_begin() const;  // per group (kGroup) its first particle here, then the particle count
  std::vector<Vec<D>> x_at_rebuild_;
  std::vector<Vec<D>> wall_at_rebuild_;
  double moved_ = kInf;                       // max particle displacement since the last rebuild (+ walls)
  double skin_floor_ = 0, skin_ceiling_ = 0;  // the adaptive skin's bounds: the skin at init, R_min
  std::int64_t step_at_rebuild_ = 0;
  double ke_half_ = 0;
  std::vector<std::int64_t> crack_counts_;  // [kind][mode][phase_a][phase_b], phase_a ≤ phase_b
  // The step's energy terms until move_walls adds them (with the walls' sums: one exchange a step when split):
  // dissipated in contacts and bonds, body work, local damping, kinetic, held supports.
  std::array<ExactSum, 6> step_sums_{};
};

template <int D>
template <class F>
void World<D>::for_each_contact_of(int p, F&& fn) const {
  const Slots<D>& s = kept();
  const auto& x = particles.x;
  const auto& r = particles.radius;
  auto ball = [&](int o, const Vec<D>& f) {
    const Vec<D> d = x[o] - x[p];
    const double dist = d.norm();
    const double overlap = r[p] + r[o] - dist;
    fn(f, Vec<D>(d * ((r[p] - 0.5 * overlap) / dist)));  // Tang (3.4), (3.56)
  };
  // As A: its pairs, found in each set's sorted list; then as B, set by set: its pairs, then its wall contacts.
  for (std::size_t k = 0; k < sets.size(); ++k) {
    const auto& pairs = sets[k]->pairs();
    for (auto it = std::lower_bound(pairs.begin(), pairs.end(), Pair{p, -1}); it != pairs.end() && (*it)[0] == p; ++it)
      ball((*it)[1], Vec<D>(-s.pair_force[pair_offset_[k] + static_cast<std::size_t>(it - pairs.begin())]));
  }
  for (int k = contact_start_[p]; k < contact_start_[p + 1]; ++k) {
    const int item = contact_items_[k];
    if (item >= 0) {
      std::size_t set = sets.size() - 1;
      while (pair_offset_[set] > static_cast<std::size_t>(item)) --set;
      ball(sets[set]->pairs()[item - pair_offset_[set]][0], s.pair_force[item]);
      continue;
    }
    const std::size_t slot = static_cast<std::size_t>(-1 - item);
    std::size_t set = sets.size() - 1;
    while (wall_offset_[set] > slot) --set;
    const Vec<D> c = walls[sets[set]->wall_pairs()[slot - wall_offset_[set]][0]].closest(x[p]);
    Vec<D> lever = c - x[p];
    const double dist = lever.norm();
    if (dist > 0) lever *= (r[p] - 0.5 * (r[p] - dist)) / dist;
    fn(s.f[slot], lever);
  }
}

template <int D>
template <class F>
void World<D>::for_each_contact_force(F&& fn) const {
  const Slots<D>& s = kept();
  for (std::size_t k = 0; k < sets.size(); ++k) {
    for (std::size_t c = 0; c < sets[k]->pairs().size(); ++c) fn(s.pair_force[pair_offset_[k] + c]);
    for (std::size_t c = 0; c < sets[k]->wall_pairs().size(); ++c) fn(s.f[wall_offset_[k] + c]);
  }
}

extern template class World<2>;
extern template class World<3>;

}  // namespace mc
