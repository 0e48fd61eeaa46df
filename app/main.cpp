// The `mesocrack` command: run a scene, summarise a run, draw its report.
// Exit status: 0 success, 2 bad input, 3 file error, 4 unstable run, 5 calibration not converged, 130 and 143 a run
// that Ctrl-C or SIGTERM ended with a checkpoint (run --resume continues it), 1 anything else.
#include <omp.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <charconv>
#include <csignal>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <limits>
#include <string>

#include "engine/errors.hpp"
#include "scene/key_reference.hpp"
#include "scene/scene.hpp"
#include "scene/toml_reader.hpp"
#include "studies/calibration.hpp"
#include "studies/model_code.hpp"
#include "studies/ranks.hpp"
#include "studies/realizations.hpp"
#include "studies/runner.hpp"
#include "studies/summary.hpp"

namespace {

// report.py lives beside an installed binary (../share/mesocrack) or in the source tree it was built from.
std::string report_script() {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path exe = fs::canonical("/proc/self/exe", ec);
  const fs::path installed = exe.parent_path() / ".." / "share" / "mesocrack" / "report.py";
  if (!ec && fs::exists(installed)) return installed.string();
  return std::string(MESOCRACK_SOURCE_DIR) + "/app/report.py";
}

std::string shell_quote(const std::string& s) {
  std::string o = "'";
  for (char c : s) o += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return o + "'";
}

// What reading the scene found suspicious but allowed, on stderr (rank 0 of an MPI launch).
void warn_about(const mc::Scene& scene) {
  if (!mc::Ranks::world().root()) return;
  for (const auto& w : scene.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
}

// The same for a scene a command reads again for each of its runs (calibrate, realizations): once, before them.
void warn_about(const std::string& scene_file, const std::vector<std::string>& sets) {
  warn_about(mc::read_scene(mc::TomlDoc::load(scene_file, sets), scene_file));
}

int run(const std::string& scene_file, std::string output, const std::vector<std::string>& sets, int threads,
        const std::string& resume, double rebalance) {
  if (!resume.empty()) {
    if (!output.empty() && std::filesystem::path(output) != std::filesystem::path(resume))
      throw mc::InputError("--resume " + resume + " continues that file; -o " + output +
                           " must name the same file or be left out");
    output = resume;
  }
  if (scene_file.empty() && resume.empty())
    throw mc::InputError("run: the scene file is required, or --resume OUT.h5 alone to continue a run from its file "
                         "(see mesocrack run --help)");
  if (output.empty()) throw mc::InputError("run: give the output file with -o OUT.h5");
  if (threads > 0) omp_set_num_threads(threads);
  // Everything is read and validated before the output file is touched: bad input leaves no half-written file.
  // `--resume OUT.h5` alone continues the scene the file stores (with any --set given now on top of it).
  const mc::Scene scene = scene_file.empty() ? mc::stored_scene(output, sets)
                                             : mc::read_scene(mc::TomlDoc::load(scene_file, sets), scene_file);
  warn_about(scene);
  mc::RunOptions opt;
  opt.output = output;
  opt.resume = !resume.empty();
  opt.imbalance_limit = rebalance;
  opt.catch_interrupts = true;
  // Under mpirun the ranks run the one specimen split across them; rank 0 writes the output and reports.
  const mc::Ranks& ranks = mc::Ranks::world();
  const mc::RanksExchange exchange(ranks);
  if (ranks.size() > 1) opt.exchange = &exchange;
  const mc::RunResult r = mc::run_scene(scene, opt);
  if (!ranks.root()) return r.signal ? 128 + r.signal : 0;
  const std::string status = r.signal ? r.status + " by " + (r.signal == SIGTERM ? "SIGTERM" : "SIGINT") : r.status;
  std::fprintf(stderr, "%s after %lld steps, t = %.6g s, %.1f s wall time -> %s", status.c_str(),
               static_cast<long long>(r.steps), r.time, r.wall_seconds, output.c_str());
  if (ranks.size() > 1)
    std::fprintf(stderr, " (split across %d ranks: %s%s)", ranks.size(), r.balance.c_str(),
                 rebalance > 0 ? "" : ", --rebalance not given");
  if (!r.cost.empty()) std::fprintf(stderr, " (%s)", r.cost.c_str());
  std::fputc('\n', stderr);
  if (r.signal) std::fprintf(stderr, "continue it with: mesocrack run --resume %s\n", output.c_str());
  return r.signal ? 128 + r.signal : 0;  // the shell's code for a program a signal ended: 130 Ctrl-C, 143 kill
}

// N packings of one scene (seeds seed … seed + N − 1): one output file each, and their statistics as JSON, printed
// and saved beside them as <stem>_realizations.json.
int realizations(const std::string& scene_file, const std::string& output, const std::vector<std::string>& sets,
                 int threads, int n) {
  if (output.empty())
    throw mc::InputError("run --realizations: give the output file with -o OUT.h5 (realization k writes OUT_rk.h5)");
  if (threads > 0) omp_set_num_threads(threads);
  warn_about(scene_file, sets);
  const mc::RealizationSet set = mc::run_realizations(scene_file, sets, n, output, stderr);
  if (!mc::Ranks::world().root()) return 0;  // another rank of an MPI launch: rank 0 writes the statistics
  const std::string json = mc::realizations_json(set);
  const std::filesystem::path p(output);
  const std::string file = (p.parent_path() / (p.stem().string() + "_realizations.json")).string();
  std::FILE* f = std::fopen((file + ".tmp").c_str(), "w");
  if (!f || std::fputs(json.c_str(), f) < 0 || std::fclose(f) != 0) throw mc::IoError(file + ": cannot write");
  std::filesystem::rename(file + ".tmp", file);
  std::cout << json;
  std::fprintf(stderr, "statistics -> %s\n", file.c_str());
  return 0;
}

int calibrate(const std::string& scene_file, const std::string& output, const std::vector<std::string>& sets,
              int threads, const std::string& targets, double tolerance, int max_iterations,
              const std::string& compression) {
  if (threads > 0) omp_set_num_threads(threads);
  const mc::CalibrationTarget target = mc::parse_targets(targets);
  warn_about(scene_file, sets);
  mc::CalibrationOptions opt;
  opt.output = output;
  opt.tolerance = tolerance;
  opt.max_iterations = max_iterations;
  opt.compression_scene = compression;
  // Under mpirun every rank iterates alike on the shared runs' numbers (studies/ranks.hpp); rank 0 reports.
  const bool root = mc::Ranks::world().root();
  std::FILE* quiet = root ? nullptr : std::fopen("/dev/null", "w");
  const mc::CalibrationResult r = mc::calibrate(scene_file, sets, target, opt, quiet ? quiet : stderr);
  if (quiet) std::fclose(quiet);
  if (!root) return r.converged ? 0 : 5;
  std::fprintf(stderr, "%s after %d iterations; calibrated scene -> %s\n", r.converged ? "converged" : "NOT converged",
               r.iterations, output.c_str());
  for (const auto& o : r.overrides) std::printf("%s\n", o.c_str());
  return r.converged ? 0 : 5;
}

// The plots mark what `summary` reads (E, the strength): its JSON goes to report.py in a temporary file. A file
// summary cannot read (damaged, killed while flushing) is drawn without them.
int report(const std::string& file) {
  std::string cmd = "/usr/bin/python3 " + shell_quote(report_script()) + " " + shell_quote(file);
  char summary[] = "/tmp/mesocrack_summary_XXXXXX";
  const int fd = mkstemp(summary);
  bool written = false;
  if (fd >= 0) {
    try {
      const std::string json = mc::summary_json(file);
      written = write(fd, json.data(), json.size()) == static_cast<ssize_t>(json.size());
    } catch (const std::exception&) {
    }
    close(fd);
    if (written) cmd += " --summary " + shell_quote(summary);
  }
  const int rc = std::system(cmd.c_str());
  if (fd >= 0) unlink(summary);
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : 1;
}

int generate(const std::string& scene_file, const std::string& output, const std::vector<std::string>& sets,
             int threads) {
  if (output.empty()) throw mc::InputError("generate: give the specimen file with -o SPECIMEN.h5");
  if (threads > 0) omp_set_num_threads(threads);
  const mc::Scene scene = mc::read_scene(mc::TomlDoc::load(scene_file, sets), scene_file);
  warn_about(scene);
  for (const auto& [name, value] : mc::generate_specimen(scene, output))
    std::fprintf(stderr, "%s = %.6g\n", name.c_str(), value);
  std::fprintf(stderr, "specimen -> %s\n", output.c_str());
  return report(output);  // the picture: particles by phase, aggregate outlines
}

// ---------------------------------------------------------------- the options' values

// An option's value: the validator's message follows CLI11's "--name: ", so it names the value and what is allowed.
std::string refused(const std::string& value, const std::string& allowed) {
  return "'" + value + "' is not allowed: " + allowed;
}

// A whole number from lo to hi; CLI11's own checks print ranges as full-width doubles and say nothing of the
// option's meaning.
CLI::Validator whole_number(long long lo, long long hi, const std::string& meaning) {
  const std::string allowed =
      "give a whole number " +
      (hi == std::numeric_limits<int>::max() ? ">= " + std::to_string(lo)
                                             : "from " + std::to_string(lo) + " to " + std::to_string(hi)) +
      " (" + meaning + ")";
  return CLI::Validator(
      [=](std::string& text) {
        long long n = 0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
        const bool whole = ec == std::errc{} && end == text.data() + text.size();
        return whole && n >= lo && n <= hi ? std::string() : refused(text, allowed);
      },
      "INT");
}

// A finite number from lo to hi (CLI::Range lets nan through: every comparison with it is false).
CLI::Validator finite_number(double lo, double hi, const std::string& meaning) {
  char range[64];
  std::snprintf(range, sizeof range, "from %g to %g", lo, hi);
  const std::string allowed = "give a number " + std::string(range) + " (" + meaning + ")";
  return CLI::Validator(
      [=](std::string& text) {
        double x = 0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), x);
        const bool number = ec == std::errc{} && end == text.data() + text.size() && std::isfinite(x);
        return number && x >= lo && x <= hi ? std::string() : refused(text, allowed);
      },
      "FLOAT");
}

constexpr int kAnyCount = std::numeric_limits<int>::max();

// ---------------------------------------------------------------- errors of the command line itself

constexpr const char* kSetHelp =
    "override a scene value: key.path=value (repeatable); a number without a unit is SI (walls[0].rate=\"5 mm/s\")";
constexpr const char* kCommands = "run, generate, calibrate, summary, report, keys, concrete";

// A first word that is no subcommand: CLI11 would only say that a subcommand is required.
bool unknown_command(int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return false;
  const std::string first = argv[1];
  for (const char* c : {"run", "generate", "calibrate", "summary", "report", "keys", "concrete"})
    if (first == c) return false;
  std::fprintf(stderr, "error: unknown command '%s'; allowed: %s (see mesocrack --help)\n", argv[1], kCommands);
  return true;
}

// --help (CLI11's exit code 0) prints the help; any other parse error is bad input: one line and exit 2, pointing
// to the help of the subcommand it concerns.
int command_line_error(const CLI::App& app, const CLI::ParseError& e) {
  if (e.get_exit_code() == 0) return app.exit(e);
  std::string message = e.what();
  std::replace(message.begin(), message.end(), '\n', ' ');
  const auto parsed = app.get_subcommands();
  if (dynamic_cast<const CLI::RequiredError*>(&e) && parsed.empty()) message += "; allowed: " + std::string(kCommands);
  const std::string help = "mesocrack " + (parsed.empty() ? "" : parsed.front()->get_name() + " ") + "--help";
  std::fprintf(stderr, "error: %s (see %s)\n", message.c_str(), help.c_str());
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  // Threads that spin while waiting at a barrier make a run many times slower as soon as anything else wants
  // the cores (measured: 2 threads at 0.16-0.19x of 1 under load, 1.06x with passive waiting). libgomp reads
  // the policy when it loads, so the command restarts itself once with it set; a user's own setting wins.
  if (!std::getenv("OMP_WAIT_POLICY")) {
    setenv("OMP_WAIT_POLICY", "PASSIVE", 1);
    execv("/proc/self/exe", argv);  // returns only on failure: then go on with the default policy
  }
  mc::Ranks::start(&argc, &argv);
  // A rank of an MPI launch that fails ends the launch: the others would wait for its share forever.
  auto failed = [](int code) {
    if (mc::Ranks::world().size() > 1) mc::Ranks::world().abort(code);
    return code;
  };
  constexpr int kMaxRealizations = 10000;
  CLI::App app{"mesocrack: meso-scale discrete element modelling of concrete fracture"};
  const CLI::Validator threads_check = whole_number(1, kAnyCount, "OpenMP threads; leave --threads out for all cores");
  app.require_subcommand(1);
  std::string scene, output, resume, target;
  std::vector<std::string> sets;
  int threads = 0, n_realizations = 1, max_iterations = 12;
  double tolerance = mc::kNaN;  // the procedure's default
  double rebalance = 0;         // never
  std::string targets, compression;
  auto* run_cmd = app.add_subcommand("run", "run a scene");
  run_cmd->add_option("scene", scene, "scene file (TOML); with --resume it may be left out (the file stores it)");
  run_cmd->add_option("-o,--output", output, "output file (HDF5)");
  run_cmd->add_option("--set", sets, kSetHelp);
  run_cmd->add_option("--threads", threads, "OpenMP threads (default: all cores)")->check(threads_check);
  run_cmd->add_option("--resume", resume, "continue this output file from its last checkpoint");
  run_cmd
      ->add_option("--rebalance", rebalance,
                   "under mpirun, one specimen split across the ranks: draw the regions afresh when the most loaded "
                   "rank owns this fraction more particles than the mean (default: never)")
      ->check(finite_number(1e-3, 10, "the imbalance that redraws the regions; 0.1 is 10 % over the mean"));
  run_cmd
      ->add_option("--realizations", n_realizations,
                   "run N packings (seeds seed..seed+N-1) into OUT_rK.h5 and report mean, std and CV of E, nu, UCS")
      // 10⁴ runs of the smallest shipped uniaxial scene (about 10 s each) are more than a day; the statistics'
      // standard error then is 0.7 % of a CV (1/√(2N)): a bound nobody reaches by intent, and each realization's
      // file name is listed and checked before the first runs (a few hundred bytes each).
      ->check(whole_number(1, kMaxRealizations, "the number of packings"))
      ->excludes("--resume")
      ->excludes("--rebalance");
  auto* calibrate_cmd = app.add_subcommand(
      "calibrate",
      "find micro-parameters matching target E, nu, UCS (bonds in compression, Tang 6.3), E, nu, ft, Gf (bonds in "
      "tension, Tang ch. 7) or E, nu, ft, fc (CPM, Smilauer)");
  calibrate_cmd
      ->add_option("scene", scene,
                   "scene file (TOML) with [uniaxial] and one parallel_bond (compression or tension), softening_bond "
                   "(tension) or cpm (tension) contact entry")
      ->required();
  calibrate_cmd
      ->add_option("--target", targets,
                   "targets, e.g. E=30GPa,nu=0.2,ucs=40MPa, E=35GPa,nu=0.16,ft=3.2MPa,Gf=170.4N/m, "
                   "E=30GPa,nu=0.2,ft=3MPa,fc=40MPa, or class=C30/37 (fib Model Code 2010: see mesocrack concrete)")
      ->required();
  calibrate_cmd->add_option("--compression", compression,
                            "cpm with an fc target: the compression test scene (same specimen and material entry)");
  calibrate_cmd->add_option("-o,--output", output, "the calibrated scene (TOML); its runs are written beside it")
      ->required();
  calibrate_cmd->add_option("--tolerance", tolerance, "relative tolerance on each target (default 0.05; cpm 0.03)")
      ->check(finite_number(1e-4, 0.5, "the relative tolerance on each target"));
  calibrate_cmd->add_option("--max-iterations", max_iterations, "give up after this many runs (default 12)")
      ->check(whole_number(1, 100, "the most calibration runs"));
  calibrate_cmd->add_option("--set", sets, kSetHelp);
  calibrate_cmd->add_option("--threads", threads, "OpenMP threads (default: all cores)")->check(threads_check);
  auto* generate_cmd = app.add_subcommand("generate", "build a scene's specimen (e.g. a dense packing) and save it");
  generate_cmd->add_option("scene", scene, "scene file (TOML)")->required();
  generate_cmd->add_option("-o,--output", output, "specimen file (HDF5; scenes load it with kind = \"output\")");
  generate_cmd->add_option("--set", sets, kSetHelp);
  generate_cmd->add_option("--threads", threads, "OpenMP threads (default: all cores)")->check(threads_check);
  auto* summary_cmd = app.add_subcommand("summary", "print the key results of a run as JSON");
  summary_cmd->add_option("output", target, "output file (HDF5)")->required();
  auto* report_cmd = app.add_subcommand("report", "write PNG plots of a run next to its output file");
  report_cmd->add_option("output", target, "output file (HDF5)")->required();
  auto* keys_cmd = app.add_subcommand("keys", "list the tables of a scene file, or the keys of one (their units, ranges, "
                                                "defaults and meaning)");
  std::string keys_table;
  bool markdown = false;
  keys_cmd->add_option("table", keys_table, "a table's name, e.g. walls, cpm, run.stop (none: the list of tables)");
  keys_cmd->add_flag("--markdown", markdown, "every table as Markdown (docs/keys.md)")->excludes("table");
  auto* concrete_cmd = app.add_subcommand(
      "concrete", "a concrete of a fib Model Code 2010 class: E, nu, f_t, f_c and G_F as calibrate's targets");
  std::string concrete_class, aggregate = "quartzite";
  concrete_cmd->add_option("class", concrete_class, "the strength class, e.g. C30/37 (C12/15 to C120/140)")->required();
  concrete_cmd->add_option("--aggregate", aggregate, "quartzite (default), basalt, limestone or sandstone (alpha_E)");
  if (unknown_command(argc, argv)) return 2;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return command_line_error(app, e);
  }
  try {
    if (*run_cmd && n_realizations > 1) return realizations(scene, output, sets, threads, n_realizations);
    if (*run_cmd) return run(scene, output, sets, threads, resume, rebalance);
    if (*calibrate_cmd) return calibrate(scene, output, sets, threads, targets, tolerance, max_iterations, compression);
    if (*generate_cmd) return generate(scene, output, sets, threads);
    if (*summary_cmd) {
      std::cout << mc::summary_json(target);
      return 0;
    }
    if (*report_cmd) return report(target);
    if (*concrete_cmd) {
      std::cout << mc::model_code_json(mc::model_code_concrete(concrete_class, aggregate));
      return 0;
    }
    if (*keys_cmd) {
      std::cout << (markdown ? mc::key_reference_markdown()
                             : keys_table.empty() ? mc::key_table_list() : mc::key_table_text(keys_table));
      return 0;
    }
  } catch (const mc::InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return failed(2);
  } catch (const mc::IoError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return failed(3);
  } catch (const mc::InstabilityError& e) {
    std::fprintf(stderr, "\nerror: %s\n", e.what());
    return failed(4);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return failed(1);
  }
  return 0;
}
