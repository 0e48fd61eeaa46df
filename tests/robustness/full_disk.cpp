// A disk that fills up during a run (tests/robustness/full_disk_shim.c, preloaded into the command, gives the
// output's folder a fixed number of free bytes): the run ends with exit 3 and one line naming the file and the
// cause, never a crash; the output file is either absent (the disk filled before its initial contents were
// complete) or readable by `summary` as it was at its last flush, and `run --resume` on a disk with room finishes
// it bit for bit like a run that never stopped.
#include <random>

#include "tests/common/cli_harness.hpp"

namespace {

const std::string kShim = FULL_DISK_SHIM;

// A bonded bar pulled apart for 1100 steps (0.4 s): frames every 100 steps and checkpoints every 300, so the disk
// fills while writing the specimen, a frame, history rows, a checkpoint or a flush, depending on its size.
std::vector<std::string> bar_run(const std::string& output) {
  return {"run",   (kScenes / "lattice_tension_2d.toml").string(),
          "-o",    output,
          "--set", "run.duration=0.04 ms",
          "--set", "output.frame_every=100",
          "--set", "output.checkpoint_every=300"};
}

}  // namespace

TEST_CASE("full_disk_ends_run_with_exit_3_and_leaves_no_file_or_a_readable_resumable_one") {
  const TempDir d;
  const Result whole = mesocrack(bar_run("whole.h5"), d.dir);
  REQUIRE_MESSAGE(whole.code == 0, whole.describe());
  // The free space the run needs: the most its files take at once, as the shim counts.
  fs::create_directories(d / "measure");
  const Result measured = mesocrack(bar_run("measure/out.h5"), d.dir,
                                    {"LD_PRELOAD=" + kShim, "MC_FULL_DISK_DIR=" + (d / "measure").string(),
                                     "MC_FULL_DISK_PEAK=" + (d / "peak.txt").string()});
  REQUIRE_MESSAGE(measured.code == 0, measured.describe());
  const std::uintmax_t needed = std::stoull(slurp(d / "peak.txt"));
  REQUIRE(needed > 1000000);

  // Free space from nothing to just short of what the run needs: 0, then one size drawn in each of kStretches equal
  // stretches (fixed seed: the same sizes every time).
  const std::uintmax_t most = needed - 1;
  std::vector<std::uintmax_t> sizes{0};
  std::mt19937_64 rng(20240514);
  constexpr int kStretches = 24;
  for (int k = 0; k < kStretches; ++k)
    sizes.push_back(most * k / kStretches + std::uniform_int_distribution<std::uintmax_t>(0, most / kStretches)(rng));

  int absent = 0, resumed = 0;
  for (const std::uintmax_t free_bytes : sizes) {
    CAPTURE(free_bytes);
    const fs::path disk = d / ("disk" + std::to_string(free_bytes));
    fs::create_directories(disk);
    const std::string out = disk.filename().string() + "/out.h5";
    const Result r = mesocrack(bar_run(out), d.dir,
                               {"LD_PRELOAD=" + kShim, "MC_FULL_DISK_DIR=" + disk.string(),
                                "MC_FULL_DISK_FREE=" + std::to_string(free_bytes)});
    REQUIRE_MESSAGE(r.code == 3, r.describe());
    CHECK_MESSAGE(r.err.rfind("error: " + out + ": ", 0) == 0, r.err);
    CHECK_MESSAGE(contains(r.err, "No space left on device"), r.err);
    CHECK_MESSAGE(std::count(r.err.begin(), r.err.end(), '\n') == 1, r.err);
    for (const auto& name : files_in(disk))
      CHECK_MESSAGE((name == "out.h5" || name == "out.xdmf"), "left behind: ", name);

    if (!fs::exists(disk / "out.h5")) {
      CHECK_MESSAGE(contains(r.err, out + " was not written"), r.err);
      CHECK(files_in(disk).empty());
      ++absent;
      continue;
    }
    CHECK_MESSAGE(contains(r.err, out + " keeps the run as last flushed"), r.err);
    const Json s = summary_of(out, d.dir);
    CHECK(s["status"].text == "running");
    CHECK(s["history_rows"].number >= 1);
    std::vector<std::string> resume = bar_run(out);
    resume[2] = "--resume";
    const Result rest = mesocrack(resume, d.dir);
    REQUIRE_MESSAGE(rest.code == 0, rest.describe());
    check_same_run(d / "whole.h5", disk / "out.h5");
    check_no_repeated_rows(disk / "out.h5");
    CHECK(slurp(d / "whole_history.csv") == slurp(disk / "out_history.csv"));
    ++resumed;
  }
  MESSAGE(sizes.size(), " disk sizes up to ", needed, " bytes: ", absent, " left no file, ", resumed,
          " a readable file that resumed to the uninterrupted run");
  CHECK(absent >= 1);
  CHECK(resumed >= kStretches / 2);
}
