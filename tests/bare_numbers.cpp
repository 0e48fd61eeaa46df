// A number written without a unit is SI, and read as such; when it lies more than 100 times outside the usual
// values of its key (or of its kind) it is more likely a unit left out than meant, and the command says so on stderr
// (a warning, exit 0): the CMOD rate 10 of a bending scene is 10 m/s, 1 000 times the scene's 10 mm/s, and a
// density 2.4 is 2.4 kg/m3. A unit written, or a bare number within the usual values, draws no warning, and no
// shipped scene draws one.
#include "scene/scene.hpp"
#include "scene/toml_reader.hpp"
#include "tests/common/cli_harness.hpp"

namespace {

Result bending_with(const TempDir& d, const std::vector<std::string>& sets) {
  std::vector<std::string> args{"run", (kScenes / "bending_small_2d.toml").string(), "-o", "b.h5", "--threads", "1",
                                "--set", "run.steps=2"};
  for (const auto& s : sets) args.insert(args.end(), {"--set", s});
  return mesocrack(args, d.dir);
}

}  // namespace

TEST_CASE("a_number_without_a_unit_far_from_its_usual_values_is_read_as_si_with_a_warning") {
  const TempDir d;
  const Result rate = bending_with(d, {"walls[2].rate=10"});
  CHECK_MESSAGE(rate.code == 0, rate.describe());
  CHECK_MESSAGE(contains(rate.err, "warning: "), rate.err);
  CHECK_MESSAGE(contains(rate.err, "key 'walls[2].rate' (from --set) = 10"), rate.err);
  CHECK_MESSAGE(contains(rate.err, "read as 10 m/s (SI), more than 100 times the usual values 1e-09 to 0.05 m/s"),
                rate.err);
  CHECK_MESSAGE(contains(rate.err, "\"10 mm/s\""), rate.err);
  const Result density = bending_with(d, {"phases[0].density=2.4"});
  CHECK_MESSAGE(density.code == 0, density.describe());
  CHECK_MESSAGE(contains(density.err, "less than 1/100 of the usual values 300 to 20000 kg/m3"), density.err);
  CHECK_MESSAGE(contains(density.err, "\"2.4 g/cm3\""), density.err);
  // The same values with their units, and a bare rate within the usual ones (5 mm/s as 0.005): no warning.
  for (const auto& set : {"walls[2].rate=10 mm/s", "phases[0].density=2.4 g/cm3", "walls[2].rate=0.005"}) {
    const Result quiet = bending_with(d, {set});
    CHECK_MESSAGE(quiet.code == 0, quiet.describe());
    const bool warned = contains(quiet.err, "warning");
    CHECK_MESSAGE(!warned, set, ": ", quiet.err);
  }
}

TEST_CASE("no_shipped_scene_has_a_number_without_a_unit_far_from_its_usual_values") {
  for (const auto& e : fs::directory_iterator(kScenes)) {
    if (e.path().extension() != ".toml") continue;
    CAPTURE(e.path().string());
    const mc::Scene s = mc::read_scene(mc::TomlDoc::load(e.path().string()), e.path().string());
    const std::string first = s.warnings.empty() ? "" : s.warnings.front();
    CHECK_MESSAGE(first.empty(), first);
  }
}
