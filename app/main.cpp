// The `mesocrack` command: run a scene, summarise a run, draw its report.
// Exit status: 0 success, 2 bad input, 3 file error, 4 unstable run, 5 calibration not converged, 1 anything else.
#include <omp.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "engine/errors.hpp"
#include "scene/scene.hpp"
#include "scene/toml_reader.hpp"
#include "studies/calibration.hpp"
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

int run(const std::string& scene_file, std::string output, const std::vector<std::string>& sets, int threads,
        const std::string& resume) {
  if (!resume.empty()) {
    if (!output.empty() && std::filesystem::path(output) != std::filesystem::path(resume))
      throw mc::InputError("--resume " + resume + " continues that file; -o " + output +
                           " must name the same file or be left out");
    output = resume;
  }
  if (output.empty()) throw mc::InputError("run: give the output file with -o OUT.h5");
  if (threads > 0) omp_set_num_threads(threads);
  // Everything is read and validated before the output file is touched: bad input leaves no half-written file.
  const mc::Scene scene = mc::read_scene(mc::TomlDoc::load(scene_file, sets), scene_file);
  mc::RunOptions opt;
  opt.output = output;
  opt.resume = !resume.empty();
  const mc::RunResult r = mc::run_scene(scene, opt);
  std::fprintf(stderr, "%s after %lld steps, t = %.6g s, %.1f s wall time -> %s\n", r.status.c_str(),
               static_cast<long long>(r.steps), r.time, r.wall_seconds, output.c_str());
  return 0;
}

// N packings of one scene (seeds seed … seed + N − 1): one output file each, and their statistics as JSON, printed
// and saved beside them as <stem>_realizations.json.
int realizations(const std::string& scene_file, const std::string& output, const std::vector<std::string>& sets,
                 int threads, int n) {
  if (output.empty())
    throw mc::InputError("run --realizations: give the output file with -o OUT.h5 (realization k writes OUT_rk.h5)");
  if (threads > 0) omp_set_num_threads(threads);
  const mc::RealizationSet set = mc::run_realizations(scene_file, sets, n, output, stderr);
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
              int threads, const std::string& targets, double tolerance, int max_iterations) {
  if (threads > 0) omp_set_num_threads(threads);
  const mc::CalibrationTarget target = mc::parse_targets(targets);
  mc::CalibrationOptions opt;
  opt.output = output;
  opt.tolerance = tolerance;
  opt.max_iterations = max_iterations;
  const mc::CalibrationResult r = mc::calibrate(scene_file, sets, target, opt, stderr);
  std::fprintf(stderr, "%s after %d iterations; calibrated scene -> %s\n", r.converged ? "converged" : "NOT converged",
               r.iterations, output.c_str());
  for (const auto& o : r.overrides) std::printf("%s\n", o.c_str());
  return r.converged ? 0 : 5;
}

int report(const std::string& file) {
  const std::string cmd = "/usr/bin/python3 " + shell_quote(report_script()) + " " + shell_quote(file);
  const int rc = std::system(cmd.c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : 1;
}

int generate(const std::string& scene_file, const std::string& output, const std::vector<std::string>& sets,
             int threads) {
  if (output.empty()) throw mc::InputError("generate: give the specimen file with -o SPECIMEN.h5");
  if (threads > 0) omp_set_num_threads(threads);
  const mc::Scene scene = mc::read_scene(mc::TomlDoc::load(scene_file, sets), scene_file);
  for (const auto& [name, value] : mc::generate_specimen(scene, output))
    std::fprintf(stderr, "%s = %.6g\n", name.c_str(), value);
  std::fprintf(stderr, "specimen -> %s\n", output.c_str());
  return report(output);  // the picture: particles by phase, aggregate outlines
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
  CLI::App app{"mesocrack: meso-scale discrete element modelling of concrete fracture"};
  app.require_subcommand(1);
  std::string scene, output, resume, target;
  std::vector<std::string> sets;
  int threads = 0, n_realizations = 1, max_iterations = 12;
  double tolerance = 0.05;
  std::string targets;
  auto* run_cmd = app.add_subcommand("run", "run a scene");
  run_cmd->add_option("scene", scene, "scene file (TOML)")->required();
  run_cmd->add_option("-o,--output", output, "output file (HDF5)");
  run_cmd->add_option("--set", sets, "override a scene value: key.path=value (repeatable)");
  run_cmd->add_option("--threads", threads, "OpenMP threads (default: all cores)")->check(CLI::PositiveNumber);
  run_cmd->add_option("--resume", resume, "continue this output file from its last checkpoint");
  run_cmd
      ->add_option("--realizations", n_realizations,
                   "run N packings (seeds seed..seed+N-1) into OUT_rK.h5 and report mean, std and CV of E, nu, UCS")
      ->check(CLI::PositiveNumber)
      ->excludes("--resume");
  auto* calibrate_cmd = app.add_subcommand("calibrate", "find micro-parameters matching target E, nu, UCS (Tang 6.3)");
  calibrate_cmd->add_option("scene", scene, "scene file (TOML) with one parallel_bond contact entry and [uniaxial]")
      ->required();
  calibrate_cmd->add_option("--target", targets, "targets, e.g. E=30GPa,nu=0.2,ucs=40MPa")->required();
  calibrate_cmd->add_option("-o,--output", output, "the calibrated scene (TOML); its runs are written beside it")
      ->required();
  calibrate_cmd->add_option("--tolerance", tolerance, "relative tolerance on each target (default 0.05)")
      ->check(CLI::Range(1e-4, 0.5));
  calibrate_cmd->add_option("--max-iterations", max_iterations, "give up after this many runs (default 12)")
      ->check(CLI::Range(1, 100));
  calibrate_cmd->add_option("--set", sets, "override a scene value: key.path=value (repeatable)");
  calibrate_cmd->add_option("--threads", threads, "OpenMP threads (default: all cores)")->check(CLI::PositiveNumber);
  auto* generate_cmd = app.add_subcommand("generate", "build a scene's specimen (e.g. a dense packing) and save it");
  generate_cmd->add_option("scene", scene, "scene file (TOML)")->required();
  generate_cmd->add_option("-o,--output", output, "specimen file (HDF5; scenes load it with kind = \"output\")");
  generate_cmd->add_option("--set", sets, "override a scene value: key.path=value (repeatable)");
  generate_cmd->add_option("--threads", threads, "OpenMP threads (default: all cores)")->check(CLI::PositiveNumber);
  auto* summary_cmd = app.add_subcommand("summary", "print the key results of a run as JSON");
  summary_cmd->add_option("output", target, "output file (HDF5)")->required();
  auto* report_cmd = app.add_subcommand("report", "write PNG plots of a run next to its output file");
  report_cmd->add_option("output", target, "output file (HDF5)")->required();
  CLI11_PARSE(app, argc, argv);
  try {
    if (*run_cmd && n_realizations > 1) return realizations(scene, output, sets, threads, n_realizations);
    if (*run_cmd) return run(scene, output, sets, threads, resume);
    if (*calibrate_cmd) return calibrate(scene, output, sets, threads, targets, tolerance, max_iterations);
    if (*generate_cmd) return generate(scene, output, sets, threads);
    if (*summary_cmd) {
      std::cout << mc::summary_json(target);
      return 0;
    }
    if (*report_cmd) return report(target);
  } catch (const mc::InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const mc::IoError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 3;
  } catch (const mc::InstabilityError& e) {
    std::fprintf(stderr, "\nerror: %s\n", e.what());
    return 4;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
