// Rate dependence and confinement of one cohesive CPM contact. Visco-damage (Šmilauer 17–22): the damage strain
// lags behind ωε_N, the lag k_N (ωε_N − ε_d) is an overstress, so pulled faster the contact peaks higher; the
// Newton iteration of (22) finds the unique root from β = 0. Isotropic confinement σ_0: the strain σ_0 causes is
// added before the law and σ_0 taken off after it, so the response is the unconfined one shifted by it.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "contact_models/cpm.hpp"
#include "tests/common/cpm_pair.hpp"
#include "tests/common/relative.hpp"

using namespace mc;

TEST_CASE("cpm: the Newton iteration of (22) finds the negative root of ln(e^b + c e^(M b)) = 0") {
  // c over eleven decades and M on both sides of 1: the residual below the iteration's 1e-12, β < 0, and the
  // root is unique, so it also equals a bisection's to the same order.
  for (double c : {1e-4, 1e-2, 1.0, 1e2, 1e4, 1e7}) {
    for (double m : {0.1, 0.3, 1.0, 2.0}) {
      const double b = cpm_solve_beta(c, m);
      const double f = std::log(std::exp(b) + c * std::exp(m * b));
      double lo = -200, hi = 0;
      for (int k = 0; k < 200; ++k) {
        const double mid = 0.5 * (lo + hi);
        (std::log(std::exp(mid) + c * std::exp(m * mid)) > 0 ? hi : lo) = mid;
      }
      CHECK(std::abs(f) < 1e-12);
      CHECK(b < 0);
      CHECK(b == doctest::Approx(0.5 * (lo + hi)).epsilon(1e-9).scale(1));
    }
  }
}

namespace {

// Pulls a visco-damaging contact at a strain increment de per step to 5 ε_0; the peak stress over k_N ε_0.
double visco_peak(double de, double tau) {
  CpmParams p = test::cpm_params();
  p.damage_time = tau;
  p.damage_rate_exponent = 0.3;
  auto c = test::cpm_pair(p);
  c.strain_to(5 * p.crack_onset_strain, de);
  return *std::max_element(c.sigma_n.begin(), c.sigma_n.end()) / (p.modulus * p.crack_onset_strain);
}

}  // namespace

TEST_CASE("cpm: with visco-damage the tensile peak rises monotonically with the strain rate") {
  // The same time step, strain increments from 1e-8 to 1e-6 per step: rates over two decades. τ_d is chosen so
  // that (τ_d ε̇)^M_d spans the visible range at these rates (Fig. 17 uses τ_d = 1 s at quasi-static rates).
  const double tau = 1e-3;
  std::vector<double> peaks;
  for (double de : {1e-8, 3e-8, 1e-7, 3e-7, 1e-6}) peaks.push_back(visco_peak(de, tau));
  const double rate_independent = visco_peak(1e-7, 0.0);
  MESSAGE("peak / (k_N eps_0) at strain steps 1e-8 … 1e-6: ", peaks[0], " ", peaks[1], " ", peaks[2], " ", peaks[3],
          " ", peaks[4], "; without viscosity ", rate_independent);
  for (std::size_t k = 1; k < peaks.size(); ++k) CHECK(peaks[k] > peaks[k - 1]);
  // Slower, it tends to the rate-independent peak k_N ε_0 (from above); faster, it is markedly above.
  CHECK(rate_independent == mc::test::relative(1.0, 1e-3));
  CHECK(peaks.front() > 1.0);
  CHECK(peaks.back() > 1.1 * peaks.front());
}

TEST_CASE("cpm: confinement shifts the response by sigma_0 and its strain") {
  const CpmParams plain = test::cpm_params();
  const double e0 = plain.crack_onset_strain, kn = plain.modulus;
  // Elastic range (σ_0 > k_N ε_s): the curve σ'(ε) = σ(ε + σ_0/k_N) − σ_0, zero at zero strain, the tensile
  // peak at ε_0 − σ_0/k_N with k_N ε_0 − σ_0.
  CpmParams p = plain;
  p.confinement = -3e6;
  auto c = test::cpm_pair(p);
  c.strain_to(6 * e0, 2e-7);
  const double shift = p.confinement / kn;
  double dev = 0, kappa = 0;
  for (std::size_t k = 0; k < c.eps.size(); ++k) {
    // The unconfined law (15) at the shifted strain, κ its running maximum.
    const double e = c.eps[k] + shift;
    kappa = std::max(kappa, e);
    const double s = (e > 0 ? 1 - Cpm::damage(plain, kappa) : 1.0) * kn * e;
    dev = std::max(dev, std::abs(c.sigma_n[k] - (s - p.confinement)));
  }
  const auto ip = std::max_element(c.sigma_n.begin(), c.sigma_n.end()) - c.sigma_n.begin();
  MESSAGE("confined (-3 MPa): first stress ", c.sigma_n[0], " Pa, peak ", c.sigma_n[ip],
          " Pa at eps = ", c.eps[ip] / e0, " eps_0; max deviation ", dev, " Pa");
  CHECK(std::abs(c.sigma_n[0]) < 1e-9 * kn * e0);  // stress-free where it was made
  CHECK(dev < 1e-9 * kn * e0);
  CHECK(c.sigma_n[ip] == mc::test::relative(kn * e0 - p.confinement, 2e-3));
  CHECK(c.eps[ip] == mc::test::relative(e0 - shift, 2e-3));

  // Beyond k_N ε_s the confinement sits on the hardening branch: the contact starts there (stress-free after
  // σ_0 is taken off), compresses with K̃_s k_N and unloads (pulls) with k_N.
  CpmParams h = plain;
  h.confinement = -120e6;  // k_N ε_s = −90 MPa
  auto d = test::cpm_pair(h);
  d.strain_to(-1e-3, 1e-6);
  const std::size_t back = d.eps.size();
  d.strain_to(-0.5e-3, 1e-6);
  const double tangent = (d.sigma_n[back - 1] - d.sigma_n[back / 2]) / (d.eps[back - 1] - d.eps[back / 2]);
  const double unload = (d.sigma_n.back() - d.sigma_n[back + 10]) / (d.eps.back() - d.eps[back + 10]);
  MESSAGE("confined on the hardening branch (-120 MPa): first stress ", d.sigma_n[0],
          " Pa, tangent / k_N = ", tangent / kn, ", unloading / k_N = ", unload / kn);
  CHECK(std::abs(d.sigma_n[0]) < 1e-9 * std::abs(h.confinement));
  CHECK(tangent == mc::test::relative(h.hardening_modulus_ratio * kn, 1e-8));
  CHECK(unload == mc::test::relative(kn, 1e-8));
}
