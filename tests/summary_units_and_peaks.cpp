// A summary says what each of its numbers is measured in, and whether a peak it reports is one. The analyses of the
// shipped uniaxial, bending and pull-test scenes read a load that rises linearly to a top and falls to 40 % of it
// (a peak: a strength, a capacity), and the same load cut at its top (a run that ended or was interrupted still
// rising): the first passes its peak, the second does not, both report the top exactly, and every number of every
// block has its unit in the block's "units" member.
#include "scene/analyses/uniaxial.hpp"
#include "scene/scene.hpp"
#include "scene/toml_reader.hpp"
#include "tests/common/cli_harness.hpp"
#include "tests/common/relative.hpp"

namespace {

constexpr int kRise = 50;    // rows up to the top
constexpr double kTop = 7;   // the load's (or stress's) largest value, in its history's unit

// `rows` rows of a load rising linearly to kTop at row kRise, then falling linearly to 0.4 kTop at row 2 kRise.
std::vector<double> load_rows(int rows) {
  std::vector<double> y;
  for (int k = 0; k < rows; ++k)
    y.push_back(k <= kRise ? kTop * k / kRise : kTop * (1 - 0.6 * (k - kRise) / kRise));
  return y;
}

// The histories an analysis reads, each `rows` long: `loads` carry the load, the others (displacements, strains,
// slips, crack counts) grow linearly with the row.
mc::Histories histories(const std::vector<std::string>& loads, const std::vector<std::string>& others, int rows) {
  mc::Histories h;
  for (const auto& n : loads) h[n] = load_rows(rows);
  for (const auto& n : others) {
    auto& y = h[n];
    for (int k = 0; k < rows; ++k) y.push_back(1e-6 * k);
  }
  return h;
}

// Every number of a block (and of its nested blocks but the energy, crack counts, crack path and strain profiles,
// whose definitions say their units) has a unit.
void check_every_number_has_a_unit(const Json& block) {
  REQUIRE(block.has("units"));
  const Json& units = block["units"];
  for (const auto& [name, value] : block.members) {
    if (value.kind != Json::Kind::Number) continue;
    CAPTURE(name);
    REQUIRE(units.has(name));
    CHECK(!units[name].text.empty());
  }
}

void check_peak(const std::string& scene_name, const std::vector<std::string>& loads,
                const std::vector<std::string>& others, const std::string& top_key, double top) {
  CAPTURE(scene_name);
  const std::string file = (kScenes / scene_name).string();
  const mc::Scene scene = mc::read_scene(mc::TomlDoc::load(file), file);
  REQUIRE(scene.analyses.size() == 1);
  for (const int rows : {2 * kRise + 1, kRise + 1}) {
    CAPTURE(rows);
    const mc::Histories h = histories(loads, others, rows);
    const std::vector<mc::LoggedCrack> no_cracks;
    const Json block = parse_json(scene.analyses[0]->summary_json(mc::RunRecord{h, no_cracks}));
    CHECK(block["peak_passed"].boolean == (rows > kRise + 1));
    // The top is a row of the record: read exactly (the analysis may scale it, e.g. by the beam's thickness).
    CHECK(block[top_key].number == mc::test::relative(top, 1e-12));
    check_every_number_has_a_unit(block);
  }
}

}  // namespace

TEST_CASE("summary_marks_a_peak_only_where_the_load_fell_after_it_and_gives_every_number_its_unit") {
  {
    const std::string file = (kScenes / "uniaxial_2d.toml").string();
    const mc::Scene s = mc::read_scene(mc::TomlDoc::load(file), file);
    const auto* u = s.analysis<mc::UniaxialAnalysis>();
    REQUIRE(u);
    std::vector<std::string> others{u->axial_strain, "uniaxial.inside_strain", "cracks.tensile", "cracks.shear",
                                    "time"};
    others.insert(others.end(), u->lateral_strain.begin(), u->lateral_strain.end());
    check_peak("uniaxial_2d.toml", {u->stress}, others, "ucs", kTop);
  }
  {
    const std::string file = (kScenes / "bending_small_2d.toml").string();
    const mc::Scene s = mc::read_scene(mc::TomlDoc::load(file), file);
    const Json thickness = parse_json(s.analyses[0]->summary_json(mc::RunRecord{
        histories({"bending.load"}, {"bending.cmod", "bending.deflection", "time"}, 2 * kRise + 1), {}}))["thickness"];
    // 2D: the simulated load is the 1 m slice's; peak_load is for the beam's thickness.
    check_peak("bending_small_2d.toml", {"bending.load"}, {"bending.cmod", "bending.deflection", "time"},
               "peak_load", kTop * thickness.number);
  }
  check_peak("pull_elastic_2d.toml", {"pullout.load"}, {"pullout.slip", "time"}, "capacity_simulated", kTop);
}
