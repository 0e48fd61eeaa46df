// Small worlds built in code for the physics tests (the scene files are tested separately).
#pragma once
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <vector>

#include "contact_models/hertz_mindlin.hpp"
#include "contact_models/linear.hpp"
#include "engine/random_stream.hpp"  // RandomStream: deterministic numbers for the test packings
#include "engine/world.hpp"

namespace mc::test {

// A world whose single phase 0 interacts through one model; the domain is wide open; contact forces are kept.
template <int D, class Model>
World<D> single_model_world(const typename Model::Params& params) {
  World<D> w;
  w.sets.push_back(std::make_unique<ContactSet<Model, D>>(params));
  w.model_of = {{0}};
  w.domain_lo = Vec<D>::Constant(-1e3);
  w.domain_hi = Vec<D>::Constant(1e3);
  w.keep_contact_forces();  // the tests read single contacts' forces
  return w;
}

// Two particles bonded by `Model` on the x axis: A (radius ra) at the origin, B (radius rb) overlapping it by
// `overlap` (negative: a gap, within the 1 % bonding tolerance). Every degree of freedom is held, so the test
// prescribes the motion; energy is traced. The single bond is installed.
template <int D, class Model>
World<D> held_bonded_pair(const typename Model::Params& p, double ra, double rb, double overlap) {
  auto w = single_model_world<D, Model>(p);
  Vec<D> b = Vec<D>::Zero();
  b[0] = ra + rb - overlap;
  w.particles.add(Vec<D>::Zero(), ra, 2600, 0);
  w.particles.add(b, rb, 2600, 0);
  w.particles.fix.assign(2, 0xff);
  w.timestep.safety = 0.5;
  w.trace_energy = true;
  w.init();
  if (w.install_bonds(0.01, 3) != 1) throw std::logic_error("held_bonded_pair: the pair was not bonded");
  return w;
}

// The energy balance counts from here: what the world holds now. Velocities prescribed after init() are not
// yet in the engine's kinetic energy (½ m v(t−Δt/2)·v(t+Δt/2) of the last step), so it is taken here.
template <int D>
void start_energy(World<D>& w) {
  w.update_energy();
  double kinetic = 0;
  for (int i = 0; i < w.particles.size(); ++i) kinetic += 0.5 * w.particles.mass[i] * w.particles.v[i].squaredNorm();
  w.energy.initial = kinetic + w.energy.strain;
}

// Parameters of a bond glued at the contact point (contact or softening bond) for the two-particle tests:
// E_c = 1 GPa, k_n/k_s = 2, μ = 0.3, the given normal and shear strengths [N].
template <class Params>
Params glued_bond_params(double normal, double shear) {
  Params p;
  p.contact.modulus = 1e9;
  p.contact.kn_ks_ratio = 2.0;
  p.contact.friction = 0.3;
  p.bond_normal_strength.mean = normal;
  p.bond_shear_strength.mean = shear;
  return p;
}

// A sample drawn from a distribution of the given mean and variance: its mean within 4 standard errors σ/√n,
// its variance within 4 of its own, σ²√(2/n) (normal-like tails).
inline void check_sample_moments(const std::vector<double>& s, double mean, double variance, const char* what) {
  const double n = static_cast<double>(s.size());
  double m = 0, v = 0;
  for (double x : s) m += x;
  m /= n;
  for (double x : s) v += (x - m) * (x - m);
  v /= n - 1;
  MESSAGE(s.size(), " ", what, ": mean ", m, " (expected ", mean, "), variance ", v, " (expected ", variance, ")");
  CHECK(std::abs(m - mean) < 4 * std::sqrt(variance / n));
  CHECK(std::abs(v - variance) < 4 * variance * std::sqrt(2 / n));
}

// Six infinite walls bounding the cube [lo, hi]³, normals inwards.
inline void add_box_walls(World<3>& w, double lo, double hi, const WallMaterial& wm) {
  for (int d = 0; d < 3; ++d) {
    const Vec<3> e = Vec<3>::Unit(d);
    w.walls.push_back(Wall<3>::plane(lo * e, e));
    w.walls.push_back(Wall<3>::plane(hi * e, -e));
    w.walls[w.walls.size() - 2].material = wm;
    w.walls.back().material = wm;
  }
}

}  // namespace mc::test
