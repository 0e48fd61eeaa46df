// How [uniaxial] reads a test: the plane-strain reading of 2D ratios against its closed form, the three windows
// for E (secant 25–50 %, secant 0–50 %, tangent at 50 %) against a parabola's exact values, and the axial strain
// inside the specimen against the supports' where the deformation is affine.
#include <cmath>

#include "scene/analyses/uniaxial.hpp"
#include "tests/common/cli_harness.hpp"
#include "tests/common/relative.hpp"

namespace {

// A uniaxial compression history: σ(ε) rising to its peak at ε_p and falling after it, the lateral strain
// ν₂ ε, no cracks. Rows every 1e-3 ε_p.
mc::Histories curve(double (*stress)(double), double nu2, double eps_peak) {
  mc::Histories h;
  for (int k = 0; k <= 1500; ++k) {
    const double eps = 1e-3 * k * eps_peak;
    h["s"].push_back(stress(eps));
    h["ea"].push_back(eps);
    h["el"].push_back(nu2 * eps);
    h["cracks.tensile"].push_back(0);
    h["cracks.shear"].push_back(0);
  }
  return h;
}

mc::UniaxialAnalysis analysis(int dimension, bool plane_strain) {
  mc::UniaxialAnalysis u;
  u.stress = "s", u.axial_strain = "ea", u.lateral_strain = {"el"};
  u.dimension = dimension, u.plane_strain = plane_strain;
  return u;
}

constexpr double kE2 = 30e9, kNu2 = 0.25, kPeak = 1e-3;
// Linear to the peak at ε = 1e-3, then down at the same slope.
double linear(double e) { return e <= kPeak ? kE2 * e : kE2 * (2 * kPeak - e); }
// σ = E₀ ε (1 − ε / 2ε_p): tangent E₀(1 − ε/ε_p), peak E₀ ε_p / 2.
double parabola(double e) { return kE2 * e * (1 - e / (2 * kPeak)); }

}  // namespace

TEST_CASE("plane strain reading of a 2D assembly: nu = nu2/(1+nu2), E = E2 (1 - nu^2)") {
  const auto h = curve(linear, kNu2, kPeak);
  const mc::UniaxialResult strain = analysis(2, true).result(h);
  const double nu = kNu2 / (1 + kNu2);  // 0.2
  // Linear rows, interpolated exactly: only rounding remains (1e-9).
  CHECK(strain.poisson == mc::test::relative(nu, 1e-9));
  CHECK(strain.modulus == mc::test::relative(kE2 * (1 - nu * nu), 1e-9));
  CHECK(strain.modulus_raw_2d == mc::test::relative(kE2, 1e-9));
  CHECK(strain.poisson_raw_2d == mc::test::relative(kNu2, 1e-9));
  const mc::UniaxialResult stress = analysis(2, false).result(h);
  CHECK(stress.modulus == mc::test::relative(kE2, 1e-9));
  CHECK(stress.poisson == mc::test::relative(kNu2, 1e-9));
  // 3D specimens give E and ν directly.
  const mc::UniaxialResult direct = analysis(3, true).result(h);
  CHECK(direct.modulus == mc::test::relative(kE2, 1e-9));
  CHECK(std::isnan(direct.modulus_raw_2d));
}

TEST_CASE("the three E windows of a parabolic curve match their closed forms") {
  // σ/σ_p = f at ε/ε_p = 1 − √(1 − f). Secant 25–50 %: 0.25 σ_p over the strain between those levels; secant
  // 0–50 %: 0.5 σ_p over the strain at 50 %; tangent at 50 %: the secant 45–55 %, which is 1.2e-3 below the
  // exact tangent E₀ √(1 − 0.5) on this curve (its curvature over the window).
  const auto h = curve(parabola, kNu2, kPeak);
  const mc::UniaxialResult r = analysis(3, true).result(h);
  const double sp = kE2 * kPeak / 2;
  auto at = [](double f) { return kPeak * (1 - std::sqrt(1 - f)); };
  // Rows every 1e-3 ε_p, linearly interpolated on a curve: 1e-5 relative.
  CHECK(r.modulus == mc::test::relative(0.25 * sp / (at(0.5) - at(0.25)), 1e-5));
  CHECK(r.modulus_secant_0_50 == mc::test::relative(0.5 * sp / at(0.5), 1e-5));
  CHECK(r.modulus_tangent_50 == mc::test::relative(0.1 * sp / (at(0.55) - at(0.45)), 1e-5));
  CHECK(r.modulus_tangent_50 == mc::test::relative(kE2 * std::sqrt(0.5), 1.5e-3));
  CHECK(r.ucs == mc::test::relative(sp, 1e-9));
}

TEST_CASE("inside axial strain equals the supports' strain in a bonded hexagonal lattice pulled with free sides") {
  // A hexagonal lattice is a Bravais lattice: under a homogeneous stress every particle is a centre of symmetry,
  // so it deforms affinely and the strain of its middle half is the strain between its ends. Supports that
  // hold only y (free sides, no end restraint) and a pull slow against the wave transit (40 mm at ~2900 m/s:
  // 14 µs, the run 1 ms) keep it homogeneous; what dynamics remain were measured at 0.04 %: 0.5 % bounds it.
  const TempDir d;
  const Result r = mesocrack({"run",   (kScenes / "lattice_tension_2d.toml").string(),
                              "-o",    "l.h5",
                              "--set", "specimen.radius=0.5 mm",
                              "--set", "contacts[0].bond_tensile_strength=1 GPa",
                              "--set", "contacts[0].bond_tensile_strength_std=0",
                              "--set", "contacts[0].bond_shear_strength=1 GPa",
                              "--set", "contacts[0].bond_shear_strength_std=0",
                              "--set", "groups[0].fix=y",
                              "--set", "groups[1].fix=y",
                              "--set", "run.duration=1 ms",
                              "--set", "uniaxial.loading=tension",
                              "--set", "uniaxial.supports=bottom top"},
                             d.dir);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  const mc::H5File f((d / "l.h5").string(), mc::H5File::Mode::ReadOnly);
  const auto supports = f.read_doubles("/history/uniaxial.strain");
  const auto inside = f.read_doubles("/history/uniaxial.inside_strain");
  REQUIRE(supports.size() == inside.size());
  REQUIRE(supports.back() > 4e-4);  // 20 mm/s for 1 ms over 40 mm: 5e-4
  for (std::size_t k = supports.size() / 4; k < supports.size(); ++k)
    CHECK(inside[k] == mc::test::relative(supports[k], 0.005));
}
