// Throughput benchmark of the engine's stepping loop (World::step), printed as markdown tables.
//
//  a) shared (throughput_shared.hpp): the specimen of benchmarks/specimens/README.md with unbonded linear contacts,
//     parallel bonds beside them, and the Concrete Particle Model; the peers are timed on it by make peers-bench.
//  b) scaling (throughput_scaling.hpp): dense random 2D and 3D assemblies from 1e3 to 1e6 particles, and a
//     parallel-bonded 3D block from 1e4 to 1e7 with its memory and bandwidth; the cost per particle-step must stay
//     flat (O(N)).
//  c) effects (throughput_effects.hpp): the cost of each optional effect (gravity, local damping, contact
//     dashpots, energy tracing) as a ratio to the same run without it.
//  d) deposition (throughput_deposition.hpp): a poured flow with a fixed and an adaptive Verlet skin.
//
// Only the stepping loop is timed (std::chrono::steady_clock); each timing is repeated (default 3) on a fresh
// world, or for the bonded block as windows of one world, and the best is kept. Ratios are always taken within one
// run: the machine is shared and noisy.
//
//   throughput [--quick] [--only shared|bonded|cpm|scaling|bonded-scaling|effects|deposition] [--specimen-dir DIR]
//              [--reps N] [--max-bonded N]
//   throughput --one n10k:parallel:1 [--specimen-dir DIR]   (one run, one RESULT line: benchmarks/peers/)
#include <omp.h>
#include <unistd.h>

#include <charconv>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "benchmarks/options.hpp"
#include "benchmarks/run_timing.hpp"
#include "benchmarks/throughput_deposition.hpp"
#include "benchmarks/throughput_effects.hpp"
#include "benchmarks/throughput_scaling.hpp"
#include "benchmarks/throughput_shared.hpp"
#include "benchmarks/throughput_world.hpp"

namespace {

using namespace mc::bench;

// --one SPECIMEN:MODEL:THREADS into its parts; empty when it reads, else what is allowed.
std::string read_one(const std::string& v, Options& o) {
  const auto c1 = v.find(':'), c2 = v.rfind(':');
  if (c1 == std::string::npos || c2 == c1) return "give SPECIMEN:MODEL:THREADS";
  o.one_specimen = v.substr(0, c1), o.one_model = v.substr(c1 + 1, c2 - c1 - 1);
  if (o.one_model != "unbonded" && o.one_model != "parallel" && o.one_model != "cpm")
    return "model '" + o.one_model + "': allowed unbonded, parallel, cpm";
  const std::string t = v.substr(c2 + 1);
  const char* last = t.data() + t.size();
  const auto [end, ec] = std::from_chars(t.data(), last, o.one_threads);
  if (ec != std::errc() || end != last || o.one_threads < 1 || o.one_threads > 64)
    return "threads '" + t + "': allowed an integer from 1 to 64";
  return "";
}

// The options, read with CLI11 as the command reads its own: a bad one exits with 2 and a message naming the
// option, the value and what is allowed.
Options parse(int argc, char** argv) {
  Options o;
  std::string only, one;
  CLI::App app{"throughput: the stepping loop's throughput, as markdown tables"};
  app.add_flag("--quick", o.quick, "small sizes, and one timing each unless --reps is given");
  app.add_option("--only", only, "one section")
      ->check(CLI::IsMember({"shared", "bonded", "cpm", "scaling", "bonded-scaling", "effects", "deposition"}));
  app.add_option("--specimen-dir", o.specimen_dir, "the folder of the shared specimens");
  const CLI::Option* reps =
      app.add_option("--reps", o.reps, "timings of each figure, the best kept")->check(CLI::Range(1, 100));
  app.add_option("--max-bonded", o.max_bonded, "the largest bonded block of the scaling section, particles")
      ->check(CLI::Range(100000, 100000000));
  // CLI11 checks a given value once: the check stores its parts.
  app.add_option("--one", one, "SPECIMEN:MODEL:THREADS: that run of the shared section alone, as one RESULT line")
      ->check([&o](const std::string& v) { return read_one(v, o); });
  if (const auto code = read_options(app, argc, argv, "throughput")) std::exit(*code);
  if (!only.empty()) {
    o.shared = only == "shared" || only == "bonded" || only == "cpm", o.effects = only == "effects";
    o.deposition = only == "deposition";
    o.scaling = only == "scaling" || only == "bonded-scaling", o.unbonded_scaling = only == "scaling";
    o.unbonded = only == "shared", o.parallel = only != "cpm", o.cpm = only != "bonded";
  }
  o.reps_given = reps->count() > 0;
  if (o.quick && !o.reps_given) o.reps = 1;
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  // On a shared machine, threads that spin at the end of each parallel region (libgomp's default) lose whole time
  // slices whenever another process holds a core, and 2-thread runs become several times slower than 1-thread
  // runs. Unless the caller chose a policy, run with passive waiting: libgomp reads it at start-up, so re-execute.
  // A --one run (benchmarks/peers/, on a quiet machine) times what `mesocrack run` does: libgomp's own policy.
  bool one = false;
  for (int i = 1; i < argc; ++i) one = one || std::string(argv[i]) == "--one";
  bool policy_set_here = false;
  if (!one && !std::getenv("OMP_WAIT_POLICY")) {
    setenv("OMP_WAIT_POLICY", "passive", 1);
    setenv("MESOCRACK_BENCH_POLICY_SET", "1", 1);
    execv("/proc/self/exe", argv);  // returns only on failure: go on with the default policy
    unsetenv("OMP_WAIT_POLICY");
  }
  policy_set_here = std::getenv("MESOCRACK_BENCH_POLICY_SET") != nullptr;
  const char* policy = std::getenv("OMP_WAIT_POLICY");
  const Options opt = parse(argc, argv);
  if (!opt.one_specimen.empty()) {
    try {
      one_shared(opt);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "throughput: %s\n", e.what());
      return 1;
    }
    return 0;
  }
  const auto t0 = Clock::now();
  std::printf("# mesocrack throughput%s\n\n", opt.quick ? " (--quick: small sizes)" : "");
  std::printf(
      "%d hardware threads visible (omp_get_num_procs); timings with omp_set_num_threads(1) and (2). "
      "OpenMP wait policy: %s%s.\n\n",
      omp_get_num_procs(), policy ? policy : "libgomp default (spin, then sleep)",
      policy_set_here ? " (set by this benchmark; run with OMP_WAIT_POLICY=active to measure spinning threads)" : "");
  std::printf(
      "Load average (1 / 5 / 15 min) at the start: %s. The machine may be shared: the CPU/wall columns and "
      "the load after each section tell how quiet it was.\n\n",
      loadavg().c_str());
  auto section = [](auto&& fn) {
    fn();
    std::printf("(load average after this section: %s)\n\n", loadavg().c_str());
    std::fflush(stdout);
  };
  try {
    if (opt.shared && opt.unbonded) section([&] { section_shared(opt, false); });
    if (opt.shared && opt.parallel) section([&] { section_shared(opt, true); });
    if (opt.shared && opt.cpm) section([&] { section_shared(opt, true, true); });
    if (opt.scaling) section([&] { section_scaling(opt); });
    if (opt.effects) section([&] { section_effects(opt); });
    if (opt.deposition) section([&] { section_deposition(opt); });
  } catch (const std::exception& e) {
    std::fprintf(stderr, "throughput: %s\n", e.what());
    return 1;
  }
  std::printf("Total run time %.0f s.\n", std::chrono::duration<double>(Clock::now() - t0).count());
  return 0;
}
