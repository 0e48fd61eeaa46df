// What the world asks of a contact set, whatever its model (ContactSet in contact_set.hpp is the one
// implementation): its pair lists, its force and stiffness passes, its bonds, its events and its history as bytes
// for checkpoints and split worlds.
#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "engine/cell_grid.hpp"
#include "engine/contact_geometry.hpp"
#include "engine/crack.hpp"
#include "engine/exact_sum.hpp"
#include "engine/particles.hpp"
#include "engine/slots.hpp"
#include "engine/wall.hpp"

namespace mc {

// Energy dissipated by one pass over the contacts [J] (energy tracing only), summed exactly: the same bits however
// the contacts are split between threads or processes.
struct Dissipated {
  ExactSum contacts;  // friction slip (Tang 3.77), plastic flow, dashpots, viscosity
  ExactSum bonds;     // bond breakage, softening and damage: the work of fracture
  Dissipated& operator+=(const Dissipated& o) {
    contacts += o.contacts;
    bonds += o.bonds;
    return *this;
  }
};

template <int D>
class ContactSetBase {
 public:
  virtual ~ContactSetBase() = default;
  virtual const char* model() const = 0;
  virtual const std::vector<Pair>& pairs() const = 0;       // ball–ball (i, j), i < j, sorted
  virtual const std::vector<Pair>& wall_pairs() const = 0;  // (wall, particle), sorted
  // New candidate lists; the history of pairs present before is carried over, and pairs the model must keep
  // (intact bonds) stay even when they are no longer candidates.
  virtual void set_pairs(const std::vector<Pair>& candidates) = 0;
  virtual void set_wall_pairs(const std::vector<Pair>& candidates) = 0;
  // The blocks of the force pass for the current pair list: `group_begin` holds the first particle of each group
  // (parallel.hpp, kGroup) in this process's numbering, then the particle count. Called whenever the pairs change.
  virtual void partition(const std::vector<int>& group_begin) = 0;
  virtual std::size_t far_count() const = 0;               // pairs whose B another block holds
  virtual std::vector<std::size_t> far_pairs() const = 0;  // their indices, in the order of their slots
  // Forces into the particles' sums and the slots at `at` (Slots); with `zero_sums` (the first set of a pass) each
  // block zeroes its group's sums before adding to them. Returns the energy dissipated this step when `energy` is
  // set, else zeros.
  virtual Dissipated forces(const Particles<D>& p, const std::vector<Wall<D>>& walls, double dt, bool energy,
                            bool zero_sums, Slots<D>& slots, const SlotOffsets& at) = 0;
  // Per-slot stiffnesses for the timestep. A pair that is neither persistent (bonded) nor within `margin` of
  // touching counts nothing (kInf: every pair counts).
  virtual void stiffness(const Particles<D>& p, const std::vector<Wall<D>>& walls, SlotStiffness<D>& k,
                         const SlotOffsets& at, double margin) const = 0;
  virtual ContactStiffness nominal_stiffness(double r) const = 0;  // one contact with an identical particle
  virtual double damping_ratio() const = 0;                        // of the model's dashpots (0: none)
  // Bonds the given pairs (sorted, all present in the list); returns how many were bonded. Models without
  // bonds bond nothing.
  virtual std::size_t install_bonds(const Particles<D>& p, const std::vector<Pair>& pairs, std::uint64_t seed) = 0;
  // R_I > 0: the model bonds the pairs with centre distance ≤ R_I (R_A + R_B) (the CPM interaction radius)
  // instead of those within the gap tolerance; 0: the gap tolerance applies.
  virtual double interaction_radius() const = 0;
  // Of the pairs whose A is held as its own (all but a split world's ghosts: each pair counts once).
  virtual ExactSum strain_energy(const Particles<D>& p, const std::vector<Wall<D>>& walls) const = 0;
  // Bonds that broke or first yielded in the last forces() call, in pair order (the same on any thread count).
  virtual const std::vector<PairEvent<D>>& events() const = 0;
  // The first contact, in pair order, that the last forces() call found overlapping by more than half the smaller
  // radius (a wall contact: by more than half the ball's): the pair (a ball–wall contact: (−1 − wall, ball)) is
  // passing through each other, which no contact law can stop. Empty when none.
  virtual std::optional<Pair> passing_through() const = 0;
  virtual std::size_t bond_count() const = 0;  // intact bonds
  // Pairs that gave a force in the last pass, of those whose A is held as its own (0 until a pass after the lists
  // were last set).
  virtual std::size_t touching() const = 0;
  virtual std::size_t memory_bytes() const = 0;     // pairs, histories and side arrays, as allocated
  virtual std::size_t rewritten_bytes() const = 0;  // of those, what a force pass writes back: the histories
  // The whole history as bytes (checkpoints): pairs, wall pairs and states.
  virtual std::vector<std::uint8_t> save() const = 0;
  virtual void load(const std::vector<std::uint8_t>& bytes) = 0;

  // A specimen split across processes (engine/world_split.cpp). Whether ball pair c must stay in the lists
  // whatever the distance (an intact bond).
  virtual bool persistent(std::size_t c) const = 0;
  // The size of one pair's history as history() gives it, and that history: its state and its last dashpot
  // force (zero unless energy is traced).
  virtual std::size_t history_size() const = 0;
  virtual void history(std::size_t c, bool wall, std::vector<std::uint8_t>& out) const = 0;
  // The particles are renumbered (to[old] = new index, −1: no longer held). Pairs that lose a particle, and pairs
  // of two ghosts (another process computes them), leave; ball–wall pairs stay only with a particle of its own.
  virtual void renumber(const std::vector<int>& to, const std::vector<std::uint8_t>& ghost) = 0;
  // Pairs that arrive with their histories (history_size() bytes each, in the pairs' order); a pair already
  // present keeps its own, which is the same.
  virtual void add(const std::vector<Pair>& pairs, const std::vector<std::uint8_t>& histories, bool wall) = 0;
  // Whether the ball (or wall) pairs carry their last dashpot forces (energy traced since the lists were set).
  virtual bool traced(bool wall) const = 0;
  // The bytes save() gives for a set holding these pairs with these histories (each pair's history_size() bytes,
  // as history() gave them), the dashpot forces kept where `traced` says: a split world's whole checkpoint.
  virtual std::vector<std::uint8_t> save_of(const std::vector<Pair>& pairs,
                                            const std::vector<const std::uint8_t*>& histories, bool traced,
                                            const std::vector<Pair>& wall_pairs,
                                            const std::vector<const std::uint8_t*>& wall_histories,
                                            bool wall_traced) const = 0;
};

}  // namespace mc
