// Heterogeneity of the particles (Tang §8.1.2): each particle's springs carry a stiffness factor f drawn per
// phase (Weibull 8.4 or truncated normal). Two balls in series then give k_n = 2tE_c f_A f_B/(f_A + f_B) in 2D
// and 4E_c (R_A f_A)(R_B f_B)/(R_A f_A + R_B f_B) in 3D, and the factors drawn over a lattice have the
// distribution's mean and variance.
#include <doctest/doctest.h>

#include <cmath>

#include "scene/build_world.hpp"
#include "scene/scene.hpp"
#include "scene/toml_reader.hpp"
#include "tests/common/relative.hpp"
#include "tests/common/test_worlds.hpp"

using namespace mc;

namespace {

// Two particles pressed by `overlap`, held; the force of the first force pass against k_n·overlap.
template <int D>
void series_springs() {
  LinearParams p;
  p.modulus = 10e9;
  auto w = test::single_model_world<D, Linear>(p);
  const double ra = 1e-3, rb = 1.5e-3, overlap = 1e-7;
  Vec<D> b = Vec<D>::Zero();
  b[0] = ra + rb - overlap;
  w.particles.add(Vec<D>::Zero(), ra, 2600, 0);
  w.particles.add(b, rb, 2600, 0);
  w.particles.fix.assign(2, 0xff);
  w.particles.stiffness = {0.5, 2.0};
  w.init();
  w.step();
  const double fa = 0.5, fb = 2.0;
  const double kn =
      D == 2 ? 2 * p.modulus * fa * fb / (fa + fb) : 4 * p.modulus * (ra * fa) * (rb * fb) / (ra * fa + rb * fb);
  // Overlap 1e-7 m out of coordinates ~ 1e-3 m: round-off ~ 1e-9 relative.
  CHECK(w.contact_force(0, 0)[0] == mc::test::relative(kn * overlap, 1e-6));
}

}  // namespace

TEST_CASE("particle_stiffness_factors_combine_as_springs_in_series_2d") { series_springs<2>(); }
TEST_CASE("particle_stiffness_factors_combine_as_springs_in_series_3d") { series_springs<3>(); }

TEST_CASE("particle_stiffness_factors_drawn_per_phase_have_the_weibull_moments_of_tang_8_4") {
  const std::string text =
      "dimension = 2\nseed = 4\n[[phases]]\nname = \"mortar\"\ndensity = \"2200 kg/m3\"\nstiffness_weibull_shape = 6\n"
      "[[phases]]\nname = \"aggregate\"\ndensity = \"2700 kg/m3\"\n"
      "[[contacts]]\nphase_a = \"mortar\"\nmodel = \"linear\"\nmodulus = \"20 GPa\"\n"
      "[[contacts]]\nphase_a = \"aggregate\"\nmodel = \"linear\"\nmodulus = \"40 GPa\"\n"
      "[[contacts]]\nphase_a = \"mortar\"\nphase_b = \"aggregate\"\nmodel = \"linear\"\nmodulus = \"15 GPa\"\n"
      "[specimen]\nkind = \"lattice\"\nlo = [0, 0]\nhi = [\"40 mm\", \"40 mm\"]\nradius = \"0.3 mm\"\nphase = "
      "\"mortar\"\n"
      "[mesostructure]\nfraction = 0.3\ngrading = \"ranges\"\nmortar_phase = \"mortar\"\naggregate_phase = "
      "\"aggregate\"\n"
      "[[mesostructure.ranges]]\nlo = \"4 mm\"\nhi = \"8 mm\"\nshare = 1\n[run]\nsteps = 1\n";
  const Scene s = read_scene(TomlDoc::parse_text(text, "h.toml"), "h.toml");
  SpecimenInfo info;
  const World<2> w = build_world<2>(s, info);
  std::vector<double> mortar;
  for (int i = 0; i < w.particles.size(); ++i) {
    if (w.particles.phase[i] == 1)
      CHECK(w.particles.stiffness[i] == 1.0);  // the aggregate declares none
    else
      mortar.push_back(w.particles.stiffness[i]);
  }
  REQUIRE(mortar.size() > 2000);
  const double k = 6, g1 = std::tgamma(1 + 1 / k), g2 = std::tgamma(1 + 2 / k);  // Weibull, scale 1
  test::check_sample_moments(mortar, g1, g2 - g1 * g1, "mortar stiffness factors");
}
