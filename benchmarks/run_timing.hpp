// What the throughput benchmark measures of a run: the stepping loop's wall and CPU time with the contact and
// list counts around it (best of repeated fresh runs), the process's peak resident set, the engine's container
// bytes, and the number formats of its tables.
#pragma once
#include <time.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "engine/world.hpp"

namespace mc::bench {

using Clock = std::chrono::steady_clock;

// ---------------------------------------------------------------------------------------------------------
// Memory: peak resident set from the kernel, and the engine's own containers.

inline long status_kib(const char* key) {
  std::ifstream f("/proc/self/status");
  std::string line;
  const std::string k = std::string(key) + ":";
  while (std::getline(f, line))
    if (line.rfind(k, 0) == 0) return std::strtol(line.c_str() + k.size(), nullptr, 10);
  return -1;
}

// Writing 5 to clear_refs resets VmHWM to the current resident set (Linux >= 4.0).
inline bool reset_peak_rss() {
  std::ofstream f("/proc/self/clear_refs");
  f << "5";
  f.flush();
  return f.good();
}

template <class T>
inline std::size_t bytes(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}

struct Footprint {
  std::size_t particles = 0, contacts = 0, slots = 0, gather = 0;
  std::size_t total() const { return particles + contacts + slots + gather; }
};

// From the container sizes: particle arrays (+ the positions kept at the last rebuild), the contact set's pairs
// and histories, the slots (per far pair and wall contact its force, moment on B and live byte; per particle its
// sums; the pairs' kept forces, when a scene measures single contacts), the gather lists (the timestep estimate
// borrows the slots: no memory of its own).
template <int D>
Footprint footprint(const World<D>& w) {
  Footprint fp;
  const auto& p = w.particles;
  fp.particles = bytes(p.x) + bytes(p.v) + bytes(p.f) + bytes(p.w) + bytes(p.radius) + bytes(p.mass) +
                 bytes(p.inertia) + bytes(p.phase) + bytes(p.stiffness) + bytes(p.fix) + bytes(p.f_applied) +
                 bytes(p.m_applied) + p.x.size() * sizeof(Vec<D>);
  for (const auto& s : w.sets) fp.contacts += s->memory_bytes();
  fp.slots = w.slot_bytes();
  fp.gather = w.gather_bytes();
  return fp;
}

// Bytes one step moves through memory, counted from the arrays it streams (read once, written once when it
// changes them): per contact its pair and state read, and its history written back (a split state's properties
// are only read: engine/state_columns.hpp); per far pair and wall contact its slot (force, moment on B, live byte)
// written and read back by the gather; per particle its sums zeroed, added to and read by the gather, its gather
// list, the state the law of motion reads and writes, and the partners' positions, velocities, spins and radii the
// contacts read; and the timestep estimate's share of the steps between estimates. Caches only make the real
// traffic smaller; this is what a machine without them would move.
template <int D>
double streamed_bytes_per_step(const World<D>& w) {
  const double n = w.particles.size();
  double contacts = 0, read_only = 0;
  for (const auto& s : w.sets) {
    contacts += static_cast<double>(s->memory_bytes() + s->rewritten_bytes());
    read_only += static_cast<double>(s->memory_bytes() - s->rewritten_bytes());
  }
  const double slots = static_cast<double>(w.slot_count());
  const double vec = sizeof(Vec<D>), rot = sizeof(Rot<D>);
  const double slot_traffic = 2 * slots * (vec + rot + 1) + 4 * n * (vec + rot);
  const double gather = static_cast<double>(w.gather_bytes());
  // Law of motion: reads x, v, w, mass, inertia, fix, x at rebuild; writes x, v, w, f.
  const double motion = n * (2 * 3 * vec + 2 * vec + 2 * sizeof(double) + sizeof(FixMask) + vec);
  // The contacts' reads of the particles: position, velocity, spin, radius, stiffness factor.
  const double partners = n * (2 * vec + rot + 2 * sizeof(double));
  // The timestep estimate, once every `every` steps (World::critical_timestep): the pairs and a split state's
  // properties read once (what it reads of a whole state, as the CPM's, is not counted), the
  // partners' positions, radii and stiffness factors, two stiffnesses per slot written and read back and its live
  // byte set, two sums per particle zeroed, added to and read, the gather lists, masses and inertias.
  const double d = sizeof(double);
  const double estimate = read_only + n * (vec + 2 * d) + slots * (2 * 2 * d + 1) + n * 3 * 2 * d + gather + n * 2 * d;
  const int every = w.timestep.every;
  return contacts + slot_traffic + gather + motion + partners + (every > 0 ? estimate / every : 0.0);
}

inline double cpu_now() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

inline std::string loadavg() {
  std::ifstream f("/proc/loadavg");
  double a = 0, b = 0, c = 0;
  f >> a >> b >> c;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.2f / %.2f / %.2f", a, b, c);
  return buf;
}

struct Timing {
  double seconds = kInf;   // stepping loop only
  double cpu_seconds = 0;  // CPU time of the process in that loop (all threads)
  int n = 0, steps = 0;
  double contacts = 0;         // touching ball–ball pairs, mean of the window's start and end
  double candidates = 0;       // pairs in the neighbour lists at the end
  double wall_candidates = 0;  // ball–wall pairs in the lists at the end
  std::int64_t rebuilds = 0;   // neighbour-list rebuilds inside the timed window
  double dt = 0, dt_critical = 0;
  Footprint fp;
  double streamed = 0;  // bytes a step streams per particle (streamed_bytes_per_step)

  double particle_steps() const { return double(n) * steps / seconds; }
  double contact_steps() const { return contacts * steps / seconds; }
  double ns_per_particle_step() const { return seconds / (double(n) * steps) * 1e9; }
  double cpu_share() const { return cpu_seconds / seconds; }  // ≈ threads when nothing else competes
  double bytes_per_second() const { return streamed * particle_steps(); }
  // CPU/wall for a table cell, flagged when the process got less than 80 % of the cores it asked for.
  std::string share(int threads) const {
    char b[48];
    std::snprintf(b, sizeof b, "%.2f%s", cpu_share(), cpu_share() < 0.8 * threads ? " (contended)" : "");
    return b;
  }
  void keep_best(const Timing& t) {
    if (t.seconds < seconds) *this = t;
  }
};

template <int D>
Timing time_steps(World<D>& w, int warmup, int steps) {
  for (int s = 0; s < warmup; ++s) w.step();
  Timing t;
  t.n = w.particles.size();
  t.steps = steps;
  const double c0 = static_cast<double>(w.contact_count());
  const std::int64_t rb0 = w.rebuilds;
  const double c0cpu = cpu_now();
  const auto t0 = Clock::now();
  for (int s = 0; s < steps; ++s) w.step();
  const auto t1 = Clock::now();
  t.cpu_seconds = cpu_now() - c0cpu;
  t.seconds = std::chrono::duration<double>(t1 - t0).count();
  t.contacts = 0.5 * (c0 + static_cast<double>(w.contact_count()));
  t.candidates = static_cast<double>(w.candidate_count());
  for (const auto& set : w.sets) t.wall_candidates += static_cast<double>(set->wall_pairs().size());
  t.rebuilds = w.rebuilds - rb0;
  t.dt = w.dt;
  t.dt_critical = w.dt_critical;
  t.fp = footprint(w);
  t.streamed = streamed_bytes_per_step(w) / t.n;
  return t;
}

// ---------------------------------------------------------------------------------------------------------
// Formatting

inline std::string sci(double v, int digits = 3) {
  if (!std::isfinite(v)) return "–";
  char b[64];
  std::snprintf(b, sizeof b, "%.*g", digits, v);
  return b;
}
inline std::string fix(double v, int decimals) {
  if (!std::isfinite(v)) return "–";
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", decimals, v);
  return b;
}

}  // namespace mc::bench
