// Time to read and validate a large scene file (TomlDoc::load + read_scene), versus its size, printed as a
// markdown table. Reading must be linear in the file: a scene may list hundreds of thousands of particles.
//
//  wide:       one table ([timestep]) with N keys besides its own: the reader refuses the first unknown one,
//              after parsing all and checking the table (the cost of one large table);
//  particles:  a valid scene with N [[specimen.particles]] sections, 3 keys each (about 85 bytes a particle:
//              50 MB is 600 000 particles);
//  one_line:   the same particles as one inline array on a single line (`particles = [{...}, {...}]`).
//
// Times are wall times of one process (std::chrono::steady_clock), best of `--repeat` (default 1) readings.
//
//   scene_reading [--kind wide|particles|one_line] [--sizes N,N,...] [--repeat R]
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "benchmarks/options.hpp"
#include "engine/errors.hpp"
#include "scene/scene.hpp"
#include "scene/toml_reader.hpp"

namespace {

using Clock = std::chrono::steady_clock;

// The scene around the particles; `extra` lines go into its [timestep] table.
std::string head(const std::string& extra = "") {
  return "dimension = 3\n[[phases]]\nname = \"grain\"\ndensity = \"2600 kg/m3\"\n[[contacts]]\nphase_a = \"grain\"\n"
         "model = \"linear\"\nmodulus = \"50 MPa\"\n[timestep]\nsafety = 0.05\n" +
         extra + "[run]\nduration = \"0.3 ms\"\n[specimen]\nkind = \"particles\"\n";
}

std::string particle(std::size_t k) {
  const double x = 0.003 * static_cast<double>(k % 1000), y = 0.003 * static_cast<double>(k / 1000);
  std::ostringstream o;
  o << "x = [" << x << ", " << y << ", \"0 mm\"]\nradius = \"1 mm\"\nvelocity = [0.05, 0, 0]\n";
  return o.str();
}

std::string wide(std::size_t n) {
  std::string extra;
  for (std::size_t k = 0; k < n; ++k) extra += "key_" + std::to_string(k) + " = " + std::to_string(k) + "\n";
  return head(extra) + "[[specimen.particles]]\n" + particle(0);
}

std::string particles(std::size_t n) {
  std::string text = head();
  for (std::size_t k = 0; k < n; ++k) text += "[[specimen.particles]]\n" + particle(k);
  return text;
}

std::string one_line(std::size_t n) {
  std::string text = head() + "particles = [";
  for (std::size_t k = 0; k < n; ++k) {
    std::string p = particle(k);
    std::replace(p.begin(), p.end(), '\n', ',');
    p.pop_back();
    text += (k ? ", {" : "{") + p + "}";
  }
  return text + "]\n";
}

struct Reading {
  double seconds = 0;
  std::string outcome;  // "valid: N particles" or the error
};

Reading read(const std::string& file) {
  const auto t0 = Clock::now();
  Reading r;
  try {
    const mc::Scene s = mc::read_scene(mc::TomlDoc::load(file), file);
    r.outcome = "valid: " + std::to_string(s.specimen.particles.size()) + " particles";
  } catch (const mc::InputError& e) {
    r.outcome = e.what();
  }
  r.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  if (r.outcome.size() > 70) r.outcome = r.outcome.substr(0, 70) + "...";
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  std::string kind = "wide";
  std::vector<std::size_t> sizes{10000, 20000, 40000};
  int repeat = 1;
  CLI::App app{"scene_reading: the time to read and check a large scene file, against its size"};
  app.add_option("--kind", kind, "what grows: one table's keys, particle sections, or one inline array")
      ->check(CLI::IsMember({"wide", "particles", "one_line"}));
  app.add_option("--sizes", sizes, "N,N,...: keys or particles of each file")
      ->delimiter(',')
      ->check(CLI::Range(std::size_t{1}, std::size_t{100000000}));
  app.add_option("--repeat", repeat, "readings of each file, the best kept")->check(CLI::Range(1, 100));
  if (const auto code = mc::bench::read_options(app, argc, argv, "scene_reading")) return *code;
  const auto dir = std::filesystem::temp_directory_path() / ("scene_reading_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  std::printf("| kind | N | MB | seconds | MB/s | outcome |\n|---|---|---|---|---|---|\n");
  for (const std::size_t n : sizes) {
    const std::string text = kind == "wide" ? wide(n) : kind == "particles" ? particles(n) : one_line(n);
    const std::string file = (dir / "scene.toml").string();
    std::ofstream(file, std::ios::binary) << text;
    Reading best;
    for (int r = 0; r < repeat; ++r) {
      const Reading x = read(file);
      if (r == 0 || x.seconds < best.seconds) best = x;
    }
    const double mb = static_cast<double>(text.size()) / 1e6;
    std::printf("| %s | %zu | %.1f | %.3f | %.1f | %s |\n", kind.c_str(), n, mb, best.seconds, mb / best.seconds,
                best.outcome.c_str());
    std::fflush(stdout);
  }
  std::filesystem::remove_all(dir);
  return 0;
}
