// `mesocrack calibrate` on the rigid-cell family (studies/calibration_rigid_cell.cpp), through the real command line
// on scenes/rigid_cell_calibration_tension_2d.toml (a 20 × 40 mm prism of about 200 cells, a second a full run): from
// a concrete's class by the fib Model Code 2010, the calibrated scene, run again, must give the targets within the
// tolerance asked for (5 %): it is the same deterministic run as the procedure's last, so a calibration that stopped
// short of its targets, or wrote other values than it ran, fails here. Bad targets are refused with exit 2.
#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include "tests/common/cli_harness.hpp"

namespace {

const fs::path kScene = kScenes / "rigid_cell_calibration_tension_2d.toml";

std::vector<double> history(const fs::path& file, const std::string& name) {
  return mc::H5File(file.string(), mc::H5File::Mode::ReadOnly).read_doubles("/history/" + name);
}

}  // namespace

TEST_CASE("rigid_cell_calibration_to_a_model_code_class_gives_its_e_nu_ft_and_gf_in_the_calibrated_scene") {
  const TempDir d;
  const Result cal = mesocrack({"calibrate", kScene.string(), "--target", "class=C30/37", "-o", "c.toml",
                                "--threads", "1"}, d.dir);
  REQUIRE_MESSAGE(cal.code == 0, cal.describe());
  CHECK(contains(cal.err, "fits E = E_ci, nu, ft = f_ctm, Gf = G_F"));
  CHECK(contains(slurp(d / "c.toml"), "calibrated at l_min = 2 mm"));
  // C30/37: E_ci 33.55 GPa, ν 0.2, f_ctm 2.896 MPa, G_F = 73 × 38^0.18 = 140.5 N/m; 2D: per metre of thickness,
  // the section 20 mm wide.
  const double E = 33.55e9, nu = 0.2, ft = 0.3 * std::pow(30.0, 2.0 / 3.0) * 1e6, gf = 73 * std::pow(38.0, 0.18);
  const double tolerance = 0.05 * (1 + 1e-9);  // calibrate's default, on each target
  const Result full = mesocrack({"run", "c.toml", "-o", "full.h5", "--threads", "1"}, d.dir);
  REQUIRE_MESSAGE(full.code == 0, full.describe());
  const std::vector<double> sigma = history(d / "full.h5", "section.y_20mm");
  const double peak = *std::max_element(sigma.begin(), sigma.end());
  CHECK(std::abs(peak / ft - 1) <= tolerance);
  CHECK(std::abs(history(d / "full.h5", "energy.dissipated").back() / 0.02 / gf - 1) <= tolerance);
  CHECK(std::abs(sigma.back()) <= 0.011 * peak);  // the scene's post-peak stop at 1 %
  // The softening curve is not fitted (only its peak and the energy under it are): after the peak σ(w)/f_t follows
  // Hordijk's (1991) curve (1 + (c₁w/w_c)³) e^(−c₂w/w_c) − (w/w_c)(1 + c₁³) e^(−c₂), c₁ = 3, c₂ = 6.93, w_c = 5.136
  // G_F/f_t, for the f_t and G_F it reads. w is the plate's travel less the elastic stretch σL/E of the 38 mm between
  // the plates' cells. Measured: an RMS difference of 0.028 f_t over the 400 post-peak steps, at most 0.078 f_t (the
  // prism softens a little later just after the peak, a little sooner at w_c/2); bounds 0.05 and 0.12. The energy
  // under the curve is G_F less what the facets dissipated before the peak (1 %): within 5 %.
  {
    const std::vector<double> travel = history(d / "full.h5", "group.top.disp_y");
    const auto k = static_cast<std::size_t>(std::max_element(sigma.begin(), sigma.end()) - sigma.begin());
    const double g = history(d / "full.h5", "energy.dissipated").back() / 0.02, wc = 5.136 * g / peak;
    auto opening = [&](std::size_t i) { return travel[i] - sigma[i] * 0.038 / E - (travel[k] - peak * 0.038 / E); };
    double sum = 0, most = 0, energy = 0;
    for (std::size_t i = k; i < sigma.size(); ++i) {
      const double r = opening(i) / wc;
      const double h = r < 1 ? (1 + std::pow(3 * r, 3)) * std::exp(-6.93 * r) - r * 28 * std::exp(-6.93) : 0.0;
      const double diff = sigma[i] / peak - h;
      sum += diff * diff, most = std::max(most, std::abs(diff));
      if (i > k) energy += 0.5 * (sigma[i] + sigma[i - 1]) * (opening(i) - opening(i - 1));
    }
    CHECK(std::sqrt(sum / static_cast<double>(sigma.size() - k)) < 0.05);
    CHECK(most < 0.12);
    CHECK(std::abs(energy / gf - 1) <= tolerance);
  }
  // The elastic constants as the procedure reads them: facets too strong to damage (f_t × 1e3, G_t × 1e6), three
  // load steps, σ over the axial strain and the lateral strain over it in the middle half.
  const std::string text = slurp(d / "c.toml");
  auto value_of = [&](const std::string& key) {
    const auto at = text.find("\n" + key + " = ");
    REQUIRE(at != std::string::npos);
    const std::string rest = text.substr(at + key.size() + 4);
    return std::stod(rest.substr(rest[0] == '"' ? 1 : 0));  // "2658168.372 Pa": SI with its unit
  };
  const double f_t = value_of("tensile_strength"), g_t = value_of("fracture_energy");
  const Result el = mesocrack({"run", "c.toml", "-o", "el.h5", "--set", "run.steps=3", "--set",
                               "contacts[0].tensile_strength=" + std::to_string(f_t * 1e3), "--set",
                               "contacts[0].fracture_energy=" + std::to_string(g_t * 1e6)}, d.dir);
  REQUIRE_MESSAGE(el.code == 0, el.describe());
  const double eyy = history(d / "el.h5", "strain.yy").back();
  CHECK(std::abs(history(d / "el.h5", "section.y_20mm").back() / eyy / E - 1) <= tolerance);
  CHECK(std::abs(-history(d / "el.h5", "strain.xx").back() / eyy / nu - 1) <= tolerance);
}

TEST_CASE("rigid_cell_calibration_refuses_targets_the_family_cannot_fit_naming_them") {
  const TempDir d;
  const std::vector<std::tuple<std::vector<std::string>, std::string>> bad = {
      {{"--target", "E=30GPa,nu=0.4"}, "nu"},  // 2D: ν < 1/3 (Květoň (3.8), α > 0)
      {{"--target", "nu=0.5"}, "nu"},
      {{"--target", "ft=3MPa,Gf=-1N/m"}, "Gf"},
      {{"--target", "ucs=40MPa"}, "--target ucs"},
      {{"--target", "E=30GPa,fc=40MPa"}, "--target fc"},
      {{"--target", "ft=3MPa,Gf=100N/m", "--set", "run.stop[0].post_peak_fraction=0.3"}, "post_peak_fraction"}};
  for (const auto& [args, named] : bad) {
    std::vector<std::string> a = {"calibrate", kScene.string(), "-o", "c.toml"};
    a.insert(a.end(), args.begin(), args.end());
    const Result r = mesocrack(a, d.dir);
    CHECK_MESSAGE(r.code == 2, args[1], ": ", r.describe());
    CHECK_MESSAGE(contains(r.err, named), args[1], ": ", r.err);
    CHECK(!fs::exists(d / "c.toml"));
    CHECK(!fs::exists(d / "c_it1.h5"));
  }
  // Facets that start elastic (no tensile strength, no fracture energy) have no strength to scale.
  std::string elastic = slurp(kScene);
  for (const std::string line : {"tensile_strength = \"2.9 MPa\"\n", "fracture_energy = \"140.5 N/m\"\n"}) {
    REQUIRE(elastic.find(line) != std::string::npos);
    elastic.erase(elastic.find(line), line.size());
  }
  write_file(d / "elastic.toml", elastic);
  const Result e = mesocrack({"calibrate", "elastic.toml", "--target", "ft=3MPa", "-o", "c.toml"}, d.dir);
  CHECK_MESSAGE(e.code == 2, e.describe());
  CHECK_MESSAGE(contains(e.err, "the facets are elastic"), e.err);
  // A rigid-cell scene that is no direct tension test (no section, no strain box).
  const Result r = mesocrack({"calibrate", (kScenes / "rigid_cell_tension_2d.toml").string(), "--target",
                              "E=30GPa", "-o", "c.toml"}, d.dir);
  CHECK_MESSAGE(r.code == 2, r.describe());
  CHECK_MESSAGE(contains(r.err, "direct tension test"), r.err);
}
