// Output files that lack what `summary` reads, or are no HDF5 at all, end `summary` and `report` with exit 3 naming
// the file and the missing entry (never a crash); and an output that is an input of the run (the scene file, the
// specimen file it loads, also through --set, or a file a sidecar would replace) is refused with exit 2 naming both,
// leaving the input as it was.
#include "tests/common/cli_harness.hpp"

namespace {

// A finished run of the two-disc collision, copied to `name` and changed by `damage`.
template <class F>
void damaged_copy(const TempDir& d, const std::string& name, F&& damage) {
  if (!fs::exists(d / "good.h5")) {
    const Result r = mesocrack({"run", (kScenes / "collision_2d.toml").string(), "-o", "good.h5"}, d.dir);
    REQUIRE_MESSAGE(r.code == 0, r.describe());
  }
  fs::copy_file(d / "good.h5", d / name);
  mc::H5File f((d / name).string(), mc::H5File::Mode::ReadWrite);
  damage(f);
}

void check_file_error(const Result& r, const std::vector<std::string>& parts) {
  CHECK_MESSAGE(r.code == 3, r.describe());
  CHECK_MESSAGE(std::count(r.err.begin(), r.err.end(), '\n') == 1, r.err);
  for (const auto& p : parts) CHECK_MESSAGE(contains(r.err, p), "stderr '", r.err, "' lacks '", p, "'");
}

}  // namespace

TEST_CASE("summary_of_a_file_lacking_what_it_reads_exits_3_naming_the_file_and_the_entry") {
  const TempDir d;
  damaged_copy(d, "no_time.h5", [](mc::H5File& f) { f.remove("/history/time"); });
  check_file_error(mesocrack({"summary", "no_time.h5"}, d.dir), {"no_time.h5", "/history/time"});
  damaged_copy(d, "no_history.h5", [](mc::H5File& f) { f.remove("/history"); });
  check_file_error(mesocrack({"summary", "no_history.h5"}, d.dir), {"no_history.h5", "/history"});
  damaged_copy(d, "short.h5", [](mc::H5File& f) { f.truncate_rows("/history/overlap", 3); });
  check_file_error(mesocrack({"summary", "short.h5"}, d.dir), {"short.h5", "/history/overlap", "3 rows"});
  damaged_copy(d, "no_scene.h5", [](mc::H5File& f) { f.remove("/scene"); });
  check_file_error(mesocrack({"summary", "no_scene.h5"}, d.dir), {"no_scene.h5", "/scene"});
  damaged_copy(d, "no_radius.h5", [](mc::H5File& f) { f.remove("/specimen/radius"); });
  check_file_error(mesocrack({"summary", "no_radius.h5"}, d.dir), {"no_radius.h5", "/specimen/radius"});
  damaged_copy(d, "bad_scene.h5", [](mc::H5File& f) { f.write_string("/scene", "dimension = 7\n"); });
  check_file_error(mesocrack({"summary", "bad_scene.h5"}, d.dir), {"bad_scene.h5", "/scene", "dimension"});
  write_file(d / "text.h5", "not HDF5\n");
  check_file_error(mesocrack({"summary", "text.h5"}, d.dir), {"text.h5"});
  check_file_error(mesocrack({"summary", "absent.h5"}, d.dir), {"absent.h5", "no such file"});
}

TEST_CASE("report_of_a_missing_or_non_hdf5_file_exits_3") {
  const TempDir d;
  write_file(d / "text.h5", "not HDF5\n");
  for (const std::string name : {"text.h5", "absent.h5"}) {
    const Result r = mesocrack({"report", name}, d.dir);
    CHECK_MESSAGE(r.code == 3, r.describe());
    CHECK_MESSAGE(contains(r.err, name), r.err);
  }
}

TEST_CASE("output_naming_an_input_of_the_run_is_refused_naming_both") {
  const TempDir d;
  const std::string scene = slurp(kScenes / "collision_2d.toml");
  write_file(d / "scene.toml", scene);
  // A specimen file the scene loads (kind = "output"): the collision's finished run.
  REQUIRE(mesocrack({"run", "scene.toml", "-o", "spec.h5"}, d.dir).code == 0);
  fs::copy_file(d / "spec.h5", d / "other.h5");
  const std::string from_file = edit(scene, "kind = \"particles\"", "kind = \"output\"\nfile = \"spec.h5\"");
  write_file(d / "loads.toml", from_file.substr(0, from_file.find("[[specimen.particles]]")) +
                                   from_file.substr(from_file.find("[[probes]]")));
  fs::create_directories(d / "sub");
  struct Case {
    std::vector<std::string> args;
    std::string input;  // the input the output would overwrite
  };
  const std::vector<Case> cases{
      {{"run", "scene.toml", "-o", "scene.toml"}, "scene.toml"},
      {{"run", "scene.toml", "-o", "sub/../scene.toml"}, "scene.toml"},  // another spelling of the same file
      {{"run", "loads.toml", "-o", "spec.h5"}, "spec.h5"},
      {{"run", "loads.toml", "-o", "./spec.h5"}, "spec.h5"},
      {{"run", "loads.toml", "--set", "specimen.file=other.h5", "-o", "other.h5"}, "other.h5"},
      {{"run", "loads.toml", "--resume", "spec.h5"}, "spec.h5"},
      {{"generate", "loads.toml", "-o", "spec.h5"}, "spec.h5"},
  };
  for (const auto& c : cases) {
    CAPTURE(c.args);
    const std::string before = slurp(d / c.input);
    const Result r = mesocrack(c.args, d.dir);
    CHECK_MESSAGE(r.code == 2, r.describe());
    CHECK_MESSAGE(contains(r.err, c.input), r.err);
    CHECK_MESSAGE(contains(r.err, "overwrite its own input"), r.err);
    CHECK(slurp(d / c.input) == before);
  }
  // A sidecar the run would replace that is an input: a scene named like the run's CSV.
  fs::copy_file(d / "scene.toml", d / "run_history.csv");
  const Result sidecar = mesocrack({"run", "run_history.csv", "-o", "run.h5"}, d.dir);
  CHECK_MESSAGE(sidecar.code == 2, sidecar.describe());
  CHECK_MESSAGE(contains(sidecar.err, "run_history.csv"), sidecar.err);
  CHECK(!fs::exists(d / "run.h5"));
}
