// Every number of a rigid-cell, a bending and a pull-test scene set, one at a time, to 0, −1, 10³⁰⁰ and 10⁻³⁰⁰
// and the scene run for two steps: each run ends with a documented exit (0 done, 2 bad input, 3 file, 4 unstable,
// 5 not converged), never 1 (an internal error) or a signal. The scene reader's own fuzzer (scene_fuzzer.cpp) reads
// mutants without building them; here each is built and stepped.
#include <map>
#include <regex>
#include <set>

#include "tests/common/cli_harness.hpp"

namespace {

// The numbers a scene gives, as --set paths: "specimen.l_min", "contacts[0].E0" (arrays of numbers left out).
std::vector<std::string> numeric_keys(const std::string& text) {
  static const std::regex table(R"(^\[([A-Za-z_.]+)\]\s*(#.*)?$)"), array_table(R"(^\[\[([A-Za-z_.]+)\]\]\s*(#.*)?$)");
  static const std::regex key(R"(^([A-Za-z_0-9]+)\s*=\s*("?[-+0-9.][^\[]*)$)");
  std::vector<std::string> keys;
  std::map<std::string, int> count;
  std::string prefix;
  std::istringstream in(text);
  std::smatch m;
  for (std::string line; std::getline(in, line);) {
    if (std::regex_match(line, m, array_table)) {
      prefix = m[1].str() + "[" + std::to_string(count[m[1].str()]++) + "].";
    } else if (std::regex_match(line, m, table)) {
      prefix = m[1].str() + ".";
    } else if (std::regex_match(line, m, key)) {
      const std::string path = prefix + m[1].str();
      if (prefix != "run." && prefix != "output." && path != "seed" && path != "dimension") keys.push_back(path);
    }
  }
  return keys;
}

}  // namespace

TEST_CASE("every_number_of_rigid_cell_bending_and_pull_scenes_at_extremes_ends_with_a_documented_exit") {
  const TempDir d;
  std::vector<std::string> scenes = {"bending_small_2d.toml", "pull_elastic_2d.toml"};
  if (MESOCRACK_RIGID_CELL_BUILT)  // a disc of cells between plates; one fibre across a pre-cracked facet
    scenes.insert(scenes.end(), {"brazilian_2d.toml", "fibre_pullout_two_sided_3d.toml"});
  const std::set<int> documented = {0, 2, 3, 4, 5};
  for (const std::string& name : scenes) {
    const std::vector<std::string> keys = numeric_keys(slurp(kScenes / name));
    REQUIRE_MESSAGE(keys.size() >= 10, name, ": the scene's numbers were not found");
    std::map<int, int> exits;
    for (const std::string& k : keys)
      for (const std::string value : {"0", "-1", "1e300", "1e-300"}) {
        const Result r = mesocrack({"run", (kScenes / name).string(), "-o", "x.h5", "--set", k + "=" + value, "--set",
                                    "run.steps=2", "--threads", "1"},
                                   d.dir);
        ++exits[r.code];
        CHECK_MESSAGE(documented.count(r.code), name, " ", k, "=", value, ": ", r.describe());
        fs::remove(d / "x.h5");
      }
    std::string seen;
    for (const auto& [code, n] : exits) seen += " exit " + std::to_string(code) + ": " + std::to_string(n) + ";";
    MESSAGE(name, ": ", keys.size(), " numbers × 4 values,", seen);
  }
}
