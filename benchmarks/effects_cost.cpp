// What each optional effect costs: the same scene run with and without one declaration, through the full
// runner (histories, output file and all), on the shared 3D specimen (benchmarks/specimens/README.md).
// Prints the ratio of wall times (with / without); "nothing declared" is run twice to show the noise.
// Usage: effects_cost [--specimen FILE] [--steps N]
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "benchmarks/options.hpp"
#include "scene/scene.hpp"
#include "scene/toml_reader.hpp"
#include "studies/runner.hpp"

namespace {

std::string base_scene(const std::string& specimen, long steps) {
  return R"(
title = "effects cost"
dimension = 3
[[phases]]
name = "concrete"
density = 2600
[[contacts]]
phase_a = "concrete"
model = "linear"
modulus = 30e9
friction = 0.5
[specimen]
kind = "sphere_list"
file = ")" +
         specimen + R"("
[[groups]]
name = "bottom"
tags = [1]
fix = "all"
[[groups]]
name = "top"
tags = [2]
fix = "all"
velocity = [0, 0, -0.04]
[timestep]
safety = 0.8
[run]
steps = )" +
         std::to_string(steps) + R"(
[output]
history_every = 1000000
checkpoint_every = 100000000
)";
}

double run_once(const std::string& text, const std::vector<std::string>& sets, const std::string& out) {
  const mc::Scene scene = mc::read_scene(mc::TomlDoc::parse_text(text, "effects.toml", sets), "effects.toml");
  mc::RunOptions opt;
  opt.output = out;
  opt.progress = false;
  const auto t0 = std::chrono::steady_clock::now();
  mc::run_scene(scene, opt);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  std::string specimen = MESOCRACK_SPECIMEN_DIR "/n10k.spheres";
  long steps = 2000;
  CLI::App app{"effects_cost: what each optional effect costs, as the ratio of wall times with and without it"};
  app.add_option("--specimen", specimen, "a .spheres specimen file")->check(CLI::ExistingFile);
  app.add_option("--steps", steps, "steps of each run")->check(CLI::Range(1L, 100000000L));
  if (const auto code = mc::bench::read_options(app, argc, argv, "effects_cost")) return *code;
  specimen = std::filesystem::absolute(specimen).string();
  const std::string text = base_scene(specimen, steps);
  const std::string out = (std::filesystem::temp_directory_path() / "mesocrack_effects.h5").string();
  struct Variant {
    const char* name;
    std::vector<std::string> sets;
  };
  const std::vector<Variant> variants = {
      {"nothing declared (repeat)", {}},
      {"gravity", {"physics.gravity=[0, 0, -9.81]"}},
      {"local damping 0.7", {"physics.local_damping=0.7"}},
      {"viscous dashpots ζ = 0.1", {"contacts[0].damping_ratio=0.1"}},
      {"energy tracing (recorded every 100 steps)", {"physics.energy=true", "output.history_every=100"}},
      {"measurement sphere: stress, porosity, coordination / 100 steps",
       {"measure=[{name=\"c\", centre=[0.05,0.05,0.1], radius=0.04, porosity=true, coordination=true}]",
        "output.history_every=100"}},
      {"measurement sphere with strain (every step)",
       {"measure=[{name=\"c\", centre=[0.05,0.05,0.1], radius=0.04, strain=true}]"}},
      {"histories every 10 steps", {"output.history_every=10"}},
      {"frames every 200 steps", {"output.frame_every=200"}},
  };
  std::printf("# Cost of optional effects: %s, %ld steps, %d threads\n", specimen.c_str(), steps,
              omp_get_max_threads());
  std::printf("| effect declared | wall time [s] | ratio to nothing declared |\n|---|---|---|\n");
  // Best of three for each: the machine is shared and noisy.
  auto best = [&](const std::vector<std::string>& sets) {
    double t = 1e300;
    for (int r = 0; r < 3; ++r) t = std::min(t, run_once(text, sets, out));
    return t;
  };
  const double base = best({});
  std::printf("| nothing declared | %.3f | 1.000 |\n", base);
  for (const auto& v : variants) {
    const double t = best(v.sets);
    std::printf("| %s | %.3f | %.3f |\n", v.name, t, t / base);
    std::fflush(stdout);
  }
  std::filesystem::remove(out);
  return 0;
}
