#include "rigid_cell/fibre_pullout.hpp"

#include <cmath>

namespace mc::rigid_cell {

namespace {
// π² E_f d_f³/2, the factor under the root of the debonding branch (5.1).
double debonding_stiffness(const FibreMaterial& f) {
  const double d = f.diameter;
  return 0.5 * M_PI * M_PI * f.modulus * d * d * d;
}
}  // namespace

double debonding_force(const FibreMaterial& f, double v) {
  return std::sqrt(debonding_stiffness(f) * (f.friction_stress * v + f.debonding_energy));
}

double full_debonding_slip(const FibreMaterial& f, double embedment) {
  const double ed = f.modulus * f.diameter, l2 = embedment * embedment;
  return 2.0 * f.friction_stress * l2 / ed + std::sqrt(8.0 * f.debonding_energy * l2 / ed);
}

double friction_force(const FibreMaterial& f, double embedment) {
  return M_PI * embedment * f.diameter * f.friction_stress;
}

double sliding_force(const FibreMaterial& f, double embedment, double v) {
  const double s = v - full_debonding_slip(f, embedment);
  const double left = 1.0 - s / embedment, hardening = 1.0 + f.slip_hardening * s / f.diameter;
  if (left <= 0 || hardening <= 0) return 0.0;
  return friction_force(f, embedment) * left * hardening;
}

double pullout_force(const FibreMaterial& f, double embedment, double v) {
  return v <= full_debonding_slip(f, embedment) ? debonding_force(f, v) : sliding_force(f, embedment, v);
}

double debonded_length(const FibreMaterial& f, double v) {
  const double g = f.debonding_energy;
  return std::sqrt(2.0 * f.modulus * f.diameter) * v / (2.0 * (std::sqrt(g + f.friction_stress * v) + std::sqrt(g)));
}

double pullout_work(const FibreMaterial& f, double embedment) {
  const double tau = f.friction_stress, g = f.debonding_energy, vd = full_debonding_slip(f, embedment);
  const double debonding =
      2.0 / 3.0 * std::sqrt(debonding_stiffness(f)) * (std::pow(tau * vd + g, 1.5) - std::pow(g, 1.5)) / tau;
  const double sliding =
      friction_force(f, embedment) * embedment * (0.5 + f.slip_hardening * embedment / (6.0 * f.diameter));
  return debonding + sliding;
}

double spalling_length(const FibreMaterial& f, double normal_force, double theta, double matrix_strength) {
  if (f.spalling_coefficient == 0) return 0.0;
  const double c = std::cos(0.5 * theta);
  return normal_force * std::sin(0.5 * theta) / (f.spalling_coefficient * matrix_strength * f.diameter * c * c);
}

double snubbing_factor(const FibreMaterial& f, double phi) { return std::exp(f.snubbing_coefficient * phi); }

double inclined_strength(const FibreMaterial& f, double phi) {
  return f.tensile_strength * std::exp(-f.rupture_coefficient * phi);
}

}  // namespace mc::rigid_cell
