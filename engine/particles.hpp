// Particle state as contiguous arrays (structure of arrays): the force loop and the law of motion stream
// through each field, and a particle's index is its identity for the whole run.
#pragma once
#include <cstdint>
#include <vector>

#include "engine/dim.hpp"

namespace mc {

// Per-degree-of-freedom fixity: bit k (k < D) holds translation k, bit D+k holds rotation k.
// A fixed degree of freedom keeps its current velocity (PFC "fix").
using FixMask = std::uint8_t;
// Every degree of freedom of a particle in d dimensions: d translations and 1 (2D) or 3 (3D) rotations.
constexpr FixMask fix_all(int d) { return static_cast<FixMask>((1u << (d + (d == 2 ? 1 : 3))) - 1); }

template <int D>
struct Particles {
  using R = Rot<D>;
  std::vector<Vec<D>> x, v, f;                // position [m], velocity at t−Δt/2 [m/s], resultant force [N]
  std::vector<R> w;                           // angular velocity [rad/s]
  std::vector<double> radius, mass, inertia;  // [m], [kg], [kg m²]
  std::vector<int> phase;
  std::vector<double> stiffness;  // factor on the particle's own springs (heterogeneity, Tang §8.1.2); 1
  std::vector<FixMask> fix;
  std::vector<Vec<D>> f_applied;  // declared external loads (empty unless the scene applies any)
  std::vector<R> m_applied;
  // A specimen split across processes (World::split): 1 for a ghost, another process's particle held here for the
  // contacts of this one's; empty when the world is whole.
  std::vector<std::uint8_t> ghost;

  int size() const { return static_cast<int>(x.size()); }
  bool is_ghost(int i) const { return !ghost.empty() && ghost[i]; }

  // Asks the memory for what a contact reads of particle i (position, velocity, spin, radius, stiffness factor)
  // some time before it is read: a partner far along the numbering misses the caches in each of these arrays.
  void prefetch_contact_fields(int i) const {
    __builtin_prefetch(&x[i]);
    __builtin_prefetch(&v[i]);
    __builtin_prefetch(&w[i]);
    __builtin_prefetch(&radius[i]);
    __builtin_prefetch(&stiffness[i]);
  }

  // density in kg/m³; in 2D the disc has unit thickness, so mass = ρ π R² · 1 m.
  int add(const Vec<D>& pos, double r, double density, int ph) {
    x.push_back(pos);
    v.push_back(Vec<D>::Zero());
    f.push_back(Vec<D>::Zero());
    w.push_back(R::Zero());
    radius.push_back(r);
    mass.push_back(0.0);
    inertia.push_back(0.0);
    phase.push_back(ph);
    stiffness.push_back(1.0);
    fix.push_back(0);
    set_density(size() - 1, density);
    return size() - 1;
  }

  // Particle i's mass and moment of inertia for its radius and a density [kg/m³] (a new phase or radius).
  void set_density(int i, double density) {
    mass[i] = density * Dim<D>::volume(radius[i]);
    inertia[i] = Dim<D>::inertia_factor * mass[i] * radius[i] * radius[i];
  }

  double max_radius() const {
    double r = 0;
    for (double ri : radius) r = std::max(r, ri);
    return r;
  }
};

}  // namespace mc
