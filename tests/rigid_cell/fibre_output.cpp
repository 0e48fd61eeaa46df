// What the output of a run with fibres holds of them (README, "Output": /specimen/fibres, /frames/fibre_*), read
// back from a real `mesocrack` run of the §6.3 prism on coarse cells: each fibre a straight polyline of its placed
// length through its crossings, the per-fibre states counted as the histories count them, no fibre carrying more
// than its strength, the XDMF grid of the fibres as large as its datasets, and `report` drawing them; a generated
// specimen's fibres at rest, and the run's closing line saying what the fibres cost it.
#include <Eigen/Core>

#include "tests/common/cli_harness.hpp"
#include "tests/common/xdmf_grids.hpp"

namespace {

using Point = Eigen::Vector3d;

Point row(const std::vector<double>& xs, std::int64_t k) { return {xs[3 * k], xs[3 * k + 1], xs[3 * k + 2]}; }

// The last frame's row of a frames table of one value per fibre.
std::vector<double> last_row(const mc::H5File& f, const std::string& ds) {
  std::vector<hsize_t> dims;
  const auto all = f.read_doubles(ds, &dims);
  REQUIRE(dims.size() == 2);
  return {all.end() - static_cast<std::ptrdiff_t>(dims[1]), all.end()};
}

}  // namespace

TEST_CASE("fibre_output_keeps_each_fibre_straight_through_its_crossings_and_its_state_as_the_histories_count_it") {
  const TempDir d;
  // l_min 5 mm instead of 2.5 mm (about 100 cells, seconds); 8 steps of 5 µm: the first cracks open at the second.
  const Result r = mesocrack({"run", (kScenes / "fibre_prism_tension_3d.toml").string(), "-o", "prism.h5", "--set",
                              "specimen.l_min=\"5 mm\"", "--set", "run.steps=8"},
                             d.dir);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  const mc::H5File f((d / "prism.h5").string(), mc::H5File::Mode::ReadOnly);
  const std::string g = "/specimen/fibres/";
  const auto point = f.read_doubles(g + "point");
  const auto start = f.read_ints(g + "line_start"), line = f.read_ints(g + "line_point");
  const auto crossings = f.read_ints(g + "crossings");
  const std::size_t fibres = crossings.size();
  REQUIRE(static_cast<double>(fibres) == f.attr_double("/specimen", "fibres"));
  REQUIRE(start.size() == fibres + 1);

  // Each fibre: its ends l_f = 10 mm apart (Květoň's rule keeps every fibre whole), its crossings between them on
  // the segment, in order from its end a. The crossings are points of that segment computed as a + t u (round-off
  // of a few ulps of 60 mm: 1e-12 m is far below any cell's size and far above round-off).
  const double l_f = 0.010, ulps = 1e-12;
  std::int64_t crossed = 0;
  for (std::size_t k = 0; k < fibres; ++k) {
    CAPTURE(k);
    const std::int64_t n = start[k + 1] - start[k];
    REQUIRE(n == crossings[k] + 2);
    crossed += crossings[k];
    const Point a = row(point, line[start[k]]), b = row(point, line[start[k + 1] - 1]);
    CHECK(std::abs((b - a).norm() - l_f) < ulps);
    const Point u = (b - a) / (b - a).norm();
    double before = 0;
    for (std::int64_t i = start[k] + 1; i + 1 < start[k + 1]; ++i) {
      const Point p = row(point, line[i]);
      const double t = (p - a).dot(u);
      CHECK(((p - a) - t * u).norm() < ulps);
      CHECK(t > before);
      CHECK(t < l_f);
      before = t;
    }
  }
  CHECK(static_cast<double>(crossed) == f.attr_double("/specimen", "fibre_crossings"));

  // The last frame: each fibre's state counted as the histories counted them in the same state, its force no more
  // than the fibre's strength f_tf π d_f²/4 (aligned fibres: no inclination lowers it, (5.10)), none where it is
  // idle, a pull-out on every fibre pulled out of a side.
  const auto state = last_row(f, "/frames/fibre_state"), force = last_row(f, "/frames/fibre_force"),
             slip = last_row(f, "/frames/fibre_slip");
  REQUIRE(state.size() == fibres);
  const auto last = [&](const std::string& series) { return f.read_doubles("/history/" + series).back(); };
  const auto count = [&](double s) { return static_cast<double>(std::count(state.begin(), state.end(), s)); };
  CHECK(count(1) == last("fibres.bridging"));
  CHECK(count(2) == last("fibres.pulled_out"));
  CHECK(count(3) == last("fibres.ruptured"));
  CHECK(count(1) > 1000);  // cracks across the prism: thousands of fibres bridge them
  const double strength = 1000e6 * std::numbers::pi * 40e-6 * 40e-6 / 4;
  for (std::size_t k = 0; k < fibres; ++k) {
    CAPTURE(k);
    CHECK(force[k] <= strength);
    if (state[k] == 0) CHECK(force[k] == 0);
    if (state[k] == 1) CHECK(force[k] > 0);
    if (state[k] == 2) CHECK(slip[k] > 0);
  }

  // The sidecar: a collection of the fibres beside the nodes, cells and facets, its grids as large as the file's.
  const std::string xdmf = slurp(d / "prism.xdmf");
  const std::vector<std::string> names = check_uniform_grids(xdmf, f);
  CHECK(contains(xdmf, "<Grid Name=\"fibres\" GridType=\"Collection\" CollectionType=\"Temporal\">"));
  CHECK(std::count(names.begin(), names.end(), "fibres0") == 1);

  const Result report = mesocrack({"report", "prism.h5"}, d.dir);
  REQUIRE_MESSAGE(report.code == 0, report.describe());
  const fs::path png = d.dir / "prism_fibres.png";
  CHECK_MESSAGE(contains(report.out, png.string()), report.out);
  REQUIRE(fs::exists(png));
  CHECK(slurp(png).substr(0, 8) == std::string("\x89PNG\r\n\x1a\n", 8));
}

TEST_CASE("generated_specimen_keeps_its_fibres_idle_and_a_run_says_what_its_fibres_cost") {
  const TempDir d;
  // `generate` writes the specimen at rest: its one fibre placed, its frame's state idle, no force, no slip.
  const Result g = mesocrack({"generate", (kScenes / "fibre_pullout_two_sided_3d.toml").string(), "-o", "spec.h5"},
                             d.dir);
  REQUIRE_MESSAGE(g.code == 0, g.describe());
  const mc::H5File f((d / "spec.h5").string(), mc::H5File::Mode::ReadOnly);
  REQUIRE(f.read_ints("/specimen/fibres/crossings") == std::vector<std::int64_t>{1});
  for (const char* t : {"/frames/fibre_state", "/frames/fibre_force", "/frames/fibre_slip"})
    CHECK(last_row(f, t) == std::vector<double>{0.0});
  // A run's closing line names the time its fibres took: a share of its wall time, between 0 and 100 %.
  const Result r = mesocrack({"run", (kScenes / "fibre_pullout_two_sided_3d.toml").string(), "-o", "run.h5"}, d.dir);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  const auto at = r.err.find("(the fibres' 1 crossing: ");
  REQUIRE_MESSAGE(at != std::string::npos, r.err);
  const double share = std::stod(r.err.substr(r.err.find(", ", at) + 2));
  CHECK(share >= 0);
  CHECK(share <= 100);
}
