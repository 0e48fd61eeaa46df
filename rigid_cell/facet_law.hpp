// The facet's constitutive law of the rigid-cell model (Květoň §3.2.2 and §3.2.4, after Cusatis & Cedolin 2007):
// elastic s = E₀ diag(1, α, α) e (3.6) with isotropic damage s = (1 − D) E₀ diag(1, α, α) e (3.11), the damage
// found in the equivalent space (3.12)-(3.14) from the straining direction ω (3.15), the elastic limit f_eq(ω)
// (3.16), the exponential softening or hardening of slope K(ω) (3.17)-(3.19) scaled by the crack band (3.20) so
// that a facet dissipates G_t per unit area in pure tension whatever its length L.
#pragma once
#include <Eigen/Core>
#include <sstream>

#include "engine/errors.hpp"
#include "engine/keys.hpp"

namespace mc::rigid_cell {

// Its keys, units, ranges and defaults: facet_law_keys() below (inline: every build reads rigid-cell scenes, also one
// without the family, which then refuses to run them).
struct FacetParams {
  double E0 = 0;                // normal modulus E₀ [Pa]
  double alpha = 0;             // tangential-to-normal stiffness ratio α [-]
  double tensile_strength = 0;  // f_t [Pa]; 0: elastic
  double fracture_energy = 0;   // in tension, G_t [N/m]
  // The rate dependence of (8.16)-(8.17): F = 1 + c₁ asinh(ė/c₀) scales the elastic limit; c₁ = 0: none.
  double rate_c0 = 0;  // c₀ [1/s] (Tab. 8.1)
  double rate_c1 = 0;  // c₁ [-]
};

// Where a contact facet's law is evaluated (Květoň §3.3): at its centroid (simple), or at the centroids of its parts
// (discretized; facet_discretization.hpp).
enum class FacetIntegration : int { Simple, Discretized };

// The keys of a [[contacts]] entry with model = "facet_damage" (beside the contacts table's model and phases): E₀ and
// α, or the macroscopic E and ν they follow from by (3.8); f_t and G_t; the rate dependence (8.16)-(8.17).
inline const KeyTable& facet_law_keys() {
  using P = FacetParams;
  static const KeyTable t = key_table<P>(
      "facet_damage", "[[contacts]] model = \"facet_damage\" (rigid-cell scenes)",
      "The rigid-cell model's facet law (Květoň §3.2, after Cusatis & Cedolin 2007): elastic s = E₀ diag(1, α, α) e "
      "(3.6) with isotropic damage (3.11) found in the equivalent space (3.12)-(3.14) from the straining direction "
      "(3.15), the elastic limit f_eq(ω) (3.16), exponential softening (3.17)-(3.19) scaled by the crack band (3.20) "
      "so that a facet dissipates G_t per unit area in pure tension whatever its length.",
      {
          bound(&P::E0, {.name = "E0",
                        .unit = Unit::Pressure,
                        .range = Range::positive(),
                        .need = Need::Required,
                        .when = "with alpha",
                        .doc = "the facets' normal modulus E₀ (3.6)",
                        .example = "60 GPa"}),
          bound(&P::alpha, {.name = "alpha",
                           .range = Range::positive(),
                           .need = Need::Required,
                           .when = "with E0",
                           .doc = "the tangential-to-normal stiffness ratio α (3.6)",
                           .example = "0.29"}),
          {.name = "modulus",
           .unit = Unit::Pressure,
           .range = Range::positive(),
           .need = Need::Required,
           .when = "instead of E0, with poisson_ratio",
           .doc = "the macroscopic E, from which E₀ and α follow by (3.8) (2D: plane stress, the same average)"},
          {.name = "poisson_ratio",
           .range = Range{-1.0, 0.5, true, true},
           .need = Need::Required,
           .when = "with modulus",
           .doc = "the macroscopic ν: below 1/4 in 3D, 1/3 in 2D"},
          bound(&P::tensile_strength, {.name = "tensile_strength",
                                      .unit = Unit::Pressure,
                                      .range = Range::non_negative(),
                                      .doc = "f_t of the elastic limit (3.16); 0: elastic facets",
                                      .example = "3 MPa"}),
          bound(&P::fracture_energy, {.name = "fracture_energy",
                                     .unit = Unit::EnergyPerArea,
                                     .range = Range::positive(),
                                     .need = Need::Required,
                                     .when = "with tensile_strength > 0",
                                     .doc = "G_t, in tension, per unit facet area (3.20)",
                                     .example = "80 N/m"}),
          bound(&P::rate_c1, {.name = "rate_c1",
                             .range = Range::positive(),
                             .need = Need::Required,
                             .when = "with rate_c0, on damaging facets",
                             .doc = "c₁ of the rate dependence F = 1 + c₁ asinh(ė/c₀) of the elastic limit (8.17)"}),
          bound(&P::rate_c0, {.name = "rate_c0",
                             .unit = Unit::Rate,
                             .range = Range::positive(),
                             .need = Need::Required,
                             .when = "with rate_c1",
                             .doc = "c₀, a strain rate (Tab. 8.1)"}),
      },
      {{.keys = {"E0", "modulus"},
        .one_required = true,
        .why = "the facets' normal modulus E0 with alpha, or the macroscopic modulus with poisson_ratio (Květoň "
               "(3.8)), one pair"}});
  return t;
}

// Květoň (8.17) after Cusatis (2011): the increase F of the elastic limit at the facet's equivalent strain rate
// [1/s]. The thesis writes it of the crack-opening rate ẇ but gives c₀ in s⁻¹ (Tab. 8.1): the rate of the facet's
// strain, its opening rate over its length.
double rate_increase(const FacetParams& p, double strain_rate);

// The macroscopic elastic constants of a tessellation with these E₀ and α, and the other way round: Květoň (3.8)
// in 3D; in 2D (plane stress, unit thickness) by the same uniform-strain average, E = 2E₀(1 + α)/(3 + α),
// ν = (1 − α)/(3 + α).
struct Elastic {
  double E, nu;
};
// (Inline: the calibration, above the family's library, reads them in a build without it.)
inline Elastic macroscopic(int dimension, double E0, double alpha) {
  if (dimension == 2) return {2 * E0 * (1 + alpha) / (3 + alpha), (1 - alpha) / (3 + alpha)};
  return {E0 * (2 + 3 * alpha) / (4 + alpha), (1 - alpha) / (4 + alpha)};
}

// E₀ and α from E and ν; throws InputError when ν leaves (−1, 1/4) in 3D or (−1, 1/3) in 2D.
inline FacetParams mesoscopic(int dimension, double E, double nu) {
  const double top = dimension == 2 ? 1.0 / 3.0 : 0.25;
  if (!(nu > -1 && nu < top)) {
    std::ostringstream m;
    m << "a rigid-cell model in " << dimension << "D cannot have Poisson's ratio " << nu << ": allowed (-1, "
      << (dimension == 2 ? "1/3" : "1/4") << ") (Kveton (3.8))";
    throw InputError(m.str());
  }
  FacetParams p;
  if (dimension == 2) {  // inverse of macroscopic() in 2D
    p.alpha = (1 - 3 * nu) / (1 + nu);
    p.E0 = E * (3 + p.alpha) / (2 * (1 + p.alpha));
  } else {  // (3.8)
    p.E0 = E / (1 - 2 * nu);
    p.alpha = (1 - 4 * nu) / (1 + nu);
  }
  return p;
}


// What a facet carries between converged steps: the largest damage reached, D_max (irreversibility, (3.17)).
struct FacetState {
  double D_max = 0;
};

// The straining direction ω at which softening turns into hardening: where the tensile-shear hyperbola of (3.16)
// meets the compressive circle, at s_N = −11.67 f_t, s_T = 10.95 f_t: tan ω₀ = √α s_N/s_T.
double omega_0(double alpha);

// The elastic limit f_eq(ω) in equivalent stress, (3.16).
double elastic_limit(double omega, const FacetParams& p);

// The initial slopes of softening in tension and shear, (3.20), for a facet of length L. Throws InputError when L
// is so long that the law snaps back (2 E₀ G_t ≤ f_t² L, or 32 α E₀ G_t ≤ 9 f_t² L in shear).
struct Slopes {
  double Kt, Ks;
};
Slopes crack_band_slopes(const FacetParams& p, double L);

// The straining direction (3.15): tan ω = e_N/(√α e_T), so that e_N = e_eq sin ω and √α e_T = e_eq cos ω (Cusatis &
// Cedolin 2007; the thesis prints α for √α, which would not parametrise (3.12)).
//
// The damage for local strain e = (e_N, e_M[, e_L]) of a facet of length L, given the damage reached before:
// (3.12)-(3.19), with the elastic limit raised by F at the equivalent strain rate (8.16). Never below D_max.
double damage(const Eigen::Vector3d& e, const FacetParams& p, double L, const FacetState& s, double strain_rate = 0);

// The facet's equivalent strain rate √(ė_N² + α ė_T²) as (3.12), from its strain rate ė (the strain of the cells'
// velocities): the relative speed of its two cells (Květoň §8.4: "the difference in velocities of particles it
// connects") over its length.
double strain_rate(const Eigen::Vector3d& e_rate, const FacetParams& p);

}  // namespace mc::rigid_cell
