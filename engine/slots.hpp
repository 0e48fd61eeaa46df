// Where the force pass puts its results: per particle the sums of its contacts computed by the thread that holds it,
// a slot for each contact whose other particle another thread holds, and the timestep estimate's use of the same
// numbers between force passes.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/dim.hpp"

namespace mc {

// The force pass runs in blocks, one per group of kGroup particles (parallel.hpp); pairs are sorted by A, so a block
// holds all of its group's pairs as A, and one thread computes them. It adds the force on A and A's moment into A's
// sums, and when B is of the same group (a near pair, most of them along a Morton curve) the force and moment on B
// into B's sums: no other thread touches those particles, and the sums run in pair order. A far pair, whose B
// another block holds, writes both into a slot of its own instead; each particle then adds its far slots and its
// wall contacts' in a fixed order (the gather). So every particle's sum is the same on any number of threads, and on
// any number of processes (groups are drawn on the whole world's numbering).
// `live` is 0 for a slot known to hold zeros: a pair apart in the last force pass whose slot was zeroed then (most
// candidates of a loose packing). The force pass writes it no more and the gather skips it, which leaves every
// sum as it was but for the sign of a zero. Whatever writes the slots outside a force pass marks them all live.
// A wall contact also gives the moment on the wall about its origin. `pair_force` keeps every ball pair's force on B
// for the measurements that read single contacts (stress, coordination), and only while the world is asked to.
// The force sums are the particles' own resultant forces (Particles::f), which the gather completes.
template <int D>
struct Slots {
  std::vector<Vec<D>> f;  // per slot: far pairs then wall contacts, set by set
  std::vector<Rot<D>> mb;
  std::vector<std::uint8_t> live;
  std::vector<Rot<D>> wall_moment;  // per wall contact
  Vec<D>* sum_force = nullptr;      // per particle (Particles::f): the forces of its contacts summed in the force pass
  std::vector<Rot<D>> sum_moment;   // and their moments on it
  std::vector<Vec<D>> pair_force;   // per ball pair (kept forces only): the force on B
  void resize(std::size_t slots, std::size_t wall_contacts, std::size_t particles, std::size_t kept_pairs) {
    f.assign(slots, Vec<D>::Zero());
    mb.assign(slots, Rot<D>::Zero());
    live.assign(slots, 0);
    wall_moment.assign(wall_contacts, Rot<D>::Zero());
    sum_moment.assign(particles, Rot<D>::Zero());
    pair_force.assign(kept_pairs, Vec<D>::Zero());
  }
  void clear() { resize(f.size(), wall_moment.size(), sum_moment.size(), pair_force.size()); }
  void mark_all_live() { std::fill(live.begin(), live.end(), std::uint8_t{1}); }
  std::size_t bytes() const {
    return f.capacity() * sizeof(Vec<D>) + mb.capacity() * sizeof(Rot<D>) + live.capacity() +
           wall_moment.capacity() * sizeof(Rot<D>) + sum_moment.capacity() * sizeof(Rot<D>) +
           pair_force.capacity() * sizeof(Vec<D>);
  }
};

// Where one contact set writes: its far pairs' slots from `far`, its wall contacts' from `wall`, their moments on the
// walls from `wall_moment`, and its pairs' kept forces from `pair`.
struct SlotOffsets {
  std::size_t far = 0, wall = 0, wall_moment = 0, pair = 0;
};

// One block of the force pass as it runs: pairs whose B is below `near_end` are near (B is of the block's group);
// the others take the far slots from `far` on, in pair order. `touching` counts the pairs that gave a force and whose
// A is held as its own (World::contact_count).
struct BlockTarget {
  int near_end = 0;
  std::size_t far = 0;
  std::size_t touching = 0;
};

// Stiffness of each slot for the timestep estimate: translational, and rotational about B's centre; and per particle
// the sums over the contacts the force pass sums (as it sums forces). The estimate runs between force passes and
// borrows the slots' own numbers for them, so it costs no memory per contact (World::refresh_timestep says when they
// are given back); the particles' sums it keeps in `sums` (two per particle) while it runs, as the particles'
// forces must stay as they are.
template <int D>
struct SlotStiffness {
  Slots<D>& s;
  std::vector<double>& sums;
  double& kt(std::size_t slot) { return s.f[slot][0]; }
  double& krb(std::size_t slot) { return s.mb[slot][0]; }
  double& sum_kt(int i) { return sums[2 * static_cast<std::size_t>(i)]; }
  double& sum_kr(int i) { return sums[2 * static_cast<std::size_t>(i) + 1]; }
};

}  // namespace mc
