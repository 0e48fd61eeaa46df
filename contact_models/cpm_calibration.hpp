// Calibration of the Concrete Particle Model (Šmilauer, "Parameter calibration"): the elastic relations of the
// microplane analogy, and the steps that bring a simulated specimen onto target properties. Elastic first
// (k_N, k_T/k_N from E, ν), then inelastic (ε_f/ε_0 from k_N G_f/f_t², tan φ from f_c/f_t, ε_0 from f_t).
#pragma once
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace mc::cpm_calibration {

// ν = (1 − k_T/k_N)/(4 + k_T/k_N), microplane analogy (Šmilauer, "Geometry and elastic parameters").
inline double poisson_from_kt_kn(double kt_kn) { return (1.0 - kt_kn) / (4.0 + kt_kn); }
// Its inverse: k_T/k_N = (1 − 4ν)/(1 + ν); ν ∈ (−1, 1/4] gives k_T/k_N ≥ 0.
inline double kt_kn_from_poisson(double nu) { return (1.0 - 4.0 * nu) / (1.0 + nu); }

// Šmilauer (25): E/k_N = Σ A_i L_i/(3V) · (2 + 3 k_T/k_N)/(4 + k_T/k_N), A_i, L_i the contacts' cross-sections
// and lengths in the volume V. The second factor alone tells how a new k_T/k_N moves E at fixed k_N.
inline double modulus_shape(double kt_kn) { return (2.0 + 3.0 * kt_kn) / (4.0 + kt_kn); }
inline double modulus_ratio(double sum_area_length, double volume, double kt_kn) {
  return sum_area_length / (3.0 * volume) * modulus_shape(kt_kn);
}

// Radial scaling: E is proportional to k_N at fixed k_T/k_N and R_I, so a run that gave E with k_N asks for
// k_N E*/E. Likewise f_t = k_N ε_0 Ψ(ε_f/ε_0, c_T0/(k_T ε_0), φ): at fixed dimensionless parameters (c_T0 scaled
// with ε_0) the run's f_t becomes f_t* with ε_0 f_t*/f_t.
inline double scale_to_target(double value, double measured, double target) { return value * target / measured; }

// The dimensionless properties of the inelastic calibration: the characteristic length k_N G_f/f_t² [m] and
// the strength ratio f_c/f_t.
inline double characteristic_length(double kn, double fracture_energy, double ft) {
  return kn * fracture_energy / (ft * ft);
}

// Steps 3 and 4 of the procedure: from runs that sampled a property against one parameter (ε_f/ε_0 against
// k_N G_f/f_t², then tan φ against f_c/f_t), the parameter that gives the target property, by linear
// interpolation between the two samples that bracket it (the dependences of Fig. 22 are monotone). Throws,
// naming the sampled range, when the target lies outside it: extrapolating a calibration curve is guessing.
inline double parameter_for(const std::vector<double>& parameter, const std::vector<double>& property, double target,
                            const std::string& what) {
  if (parameter.size() != property.size() || parameter.size() < 2)
    throw std::invalid_argument(what + ": need at least two (parameter, property) samples of equal count");
  for (std::size_t k = 1; k < property.size(); ++k) {
    const double a = property[k - 1], b = property[k];
    if ((a <= target && target <= b) || (b <= target && target <= a)) {
      if (a == b) return parameter[k - 1];
      return parameter[k - 1] + (target - a) / (b - a) * (parameter[k] - parameter[k - 1]);
    }
  }
  throw std::invalid_argument(what + ": target " + std::to_string(target) + " lies outside the sampled properties (" +
                              std::to_string(property.front()) + " … " + std::to_string(property.back()) +
                              "); sample a wider parameter range");
}

}  // namespace mc::cpm_calibration
