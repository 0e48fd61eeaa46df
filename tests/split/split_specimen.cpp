// One specimen split across the ranks of an MPI launch (World::split): tests/split/split_world_check.cpp steps a
// bonded block whole and split on every rank and compares the bits; here it runs on 2 and 4 ranks (two cores:
// --oversubscribe), and `mesocrack run` on a bonded block (1, 2, 4 ranks) and the CPM tension scene (2, 4), whose
// files must be the serial run's. Built when the build has MPI and an mpirun.
#include "tests/common/cli_harness.hpp"

#ifdef MESOCRACK_MPIEXEC

namespace {

// `mesocrack args...` under mpirun -np n, one thread per rank.
Result on_ranks(int n, const std::vector<std::string>& args, const fs::path& dir) {
  return Child(args, dir, {"OMPI_ALLOW_RUN_AS_ROOT=1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1", "OMP_NUM_THREADS=1"},
               {MESOCRACK_MPIEXEC, "-np", std::to_string(n), "--oversubscribe"})
      .wait();
}

// The checkpoints of two files hold the same state, bit for bit: every array of both slots (a split run's is
// gathered from its ranks, so it must be the serial run's to the byte).
void check_same_checkpoints(const fs::path& a, const fs::path& b) {
  CAPTURE(a.string());
  CAPTURE(b.string());
  const mc::H5File fa(a.string(), mc::H5File::Mode::ReadOnly), fb(b.string(), mc::H5File::Mode::ReadOnly);
  int arrays = 0;
  for (const std::string slot : {"/checkpoint/a", "/checkpoint/b"}) {
    REQUIRE(fa.exists(slot) == fb.exists(slot));
    if (!fa.exists(slot)) continue;
    CHECK(fa.attr_int(slot, "step") == fb.attr_int(slot, "step"));
    for (const std::string kind : {"/reals", "/bytes"}) {
      REQUIRE(fa.list(slot + kind) == fb.list(slot + kind));
      for (const auto& name : fa.list(slot + kind)) {
        const std::string ds = slot + kind + "/" + name;
        const auto xa = fa.read_doubles(ds), xb = fb.read_doubles(ds);
        CHECK_MESSAGE(same_bits(xa, xb), ds, ": first difference at value ", first_difference(xa, xb));
        ++arrays;
      }
    }
  }
  CHECK(arrays > 20);
}

// Runs the scene serially and on each of `rank_counts`; each file must be the serial one. Returns the serial
// summary.
Json same_file_on_ranks(const std::vector<int>& rank_counts, const fs::path& scene,
                        const std::vector<std::string>& sets, const fs::path& dir) {
  std::vector<std::string> args{"run", scene.string(), "--threads", "1"};
  args.insert(args.end(), sets.begin(), sets.end());
  auto with_output = [&](const std::string& out) {
    auto a = args;
    a.insert(a.end(), {"-o", out});
    return a;
  };
  const Result serial = mesocrack(with_output("serial.h5"), dir);
  REQUIRE_MESSAGE(serial.code == 0, serial.describe());
  for (int n : rank_counts) {
    CAPTURE(n);
    const std::string out = "ranks" + std::to_string(n) + ".h5";
    const Result r = on_ranks(n, with_output(out), dir);
    REQUIRE_MESSAGE(r.code == 0, r.describe());
    if (n > 1) CHECK_MESSAGE(contains(r.err, "split across " + std::to_string(n) + " ranks"), r.err);
    MESSAGE(scene.filename().string(), ": serial ", serial.seconds, " s, ", n, " ranks ", r.seconds, " s");
    check_same_run(dir / "serial.h5", dir / out);
    check_same_checkpoints(dir / "serial.h5", dir / out);
    CHECK(slurp(dir / "serial_history.csv") == slurp(dir / ("ranks" + std::to_string(n) + "_history.csv")));
  }
  return summary_of("serial.h5", dir);
}

}  // namespace

// A bonded block pulled apart to failure (tests/scenes/split_bonded_pull_3d.toml), observed every way a scene
// can: group reactions and displacements, a servo wall, a measurement sphere (stress, strain, porosity,
// coordination), probes on particles, energy terms and the crack log. Split over 2 and 4 ranks, `mesocrack run`
// writes the serial run's file to the bit: histories, frames, crack log and checkpoints.
TEST_CASE("split_run_of_a_bonded_block_pulled_to_failure_writes_the_serial_file_on_1_2_and_4_ranks") {
  const TempDir d;
  const Json j = same_file_on_ranks(
      {1, 2, 4}, fs::path(MESOCRACK_SOURCE_DIR) / "tests/scenes/split_bonded_pull_3d.toml", {}, d.dir);
  CHECK(j["status"].text == "stopped");  // past the peak
  CHECK(j["final"]["cracks.tensile"].number > 100);
  CHECK(j["final"]["wall.side.stress"].number > 0);  // the servo wall presses on the block
}

// --rebalance: spheres settling under gravity (scenes/deposition_3d.toml, 10 000 steps) cross from the upper
// region into the lower one, which redraws the regions; the file is still the serial run's, and the closing line
// says how many particles each rank owned and how often the regions were redrawn.
TEST_CASE("split_run_with_rebalance_redraws_the_regions_of_a_settling_deposit_and_writes_the_serial_file") {
  const TempDir d;
  const std::vector<std::string> args{
      "run",           (kScenes / "deposition_3d.toml").string(), "--threads", "1", "--set", "run.steps=10000", "--set",
      "run.duration=0"};
  auto with = [&](std::vector<std::string> extra) {
    auto a = args;
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  const Result serial = mesocrack(with({"-o", "serial.h5"}), d.dir);
  REQUIRE_MESSAGE(serial.code == 0, serial.describe());
  const Result r = on_ranks(2, with({"-o", "rebalanced.h5", "--rebalance", "0.01"}), d.dir);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  check_same_run(d / "serial.h5", d / "rebalanced.h5");
  check_same_checkpoints(d / "serial.h5", d / "rebalanced.h5");
  const auto at = r.err.find("particles owned per rank ");
  REQUIRE_MESSAGE(at != std::string::npos, r.err);
  long long split_lo = 0, split_hi = 0, end_lo = 0, end_hi = 0, rebalances = -1;
  REQUIRE_MESSAGE(std::sscanf(r.err.c_str() + at,
                              "particles owned per rank %lld-%lld (most %*f %% over the mean) when split, "
                              "%lld-%lld (most %*f %% over the mean) at the end; %lld",
                              &split_lo, &split_hi, &end_lo, &end_hi, &rebalances) == 5,
                  r.err);
  const double n = summary_of("serial.h5", d.dir)["particles"].number;
  CHECK(split_lo + split_hi == n);  // two ranks own every particle once
  CHECK(end_lo + end_hi == n);
  CHECK(rebalances >= 1);
}

// Šmilauer's CPM tension test (scenes/cpm_uniax_tension.toml) pulled ten times faster, to 40 % of its peak
// stress after it: the damage of CPM's bonds, which reach beyond contact (R_I = 1.5), split over the ranks (one
// rank, which does not split, is checked on the bonded block above).
TEST_CASE("split_run_of_the_cpm_tension_scene_to_failure_writes_the_serial_file_on_2_and_4_ranks") {
  const TempDir d;
  std::string scene = slurp(kScenes / "cpm_uniax_tension.toml");
  scene = edit(scene, "file = \"specimens/cpm_1x1x2.spheres\"",
               "file = \"" + (kScenes / "specimens/cpm_1x1x2.spheres").string() + "\"");
  scene = edit(scene, "velocity = [0, 0, \"-2.25 mm/s\"]", "velocity = [0, 0, \"-22.5 mm/s\"]");
  scene = edit(scene, "velocity = [0, 0, \"2.25 mm/s\"]", "velocity = [0, 0, \"22.5 mm/s\"]");
  scene = edit(scene, "post_peak_fraction = 0.15", "post_peak_fraction = 0.4");
  write_file(d / "cpm.toml", scene);
  const Json j = same_file_on_ranks({2, 4}, d / "cpm.toml", {"--set", "output.frame_every=1000"}, d.dir);
  CHECK(j["status"].text == "stopped");
  CHECK(j["final"]["cracks.yield"].number > 100);
}

// A checkpoint does not remember how many ranks wrote it: a run begun serially and resumed on 2 ranks, and one
// begun on 4 ranks and resumed serially, each end as the uninterrupted serial run.
TEST_CASE("split_run_resumes_on_another_rank_count_bit_for_bit") {
  const TempDir d;
  const fs::path scene = fs::path(MESOCRACK_SOURCE_DIR) / "tests/scenes/split_bonded_pull_3d.toml";
  auto args = [&](std::vector<std::string> a, int steps) {
    a.insert(a.end(), {"--threads", "1", "--set", "run.steps=" + std::to_string(steps)});
    return a;
  };
  const Result whole = mesocrack(args({"run", scene.string(), "-o", "whole.h5"}, 800), d.dir);
  REQUIRE_MESSAGE(whole.code == 0, whole.describe());
  for (const auto& [first, then] : {std::pair{1, 2}, std::pair{4, 1}}) {
    CAPTURE(first);
    CAPTURE(then);
    const std::string out = "from" + std::to_string(first) + "to" + std::to_string(then) + ".h5";
    const Result a = first == 1 ? mesocrack(args({"run", scene.string(), "-o", out}, 400), d.dir)
                                : on_ranks(first, args({"run", scene.string(), "-o", out}, 400), d.dir);
    REQUIRE_MESSAGE(a.code == 0, a.describe());
    const std::vector<std::string> rest = args({"run", scene.string(), "--resume", out}, 800);
    const Result b = then == 1 ? mesocrack(rest, d.dir) : on_ranks(then, rest, d.dir);
    REQUIRE_MESSAGE(b.code == 0, b.describe());
    check_same_run(d / "whole.h5", d / out);
    check_no_repeated_rows(d / out);
  }
}

// Each contact is computed on every rank that holds one of its particles and each particle sums its contacts in
// the whole world's order, so a split run must equal the whole run to the last bit: particles, timestep, walls,
// energy and crack log, through bond breaks, migration between ranks at every rebuild, new regions when the load
// is out of balance, an adaptive skin, walls under velocity, stress and opening control, gravity and energy.
// One rank is left out here: the command does not split a world over one process (it is the serial run, checked
// through the command above), and a one-process split would step every scene twice on one core.
TEST_CASE("split_specimen_on_2_and_4_ranks_gives_the_whole_world_bits") {
  const TempDir d;
  for (int n : {2, 4}) {
    const Result r =
        Child({}, d.dir, {"OMPI_ALLOW_RUN_AS_ROOT=1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1", "OMP_NUM_THREADS=1"},
              {MESOCRACK_MPIEXEC, "-np", std::to_string(n), "--oversubscribe"}, SPLIT_WORLD_CHECK)
            .wait();
    MESSAGE(n, " ranks: ", r.out);
    REQUIRE_MESSAGE(r.code == 0, n, " ranks: ", r.describe());
    // Every rank reported each scene; particles changed hands, and the drifting block's regions were drawn anew.
    int reports = 0;
    long arrived = 0, rebalances = 0;
    auto number_before = [&](std::size_t at, const char* word) {
      const std::size_t end = r.out.find(word, at);
      return std::stol(r.out.substr(r.out.rfind(' ', end - 1) + 1));
    };
    for (std::size_t at = 0; (at = r.out.find("same bits", at)) != std::string::npos; ++at) {
      ++reports;
      arrived += number_before(at, " arrived");
      rebalances += number_before(at, " rebalances");
    }
    CHECK(reports == 4 * n);  // four scenes
    int stops = 0;
    for (std::size_t at = 0; (at = r.out.find("same stop: ", at)) != std::string::npos; ++at) ++stops;
    CHECK(stops == 3 * n);  // three failures found alike on every rank
    CHECK(arrived > 0);
    CHECK(rebalances > 0);
  }
}

// A run that goes unstable on 2 ranks stops as the serial one does: exit 4, the same message on stderr and in
// the file (written by rank 0 while the other waits), and the same rows up to the failure.
TEST_CASE("split_run_that_goes_unstable_stops_every_rank_with_the_serial_message_in_the_file") {
  const TempDir d;
  const fs::path scene = fs::path(MESOCRACK_SOURCE_DIR) / "tests/scenes/split_bonded_pull_3d.toml";
  // The top layer shot off at 50 km/s: its particles move more than half their radius in the first step.
  const std::vector<std::string> sets{"--threads", "1", "--set", "groups[1].velocity=[0, 0, 50000]"};
  auto args = [&](const std::string& out) {
    std::vector<std::string> a{"run", scene.string(), "-o", out};
    a.insert(a.end(), sets.begin(), sets.end());
    return a;
  };
  const Result serial = mesocrack(args("serial.h5"), d.dir);
  REQUIRE_MESSAGE(serial.code == 4, serial.describe());
  const Result split = on_ranks(2, args("ranks2.h5"), d.dir);
  CHECK_MESSAGE(split.code == 4, split.describe());
  const std::string message = serial.err.substr(serial.err.find("error: "));
  CHECK_MESSAGE(contains(split.err, message), "serial: ", serial.err, "split: ", split.err);
  check_same_run(d / "serial.h5", d / "ranks2.h5");
}

// A rigid-cell specimen is one matrix factorised in one process: split over ranks it is refused as bad input,
// naming the scene and the way to run it, before any file is written. (A build without the family refuses the
// scene whatever the rank count: tests/command_line_bad_input.cpp.)
#if MESOCRACK_RIGID_CELL_BUILT
TEST_CASE("split_run_of_a_rigid_cell_scene_is_refused_naming_the_scene") {
  const TempDir d;
  const Result r = on_ranks(2, {"run", (kScenes / "rigid_cell_tension_2d.toml").string(), "-o", "rc.h5"}, d.dir);
  CHECK_MESSAGE(r.code == 2, r.describe());
  CHECK_MESSAGE(contains(r.err, "rigid_cell_tension_2d.toml: [rigid_cell]: a rigid-cell specimen runs in one process"),
                r.err);
  CHECK(!fs::exists(d / "rc.h5"));
}
#endif

#endif
