// Runs spread over the ranks of an MPI launch (studies/ranks.hpp): `mpirun -np 2 mesocrack run --realizations`
// and `mpirun -np 2 mesocrack calibrate` give the serial command's runs, statistics and calibrated scene to the
// last bit. Built when the build has MPI and an mpirun; two ranks on a two-core machine with --oversubscribe.
#include "tests/common/cli_harness.hpp"
#include "tests/common/small_cpm_scenes.hpp"

#ifdef MESOCRACK_MPIEXEC

namespace {

const std::string kSmall = (fs::path(MESOCRACK_SOURCE_DIR) / "tests" / "scenes" / "uniaxial_2d_small.toml").string();

// Open MPI refuses to start as root unless told it may (CI runs as root).
const std::vector<std::string> kRootOk = {"OMPI_ALLOW_RUN_AS_ROOT=1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1"};

Result on_ranks(int n, const std::vector<std::string>& args, const fs::path& cwd) {
  return Child(args, cwd, kRootOk, {MESOCRACK_MPIEXEC, "-np", std::to_string(n), "--oversubscribe"}).wait();
}

}  // namespace

// Realization k runs on rank k mod 2 with seed + k: each is the serial run of that seed, so every history is the
// same bits and rank 0's statistics are the serial statistics (same inputs, summed in the same order).
TEST_CASE("realizations_over_two_ranks_equal_the_serial_runs_bit_for_bit") {
  const TempDir d;
  fs::create_directories(d / "serial");
  fs::create_directories(d / "ranks");
  const Result serial = mesocrack({"run", kSmall, "-o", "serial/u.h5", "--realizations", "3", "--threads", "1"}, d.dir);
  REQUIRE_MESSAGE(serial.code == 0, serial.describe());
  const Result ranks = on_ranks(2, {"run", kSmall, "-o", "ranks/u.h5", "--realizations", "3", "--threads", "1"}, d.dir);
  REQUIRE_MESSAGE(ranks.code == 0, ranks.describe());
  for (const char* f : {"u_r0.h5", "u_r1.h5", "u_r2.h5"}) check_same_run(d / "serial" / f, d / "ranks" / f);
  // One statistics document, written by rank 0 alone; its numbers equal the serial ones as printed.
  const Json js = parse_json(serial.out), jr = parse_json(ranks.out);
  for (const char* q : {"E", "nu", "ucs", "strain_at_peak", "crack_initiation_ratio"})
    for (const char* m : {"mean", "std", "cv"})
      CHECK_MESSAGE(js["statistics"][q][m].text == jr["statistics"][q][m].text, q, ".", m);
  const auto& rs = jr["realizations"].items;
  REQUIRE(rs.size() == 3);
  for (int k = 0; k < 3; ++k) CHECK(rs[k]["seed"].number == k + 1);
  CHECK(parse_json(slurp(d / "ranks" / "u_realizations.json"))["statistics"]["ucs"]["mean"].text ==
        jr["statistics"]["ucs"]["mean"].text);
}

// A CPM calibration with an f_c target runs a tension and a compression test per full iteration: on two ranks at
// once. Every rank iterates on the same shared numbers, so each run, the log's numbers and the calibrated scenes
// are the serial command's (4 iterations: the elastic ones and full ones with both tests; not converged, exit 5).
TEST_CASE("calibration_over_two_ranks_equals_the_serial_calibration_bit_for_bit") {
  const TempDir d;
  write_file(d / "packing.toml", small_cpm::kPacking);
  write_file(d / "tension.toml", small_cpm::kTension);
  write_file(d / "compression.toml", small_cpm::compression());
  const Result g = mesocrack({"generate", "packing.toml", "-o", "packing.h5"}, d.dir);
  REQUIRE_MESSAGE(g.code == 0, g.describe());
  fs::create_directories(d / "serial");
  fs::create_directories(d / "ranks");
  auto calibrate = [&](const std::string& dir) {
    return std::vector<std::string>{"calibrate",
                                    "tension.toml",
                                    "--target",
                                    "E=30GPa,nu=0.15,ft=3MPa,fc=30MPa",
                                    "--compression",
                                    "compression.toml",
                                    "-o",
                                    dir + "/cal.toml",
                                    "--max-iterations",
                                    "4",
                                    "--threads",
                                    "1"};
  };
  const Result serial = mesocrack(calibrate("serial"), d.dir);
  const Result ranks = on_ranks(2, calibrate("ranks"), d.dir);
  REQUIRE_MESSAGE(serial.code == 5, serial.describe());
  REQUIRE_MESSAGE(ranks.code == 5, ranks.describe());
  CHECK(serial.out == ranks.out);  // the calibrated values, to 8 digits
  CHECK(slurp(d / "serial" / "cal.toml") == slurp(d / "ranks" / "cal.toml"));
  CHECK(slurp(d / "serial" / "cal_compression.toml") == slurp(d / "ranks" / "cal_compression.toml"));
  int compression_runs = 0;
  for (int it = 1; it <= 4; ++it) {
    const std::string run = "cal_it" + std::to_string(it) + ".h5",
                      comp = "cal_it" + std::to_string(it) + "_compression.h5";
    check_same_run(d / "serial" / run, d / "ranks" / run);
    if (fs::exists(d / "serial" / comp)) {
      check_same_run(d / "serial" / comp, d / "ranks" / comp);
      ++compression_runs;
    }
  }
  CHECK(compression_runs >= 1);  // the full iterations ran both tests, on the two ranks
}

// A rank whose run fails ends the whole launch with the command's exit code, naming the cause, instead of leaving
// rank 0 waiting for its share: realization 1 (rank 1) cannot write its output, where a folder stands.
TEST_CASE("a_failing_rank_ends_the_mpi_launch_with_its_exit_code") {
  const TempDir d;
  fs::create_directories(d / "u_r1.h5");
  const Result r = on_ranks(2, {"run", kSmall, "-o", "u.h5", "--realizations", "2", "--threads", "1"}, d.dir);
  CHECK_MESSAGE(r.code == 3, r.describe());
  CHECK_MESSAGE(contains(r.err, "u_r1.h5"), r.err);
  CHECK(!fs::exists(d / "u_realizations.json"));
}

#endif
