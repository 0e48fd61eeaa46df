// Regular packings of equal particles, and the closed-form contact stiffnesses of a bonded hexagonal lattice
// (Tang 2013 §8.1.1). A hexagonal (2D) or face-centred cubic (3D) packing has every interior particle touching
// 6 / 12 neighbours at exactly 2R; bonded with a normal spring K^n and a shear spring K^s at every contact, the
// hexagonal lattice is an isotropic elastic plate whose E and ν follow from K^n and K^s in closed form.
#pragma once
#include "engine/dim.hpp"
#include "preprocess/random_box.hpp"  // Packing<D>: centres and radii

namespace mc {

// Discs of radius R on a hexagonal lattice inside [lo, hi] (each disc wholly inside, up to 1e-9 R of
// round-off): rows along x at spacing 2R, row spacing √3 R, every second row (rows 1, 3, …) offset by +R.
// The first row lies at y = lo.y + R, its first disc at x = lo.x + R. Ordered row by row from the bottom, each
// row from left to right. A rectangle (2N + 1) R wide holds N discs in every row. Throws InputError when R is
// not positive or the box holds no disc.
Packing<2> hexagonal_packing(const Vec<2>& lo, const Vec<2>& hi, double radius);

// Spheres of radius R on a face-centred cubic lattice inside [lo, hi] (each sphere wholly inside, up to 1e-9 R):
// the cubic cell a = 2√2 R has its edges along the axes, so the sites are lo + R + (a/2)(i, j, k) with i + j + k
// even, nearest neighbours at (a/2)√2 = 2R. Ordered by layer along z, then row along y, then along x. Throws
// InputError when R is not positive or the box holds no sphere.
Packing<3> fcc_packing(const Vec<3>& lo, const Vec<3>& hi, double radius);

// The springs of one contact of the hexagonal lattice, per unit thickness (t = 1 m) [N/m].
struct LatticeStiffness {
  double normal = 0;  // K^n
  double shear = 0;   // K^s
};

// The lattice's energy density gives Lamé λ = √3/4 (K^n − K^s), μ = √3/4 (K^n + K^s), so as a plate it has
// ν₂D = (K^n − K^s)/(3K^n + K^s) and E₂D = 4μ(λ + μ)/(λ + 2μ). Inverted for a target E [Pa] and ν:
//
// Plane strain, Tang (8.2): K^n = E/(√3(1+ν)(1−2ν)), K^s = E(1−4ν)/(√3(1+ν)(1−2ν)).
// K^s > 0 needs ν < 1/4: a lattice with positive springs has ν₂D < 1/3, i.e. ν = ν₂D/(1+ν₂D) < 1/4. ν ≥ 1/4
// would need no or a negative shear spring (unstable), so it is refused (InputError), as are ν ≤ −1 and E ≤ 0.
LatticeStiffness hex_lattice_stiffness_plane_strain(double young, double poisson);

// Plane stress, Tang (8.3): K^n = E/(√3(1−ν)), K^s = E(1−3ν)/(√3(1−ν²)).
// K^s > 0 needs ν < 1/3 (ν₂D = ν here); ν ≥ 1/3, ν ≤ −1 and E ≤ 0 are refused (InputError).
LatticeStiffness hex_lattice_stiffness_plane_stress(double young, double poisson);

}  // namespace mc
