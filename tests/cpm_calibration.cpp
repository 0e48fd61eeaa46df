// The CPM calibration helpers (Šmilauer, "Parameter calibration"): the microplane relations between k_T/k_N and
// ν and E/k_N (25), and the interpolation of a sampled parameter/property dependence (steps 3–4).
#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "contact_models/cpm_calibration.hpp"
#include "tests/common/relative.hpp"

using namespace mc::cpm_calibration;

TEST_CASE("cpm calibration: nu from kT/kN and back, and E/kN from (25)") {
  // ν = (1 − k_T/k_N)/(4 + k_T/k_N): k_T = k_N gives 0, k_T = 0 gives 1/4, the recommended 0.2 gives 0.8/4.2.
  CHECK(poisson_from_kt_kn(1.0) == 0.0);
  CHECK(poisson_from_kt_kn(0.0) == 0.25);
  CHECK(poisson_from_kt_kn(0.2) == mc::test::relative(0.8 / 4.2, 1e-15));
  for (double r : {0.0, 0.1, 0.2, 0.5, 1.0})
    CHECK(kt_kn_from_poisson(poisson_from_kt_kn(r)) == doctest::Approx(r).epsilon(1e-14).scale(1));
  // (25) at k_T/k_N = 1 is Σ A L/(3V) (the (2 + 3)/(4 + 1) factor is 1); at 0.2, Σ A L/(3V) · 2.6/4.2.
  CHECK(modulus_ratio(3.0, 1.0, 1.0) == mc::test::relative(1.0, 1e-15));
  CHECK(modulus_ratio(1.2, 2.0, 0.2) == mc::test::relative(0.2 * 2.6 / 4.2, 1e-15));
}

TEST_CASE("cpm calibration: radial scaling and the interpolated epsf/eps0 and tan(phi) steps") {
  // E ∝ k_N: a run with k_N = 30 GPa that gave E = 24 GPa asks for 37.5 GPa to reach 30 GPa.
  CHECK(scale_to_target(30e9, 24e9, 30e9) == mc::test::relative(37.5e9, 1e-15));
  CHECK(characteristic_length(30e9, 100.0, 3e6) == mc::test::relative(30e9 * 100 / 9e12, 1e-15));
  // A monotone sampled dependence (decreasing is allowed too): the interpolated parameter reproduces a linear
  // dependence exactly, and a target outside the samples is refused with the sampled range named.
  const std::vector<double> ductility = {5, 10, 20, 40}, length = {0.5, 1.0, 2.0, 4.0};  // ∝: length = ductility/10
  CHECK(parameter_for(ductility, length, 3.0, "relative_ductility") == mc::test::relative(30.0, 1e-14));
  const std::vector<double> tan_phi = {0.2, 0.5, 0.8}, ratio = {12.0, 9.0, 6.0};
  CHECK(parameter_for(tan_phi, ratio, 10.0, "tan_phi") == mc::test::relative(0.4, 1e-14));
  CHECK_THROWS_WITH_AS(parameter_for(tan_phi, ratio, 20.0, "tan_phi"), doctest::Contains("outside the sampled"),
                       std::invalid_argument);
  CHECK_THROWS_AS(parameter_for({1.0}, {1.0}, 1.0, "x"), std::invalid_argument);
}
