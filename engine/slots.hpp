// Where the force pass puts its results: a slot per contact for its partner B, sums per particle for its contacts
// as A, and the timestep estimate's use of the same numbers between force passes.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/dim.hpp"

namespace mc {

// Every contact owns one slot: the force on B and the moment on B. Each particle sums its slots as B in a fixed
// order (the gather), so no two threads ever add into the same particle. Its contacts as A it sums in the force pass
// itself, into a_force and a_moment: the pairs are sorted by A and a block of the pass holds all of a particle's pairs
// as A, so the sum runs in pair order on one thread, the same sum as a gather over slots would be, without the slots'
// moments on A or the lists to find them. A wall contact also gives the moment on the wall about its origin.
// `live` is 0 for a slot known to hold zeros: a pair apart in the last force pass whose slot was zeroed then (most
// candidates of a loose packing). The force pass writes it no more and the gather skips it, which leaves every
// sum as it was but for the sign of a zero. Whatever writes the slots outside a force pass marks them all live.
template <int D>
struct Slots {
  std::vector<Vec<D>> f;
  std::vector<Rot<D>> mb;
  std::vector<std::uint8_t> live;
  std::vector<Rot<D>> wall_moment;  // per wall contact
  std::vector<Vec<D>> a_force;      // per particle: −Σ F of its contacts as A
  std::vector<Rot<D>> a_moment;     // per particle: Σ of their moments on it
  void resize(std::size_t contacts, std::size_t wall_contacts, std::size_t particles) {
    f.assign(contacts, Vec<D>::Zero());
    mb.assign(contacts, Rot<D>::Zero());
    live.assign(contacts, 0);
    wall_moment.assign(wall_contacts, Rot<D>::Zero());
    a_force.assign(particles, Vec<D>::Zero());
    a_moment.assign(particles, Rot<D>::Zero());
  }
  void clear() { resize(f.size(), wall_moment.size(), a_force.size()); }
  void mark_all_live() { std::fill(live.begin(), live.end(), std::uint8_t{1}); }
  std::size_t bytes() const {
    return f.capacity() * sizeof(Vec<D>) + mb.capacity() * sizeof(Rot<D>) + live.capacity() +
           wall_moment.capacity() * sizeof(Rot<D>) + a_force.capacity() * sizeof(Vec<D>) +
           a_moment.capacity() * sizeof(Rot<D>);
  }
};

// Where one contact set writes: ball contacts' slots from `ball`, wall contacts' from `wall`, and their moments on the
// walls from `wall_moment`.
struct SlotOffsets {
  std::size_t ball = 0, wall = 0, wall_moment = 0;
};

// Stiffness of each slot for the timestep estimate: translational, and rotational about B's centre; and per particle
// the sums over its contacts as A (as the force pass sums forces). The estimate runs between force passes and borrows
// the slots' own numbers for them, so it costs no memory per contact; World::refresh_timestep says when they are
// given back.
template <int D>
struct SlotStiffness {
  Slots<D>& s;
  double& kt(std::size_t slot) { return s.f[slot][0]; }
  double& krb(std::size_t slot) { return s.mb[slot][0]; }
  double& a_kt(int i) { return s.a_force[i][0]; }
  double& a_kr(int i) { return s.a_force[i][1]; }
};

}  // namespace mc
