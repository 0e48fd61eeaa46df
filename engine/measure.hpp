// Measurements inside a circle (2D) or sphere (3D), as PFC's measurement circles (Tang 2013 §3.4): porosity,
// average stress, coordination number and the best-fit strain rate. Stress and strain are tension positive.
// Every sum is exact (engine/exact_sum.hpp) over the particles a process owns, then shared: a measurement does not
// depend on the thread count, nor on how a split world is divided (its processes measure together).
// A region holding no particle centre gives NaN: "nothing measured" must not read as a zero stress or strain.
// Stress and coordination read the contact forces of the last step, so they need an initialised world.
#pragma once
#include "engine/world.hpp"

namespace mc {

template <int D>
using Tensor = Eigen::Matrix<double, D, D>;

template <int D>
struct Region {
  Vec<D> centre = Vec<D>::Zero();
  double radius = 0;
  bool contains(const Vec<D>& x) const { return (x - centre).squaredNorm() <= radius * radius; }
  double volume() const { return Dim<D>::volume(radius); }  // 2D: per unit thickness
};

// Exact volume (2D: area per unit thickness) of the part of a ball of radius r, its centre at distance d from
// the centre of a region of radius R, that lies inside the region (the lens).
template <int D>
double lens_volume(double R, double r, double d);

// n = 1 − Σ (each particle's part inside the region) / V_region. Overlaps between particles count twice.
template <int D>
double porosity(const World<D>& world, const Region<D>& region);

// Tang (3.63) over the particles whose centre lies in the region, with the force on each particle at each of
// its contacts (ball–ball and ball–wall). Returned as summed: its antisymmetric part is Σ (x^c − x^p) × F^c,
// which at rest balances the moments the contacts carry themselves (bond bending), zero without them.
template <int D>
Tensor<D> average_stress(const World<D>& world, const Region<D>& region);

template <int D>
Tensor<D> symmetric_part(const Tensor<D>& a) {
  return 0.5 * (a + a.transpose());
}

// Mean number of contacts carrying a force (ball–ball and ball–wall, as PFC counts them) per particle whose
// centre lies in the region. A contact is counted from the slot force being nonzero, so a bond carrying
// exactly zero force is not counted.
template <int D>
double coordination_number(const World<D>& world, const Region<D>& region);

// Least-squares velocity gradient α̇_ij = ∂v_i/∂x_j, Tang (3.68)–(3.73), from the velocities and positions of
// the particles whose centre lies in the region; the strain rate is its symmetric part (3.67). NaN when fewer
// than D + 1 particles, or all of them on a line (plane), leave the fit undetermined.
template <int D>
Tensor<D> best_fit_velocity_gradient(const World<D>& world, const Region<D>& region);

// Strain of a region, integrated in time: the runner calls update() after every step. The velocities are those
// the step just used to move the particles (t + Δt/2), so sym(α̇)·Δt is that step's strain increment.
template <int D>
struct StrainIntegrator {
  Region<D> region;
  Tensor<D> strain = Tensor<D>::Zero();
  void update(const World<D>& world) {
    strain += symmetric_part<D>(best_fit_velocity_gradient(world, region)) * world.dt;
  }
};

}  // namespace mc
