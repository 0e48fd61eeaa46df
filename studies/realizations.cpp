#include "studies/realizations.hpp"

#include <cmath>
#include <filesystem>
#include <sstream>

#include "engine/errors.hpp"
#include "scene/json.hpp"
#include "scene/scene.hpp"
#include "scene/toml_reader.hpp"
#include "studies/ranks.hpp"
#include "studies/runner.hpp"

namespace mc {

Statistic statistic(const std::vector<double>& x) {
  Statistic s;
  if (x.empty()) return s;
  double sum = 0;
  for (double v : x) sum += v;
  s.mean = sum / static_cast<double>(x.size());
  if (x.size() < 2) return s;
  double ss = 0;
  for (double v : x) ss += (v - s.mean) * (v - s.mean);
  s.std = std::sqrt(ss / static_cast<double>(x.size() - 1));
  s.cv = s.std / std::abs(s.mean);
  return s;
}

std::string realization_file(const std::string& output, int k) {
  const std::filesystem::path p(output);
  return (p.parent_path() / (p.stem().string() + "_r" + std::to_string(k) + p.extension().string())).string();
}

RealizationSet run_realizations(const std::string& scene_file, const std::vector<std::string>& overrides, int n,
                                const std::string& output, std::FILE* log) {
  if (n < 1) throw InputError("--realizations " + std::to_string(n) + ": give 1 or more");
  // Read and validate once, before any output exists.
  const Scene base = read_scene(TomlDoc::load(scene_file, overrides), scene_file);
  if (!base.analysis<UniaxialAnalysis>())
    throw InputError(scene_file +
                     ": --realizations needs a [uniaxial] table: it compares E, ν and UCS across packings");
  // Every realization's files and the statistics (which the command writes to <stem>_realizations.json).
  std::vector<std::string> outputs;
  for (int k = 0; k < n; ++k)
    for (const auto& f : run_files(realization_file(output, k))) outputs.push_back(f);
  const std::filesystem::path p(output);
  const std::string json = (p.parent_path() / (p.stem().string() + "_realizations.json")).string();
  outputs.insert(outputs.end(), {json, json + ".tmp"});
  refuse_unsafe_outputs(base, outputs);
  // Under mpirun each rank runs its share (Ranks::share) with its own threads: each run is the serial command's
  // run for its seed, so rank 0's statistics are the serial ones, bit for bit.
  const Ranks& ranks = Ranks::world();
  struct Record {
    UniaxialResult result;
    double wall_seconds;
  };
  if (ranks.root())
    std::fprintf(log, "%4s %12s %10s %8s %10s %10s %9s\n", "k", "seed", "E [GPa]", "nu", "UCS [MPa]", "init/UCS",
                 "wall [s]");
  auto seed_of = [&](int k) { return base.seed + static_cast<std::uint64_t>(k); };
  const auto records = share_values<Record>(ranks, n, [&](int k) {
    std::vector<std::string> o = overrides;
    o.push_back("seed=" + std::to_string(seed_of(k)));
    const Scene scene = read_scene(TomlDoc::load(scene_file, o), scene_file);
    RunOptions opt;
    opt.output = realization_file(output, k);
    const RunResult r = run_scene(scene, opt);
    const Record rec{uniaxial_result(opt.output), r.wall_seconds};
    const UniaxialResult& u = rec.result;
    std::fprintf(log, "%4d %12llu %10.4g %8.4g %10.4g %10.3g %9.1f\n", k, static_cast<unsigned long long>(seed_of(k)),
                 u.modulus * 1e-9, u.poisson, u.ucs * 1e-6, u.initiation_stress / u.ucs, r.wall_seconds);
    std::fflush(log);
    return rec;
  });
  RealizationSet set;
  for (int k = 0; k < n; ++k) {
    const Record& rec = records[k];
    set.seeds.push_back(seed_of(k));
    set.files.push_back(realization_file(output, k));
    set.results.push_back(rec.result);
    set.wall_seconds.push_back(rec.wall_seconds);
  }
  return set;
}

std::string realizations_json(const RealizationSet& set) {
  struct Column {
    const char* name;
    double (*get)(const UniaxialResult&);
  };
  const Column cols[] = {
      {"E", [](const UniaxialResult& u) { return u.modulus; }},
      {"E_platens", [](const UniaxialResult& u) { return u.modulus_platens; }},
      {"E_inside", [](const UniaxialResult& u) { return u.modulus_inside; }},
      {"nu", [](const UniaxialResult& u) { return u.poisson; }},
      {"ucs", [](const UniaxialResult& u) { return u.ucs; }},
      {"strain_at_peak", [](const UniaxialResult& u) { return u.strain_at_peak; }},
      {"crack_initiation_ratio", [](const UniaxialResult& u) { return u.initiation_stress / u.ucs; }},
  };
  std::ostringstream o;
  o << "{\n  \"realizations\": [";
  for (std::size_t k = 0; k < set.results.size(); ++k) {
    o << (k ? "," : "") << "\n    {\"file\": \"" << set.files[k] << "\", \"seed\": " << set.seeds[k]
      << ", \"wall_seconds\": " << json_number(set.wall_seconds[k]);
    for (const Column& c : cols) o << ", \"" << c.name << "\": " << json_number(c.get(set.results[k]));
    o << "}";
  }
  o << "\n  ],\n  \"statistics\": {";
  bool first = true;
  for (const Column& c : cols) {
    std::vector<double> x;
    for (const auto& u : set.results) x.push_back(c.get(u));
    const Statistic s = statistic(x);
    o << (first ? "" : ",") << "\n    \"" << c.name << "\": {\"mean\": " << json_number(s.mean)
      << ", \"std\": " << json_number(s.std) << ", \"cv\": " << json_number(s.cv) << "}";
    first = false;
  }
  o << "\n  }\n}\n";
  return o.str();
}

}  // namespace mc
