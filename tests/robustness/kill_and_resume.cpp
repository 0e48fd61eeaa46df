// kill -9 at many moments of a bonded run: whenever it dies, the output is absent (killed before its initial contents
// were complete: only OUT.h5.partial may be left) or a file `summary` reads and `run --resume` finishes bit for bit
// like the uninterrupted run: histories, frames, the crack log and the CSV.
// Two ways of choosing the moments: times drawn from a fixed seed, a few within the first 60 ms (creating the file)
// and the rest spread over the run; and exact writes inside HDF5's flushes (tests/robustness/kill_at_write_shim.c),
// where a kill leaves the file's metadata half-updated (a timed kill rarely lands there: flushes are short).
#include <fstream>
#include <random>

#include "tests/common/cli_harness.hpp"

namespace {

// The bonded bar of scenes/lattice_tension_2d.toml pulled for 0.12 ms (about 3300 steps, a second on one core):
// bonds break from ~0.1 ms on. Rows every 50 steps, frames every 250, checkpoints every 400, so most kills fall
// after rows, frames and cracks that the resume must drop and write again.
std::vector<std::string> bar(const std::string& mode, const std::string& output) {
  return {"run",       (kScenes / "lattice_tension_2d.toml").string(),
          mode,        output,
          "--set",     "run.duration=0.12 ms",
          "--set",     "output.history_every=50",
          "--set",     "output.frame_every=250",
          "--set",     "output.checkpoint_every=400",
          "--threads", "1"};
}

// The run's output `out` killed (or ended) somehow, then summarised and resumed: true when a file was left and
// resumed to `whole`, bit for bit; false when no file was left (the resume then fails, exit 3).
bool resumes_to_the_whole_run(const TempDir& d, const std::string& out) {
  if (!fs::exists(d / out)) {
    const Result again = mesocrack(bar("--resume", out), d.dir);
    CHECK_MESSAGE(again.code == 3, again.describe());
    if (fs::exists(d / (out + ".partial"))) CHECK_MESSAGE(contains(again.err, out + ".partial"), again.err);
    return false;
  }
  const Json s = summary_of(out, d.dir);
  CHECK(s["history_rows"].number >= 1);
  const Result rest = mesocrack(bar("--resume", out), d.dir);
  REQUIRE_MESSAGE(rest.code == 0, rest.describe());
  check_same_run(d / "whole.h5", d / out);
  check_no_repeated_rows(d / out);
  CHECK(slurp(d / "whole_history.csv") == slurp(d / (fs::path(out).stem().string() + "_history.csv")));
  return true;
}

}  // namespace

TEST_CASE("kill_9_inside_hdf5_flushes_then_resume_gives_the_uninterrupted_run_bit_for_bit") {
  const TempDir d;
  const std::string shim = std::string("LD_PRELOAD=") + KILL_AT_WRITE_SHIM;
  // The uninterrupted run, its writes listed: each flush ends by rewriting the superblock at offset 0.
  const Result whole = mesocrack(bar("-o", "whole.h5"), d.dir, {shim, "MC_WRITE_LOG=" + (d / "writes.txt").string()});
  REQUIRE_MESSAGE(whole.code == 0, whole.describe());
  std::vector<long> superblock;  // the numbers of the writes at offset 0 once the file has its name
  {
    std::ifstream in(d / "writes.txt");
    long n = 0, offset = 0, size = 0, published = -1;  // the writes before the first rename create the file
    while (in >> n >> offset >> size) {
      if (offset == -1 && published < 0) published = n;
      if (offset == 0 && published >= 0 && n > published) superblock.push_back(n);
    }
  }
  REQUIRE(superblock.size() >= 12);  // one per flush that moved the end of the file
  // Kills at the superblock's write (every other object of the flush written, the file's new end not) and three
  // writes before it (objects half-updated), at 4 flushes spread over the run and 2 near its end, while the bonds
  // break and the crack log grows. The files killed at those two superblock writes hold tables whose last chunks
  // lie past the file's recorded end: `report` must draw what reads.
  const std::size_t m = superblock.size();
  int absent = 0, resumed = 0;
  for (const std::size_t k : {std::size_t{0}, m / 4, m / 2, m - 5, m - 4, m - 3}) {
    for (const long n : {superblock[k] - 3, superblock[k]}) {
      CAPTURE(n);
      const std::string out = "w" + std::to_string(n) + ".h5";
      const Result r = mesocrack(bar("-o", out), d.dir, {shim, "MC_KILL_AT_WRITE=" + std::to_string(n)});
      REQUIRE_MESSAGE(r.code == -SIGKILL, r.describe());
      if (k >= m - 4 && n == superblock[k]) {
        const Result report = mesocrack({"report", out}, d.dir);
        CHECK_MESSAGE(report.code == 0, report.describe());
        CHECK(contains(report.out, ".png"));
      }
      resumes_to_the_whole_run(d, out) ? ++resumed : ++absent;
    }
  }
  MESSAGE("12 kills inside flushes: ", absent, " before the file existed, ", resumed, " resumed bit for bit");
  CHECK(resumed == 12);
}

TEST_CASE("kill_9_at_random_moments_then_resume_gives_the_uninterrupted_run_bit_for_bit") {
  const TempDir d;
  const Result whole = mesocrack(bar("-o", "whole.h5"), d.dir);
  REQUIRE_MESSAGE(whole.code == 0, whole.describe());
  {
    const mc::H5File f((d / "whole.h5").string(), mc::H5File::Mode::ReadOnly);
    REQUIRE(f.rows("/cracks/step") > 0);  // the resumes must carry a crack log across
  }
  const double run_seconds = whole.seconds;

  std::mt19937_64 rng(14);
  std::vector<double> moments;  // seconds after the start
  for (int k = 0; k < 2; ++k) moments.push_back(std::uniform_real_distribution<double>(0.0, 0.06)(rng));
  for (int k = 0; k < 8; ++k) moments.push_back(std::uniform_real_distribution<double>(0.0, run_seconds)(rng));

  int absent = 0, resumed = 0, finished_first = 0;
  for (std::size_t k = 0; k < moments.size(); ++k) {
    CAPTURE(moments[k]);
    const std::string out = "k" + std::to_string(k) + ".h5";
    {
      Child run(bar("-o", out), d.dir);
      std::this_thread::sleep_for(std::chrono::duration<double>(moments[k]));
      run.kill_now();
      const Result r = run.wait();
      if (r.code == 0)
        ++finished_first;
      else
        REQUIRE_MESSAGE(r.code == -SIGKILL, r.describe());
    }
    resumes_to_the_whole_run(d, out) ? ++resumed : ++absent;
  }
  MESSAGE(moments.size(), " kills over a ", run_seconds, " s run: ", absent, " before the file existed, ", resumed,
          " resumed to the uninterrupted run bit for bit (", finished_first, " of them had finished before the kill)");
  CHECK(resumed >= 4);
}

// Ctrl-C (SIGINT) or `kill` (SIGTERM) once the output exists: the run finishes its step, checkpoints, says so and
// exits 128 + the signal, its file "interrupted"; `run --resume OUT.h5` alone (the scene and its --set read from the
// file) then finishes it bit for bit like the uninterrupted run.
TEST_CASE("ctrl_c_or_sigterm_checkpoint_the_run_and_resume_from_the_file_alone_gives_the_uninterrupted_run") {
  const TempDir d;
  const Result whole = mesocrack(bar("-o", "whole.h5"), d.dir);
  REQUIRE_MESSAGE(whole.code == 0, whole.describe());
  for (const int sig : {SIGINT, SIGTERM}) {
    CAPTURE(sig);
    const std::string out = "i" + std::to_string(sig) + ".h5";
    {
      Child run(bar("-o", out), d.dir);
      // Once the file is published (before it, a signal kills as it would any program), a third into the run.
      while (!fs::exists(d / out) && !run.ended()) std::this_thread::sleep_for(std::chrono::milliseconds(2));
      std::this_thread::sleep_for(std::chrono::duration<double>(whole.seconds / 3));
      run.send(sig);
      const Result r = run.wait();
      REQUIRE_MESSAGE(r.code == 128 + sig, r.describe());
      CHECK(contains(r.err, "interrupted by " + std::string(sig == SIGINT ? "SIGINT" : "SIGTERM") + " after "));
      CHECK(contains(r.err, "mesocrack run --resume " + out));
    }
    const Json s = summary_of(out, d.dir);
    CHECK(s["status"].text == "interrupted");
    CHECK(s["steps"].number > 0);
    const Result rest = mesocrack({"run", "--resume", out, "--threads", "1"}, d.dir);
    REQUIRE_MESSAGE(rest.code == 0, rest.describe());
    CHECK(contains(rest.err, "resumed " + out + " at step "));
    check_same_run(d / "whole.h5", d / out);
    check_no_repeated_rows(d / out);
    CHECK(slurp(d / "whole_history.csv") == slurp(d / (fs::path(out).stem().string() + "_history.csv")));
  }
}

TEST_CASE("resume_from_the_file_alone_in_another_folder_finds_the_files_the_scene_names_relative_to_itself") {
  // The scene names its specimen relative to its own folder, a/; the resume runs in b/ with no scene given.
  const TempDir d;
  fs::create_directories(d / "a");
  fs::create_directories(d / "b");
  fs::copy_file(kScenes / "specimens" / "cpm_1x1x2.spheres", d / "a" / "block.spheres");
  std::string scene = slurp(fs::path(MESOCRACK_SOURCE_DIR) / "tests" / "scenes" / "split_bonded_pull_3d.toml");
  const std::string named = "../../scenes/specimens/cpm_1x1x2.spheres";
  REQUIRE(scene.find(named) != std::string::npos);
  scene.replace(scene.find(named), named.size(), "block.spheres");
  std::ofstream(d / "a" / "scene.toml") << scene;
  const std::vector<std::string> common = {"--set", "output.checkpoint_every=20", "--threads", "1"};
  std::vector<std::string> first = {"run", "a/scene.toml", "-o", "out.h5", "--set", "run.duration=20 us"};
  first.insert(first.end(), common.begin(), common.end());
  const Result r = mesocrack(first, d.dir);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  std::vector<std::string> rest = {"run", "--resume", "../out.h5", "--set", "run.duration=40 us"};
  rest.insert(rest.end(), common.begin(), common.end());
  const Result again = mesocrack(rest, d / "b");
  REQUIRE_MESSAGE(again.code == 0, again.describe());
  CHECK(contains(again.err, "resumed ../out.h5 at step "));
  CHECK(summary_of("out.h5", d.dir)["time"].number >= 40e-6 * (1 - 1e-9));
}
