// One CPM contact between two held spheres, driven kinematically, for the single-contact tests: the strain
// history is prescribed and the stresses read back from the contact's force.
#pragma once
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "contact_models/cpm.hpp"
#include "tests/common/relative.hpp"
#include "tests/common/test_worlds.hpp"

namespace mc::test {

constexpr double kCpmR = 1e-3;  // both radii [m]

// The document's kind of concrete contact: k_N = 30 GPa, ε_0 = 1e-4, ε_f = 30 ε_0, c_T0 = 3 MPa, tan φ = 0.8,
// k_T/k_N = 0.2 and the recommended ε_s = −3e-3, K̃_s = 0.3, Y_0 = 0.1.
inline CpmParams cpm_params() {
  CpmParams p;
  p.modulus = 30e9;
  p.crack_onset_strain = 1e-4;
  p.relative_ductility = 30;
  p.cohesion = 3e6;
  p.tan_friction = 0.8;
  return p;
}

struct CpmPair {
  World<3> w;
  double length = 0, area = 0;                // L (centre distance at bonding), A = π r²
  std::vector<double> eps, sigma_n, sigma_t;  // per force pass: ε_N, σ_N (tension positive), |σ_T|

  Cpm::State<3> state() const { return static_cast<const ContactSet<Cpm, 3>&>(*w.sets[0]).state(0); }
  Vec<3> d() const { return w.particles.x[1] - w.particles.x[0]; }
  double strain() const { return (d().norm() - length) / length; }

  // One step with B moving at v: the force pass sees the positions before the move.
  void step(const Vec<3>& v) {
    w.particles.v[1] = v;
    const Vec<3> n = d().normalized();
    eps.push_back(strain());
    w.step();
    const Vec<3> f = w.contact_force(0, 0);  // on B
    sigma_n.push_back(-f.dot(n) / area);
    sigma_t.push_back((f - f.dot(n) * n).norm() / area);
  }
  // Normal strain changed by `de` per step for n steps (along the line of centres).
  void strain_by(double de, int n) {
    for (int k = 0; k < n; ++k) step(d().normalized() * (de * length / w.dt));
  }
  // To the normal strain `target` in steps of |de|.
  void strain_to(double target, double de) {
    const int n = static_cast<int>(std::ceil(std::abs(target - strain()) / de));
    if (n > 0) strain_by((target - strain()) / n, n);
  }
};

// Bonded across a gap of 0.1 r, inside R_I = 1.5: L = 2.1 r.
inline CpmPair cpm_pair(const CpmParams& p, double gap = 0.1 * kCpmR) {
  CpmPair c{held_bonded_pair<3, Cpm>(p, kCpmR, kCpmR, -gap)};
  c.length = 2 * kCpmR + gap;
  c.area = M_PI * kCpmR * kCpmR;
  REQUIRE(c.state().length == mc::test::relative(c.length, 1e-14));
  return c;
}

}  // namespace mc::test
