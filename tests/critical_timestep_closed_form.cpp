// The critical timestep the engine estimates (Tang 3.22–3.23: per particle √(m/Σk) and √(I/Σk_rot)) against the
// true limit of central differences, Δt_c = 2/ω_max, of systems whose ω_max is known in closed form:
//  - two touching particles: the normal mode ω² = 2k_n/m, and the shear mode, in which the shear spring at the
//    contact point works through both translations and both rotations, ω² = 2k_s(1/m + r²/I);
//  - a chain of touching particles (a one-dimensional lattice): ω_max from the eigenvalues of its stiffness matrix,
//    assembled here contact by contact from the same two springs, and bounded by the infinite chain's closed form:
//    ω²(q) = 4k_n sin²(q/2)/m along it, 4k_s (sin²(q/2)/m + r² cos²(q/2)/I) across it (translations and
//    rotations of wavenumber q), whose largest values are 4k_n/m and 4k_s r²/I (all turning alike, as r²/I > 1/m).
// The estimate must be below the true limit (else the run is unstable) and not far below it (else the run is
// needlessly slow). Tang's estimate sums a particle's normal and shear springs for every translation and all its
// contacts at once, so it is conservative: 0.60–0.87 of Δt_c in these systems. Below Δt_c and above half of it
// is asserted; the estimate itself must be Tang (3.22)–(3.23) evaluated by hand.
#include <doctest/doctest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "contact_models/linear.hpp"
#include "tests/common/relative.hpp"
#include "tests/common/test_worlds.hpp"

using namespace mc;

namespace {

constexpr double kRadius = 1e-3, kDensity = 2600, kModulus = 30e9;

template <int D>
World<D> chain(int n, double kn_ks_ratio) {
  LinearParams p;
  p.modulus = kModulus;
  p.kn_ks_ratio = kn_ks_ratio;
  auto w = test::single_model_world<D, Linear>(p);
  for (int i = 0; i < n; ++i) {
    Vec<D> x = Vec<D>::Zero();
    x[0] = 2 * kRadius * i;  // touching: the springs are in the lists, at zero force
    w.particles.add(x, kRadius, kDensity, 0);
  }
  w.init();
  return w;
}

// The stiffness of one contact of the chain (two equal balls in series, Tang 3.25 and 3.38).
template <int D>
Linear::Coeffs springs(double kn_ks_ratio) {
  LinearParams p;
  p.modulus = kModulus;
  p.kn_ks_ratio = kn_ks_ratio;
  return Linear::pair<D>(p, kRadius, kRadius);
}

// The true critical timestep of a chain of n particles: the largest ω² of K x = ω² M x, K assembled from each
// contact's normal spring (along the chain) and shear spring (across it, at the contact point, lever r on both
// sides: its stretch is u_b − r θ_b − u_a − r θ_a), for the in-plane degrees of freedom (x, y, θ_z). In 3D the
// out-of-plane ones repeat the in-plane shear and rotation modes, and the twist about the chain carries no spring.
template <int D>
double true_critical_timestep(int n, double kn_ks_ratio, double m, double inertia) {
  const Linear::Coeffs c = springs<D>(kn_ks_ratio);
  const int dofs = 3 * n;  // per particle: x, y, θ
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(dofs, dofs), mass = Eigen::MatrixXd::Zero(dofs, dofs);
  for (int i = 0; i < n; ++i) mass(3 * i, 3 * i) = mass(3 * i + 1, 3 * i + 1) = m, mass(3 * i + 2, 3 * i + 2) = inertia;
  for (int i = 0; i + 1 < n; ++i) {
    const int a = 3 * i, b = 3 * (i + 1);
    Eigen::VectorXd normal = Eigen::VectorXd::Zero(dofs), shear = Eigen::VectorXd::Zero(dofs);
    normal(b) = 1, normal(a) = -1;                                                          // x_b − x_a
    shear(b + 1) = 1, shear(b + 2) = -kRadius, shear(a + 1) = -1, shear(a + 2) = -kRadius;  // the stretch above
    k += c.kn * normal * normal.transpose() + c.ks * shear * shear.transpose();
  }
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(k, mass, Eigen::EigenvaluesOnly);
  return 2.0 / std::sqrt(solver.eigenvalues().maxCoeff());
}

template <int D>
void two_particles(double kn_ks_ratio) {
  const World<D> w = chain<D>(2, kn_ks_ratio);
  const Linear::Coeffs c = springs<D>(kn_ks_ratio);
  const double m = w.particles.mass[0], inertia = w.particles.inertia[0];
  const double normal = 2.0 / std::sqrt(2 * c.kn / m);
  const double shear = 2.0 / std::sqrt(2 * c.ks * (1 / m + kRadius * kRadius / inertia));
  const double exact = std::min(normal, shear);
  // The same limit from the eigenvalues: the assembly below is checked against the two-particle closed form.
  CHECK(true_critical_timestep<D>(2, kn_ks_ratio, m, inertia) == mc::test::relative(exact, 1e-10));
  // Tang (3.22)–(3.23) for either particle: one contact.
  const double tang = std::min(std::sqrt(m / (c.kn + c.ks)), std::sqrt(inertia / (c.ks * kRadius * kRadius)));
  MESSAGE(D, "D, k_n/k_s = ", kn_ks_ratio, ": estimate ", w.dt_critical, " s, exact ", exact, " s (normal ", normal,
          ", shear ", shear, "), ratio ", w.dt_critical / exact);
  CHECK(w.dt_critical == mc::test::relative(tang, 1e-12));
  CHECK(w.dt_critical < exact);
  CHECK(w.dt_critical > 0.5 * exact);
}

template <int D>
void lattice_chain(int n, double kn_ks_ratio) {
  const World<D> w = chain<D>(n, kn_ks_ratio);
  const Linear::Coeffs c = springs<D>(kn_ks_ratio);
  const double m = w.particles.mass[0], inertia = w.particles.inertia[0];
  const double exact = true_critical_timestep<D>(n, kn_ks_ratio, m, inertia);
  const double infinite =
      std::min(2.0 / std::sqrt(4 * c.kn / m), 2.0 / std::sqrt(4 * c.ks * kRadius * kRadius / inertia));
  // An interior particle has two contacts: Tang (3.22)–(3.23) with twice the springs.
  const double tang = std::min(std::sqrt(m / (2 * (c.kn + c.ks))), std::sqrt(inertia / (2 * c.ks * kRadius * kRadius)));
  MESSAGE(D, "D chain of ", n, ", k_n/k_s = ", kn_ks_ratio, ": estimate ", w.dt_critical, " s, exact ", exact,
          " s (infinite chain ", infinite, " s), ratio ", w.dt_critical / exact);
  CHECK(exact >= infinite * (1 - 1e-12));  // a finite chain is no stiffer than the infinite one ...
  CHECK(exact < 1.01 * infinite);          // ... and at 20 particles within 1 % of it
  CHECK(w.dt_critical == mc::test::relative(tang, 1e-12));
  CHECK(w.dt_critical < exact);
  CHECK(w.dt_critical > 0.5 * exact);
}

}  // namespace

TEST_CASE("critical_timestep_of_two_particles_against_their_normal_and_shear_modes") {
  for (const double ratio : {1.0, 2.5}) {
    two_particles<2>(ratio);
    two_particles<3>(ratio);
  }
}

TEST_CASE("critical_timestep_of_a_particle_chain_against_its_largest_eigenfrequency") {
  for (const double ratio : {1.0, 2.5}) {
    lattice_chain<2>(20, ratio);
    lattice_chain<3>(20, ratio);
  }
}
