#include "studies/calibration.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "engine/errors.hpp"
#include "scene/scene.hpp"
#include "scene/toml_reader.hpp"
#include "studies/calibration_run.hpp"
#include "studies/runner.hpp"

namespace mc {

using namespace calibration;

CalibrationTarget parse_targets(const std::string& text) {
  // Each "name=value" becomes a TOML line, so units and ranges are checked by the scene reader's own rules.
  std::string toml;
  std::istringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    const auto eq = item.find('=');
    if (eq == std::string::npos)
      throw InputError("--target '" + item + "': give name=value, e.g. E=30GPa,nu=0.2,ucs=40MPa");
    auto trim = [](std::string s) {
      s.erase(0, s.find_first_not_of(" \t"));
      s.erase(s.find_last_not_of(" \t") + 1);
      return s;
    };
    const std::string key = trim(item.substr(0, eq)), value = trim(item.substr(eq + 1));
    const bool number = !value.empty() && value.find_first_not_of("0123456789.eE+-") == std::string::npos;
    toml += key + " = " + (number ? value : "\"" + value + "\"") + "\n";
  }
  try {
    const TomlDoc doc = TomlDoc::parse_text(toml, "--target");
    const Table t = doc.root();
    CalibrationTarget c;
    c.modulus = t.number("E", Unit::Pressure, Range::positive(), kNaN);
    c.poisson = t.number("nu", Unit::None, Range{0.0, 0.5, true, true}, kNaN);
    c.ucs = t.number("ucs", Unit::Pressure, Range::positive(), kNaN);
    c.tensile = t.number("ft", Unit::Pressure, Range::positive(), kNaN);
    c.compressive = t.number("fc", Unit::Pressure, Range::positive(), kNaN);
    t.finish();
    if (std::isnan(c.modulus) && std::isnan(c.poisson) && std::isnan(c.ucs) && std::isnan(c.tensile) &&
        std::isnan(c.compressive))
      throw InputError("--target '" + text + "': name at least one of E, nu, ucs, ft, fc");
    return c;
  } catch (const InputError& e) {
    throw InputError(std::string(e.what()) +
                     " (allowed targets: E [Pa], nu in (0, 0.5), and ucs [Pa] for parallel_bond scenes or ft, fc "
                     "[Pa] for cpm scenes)");
  }
}

namespace {

// The micro-parameters being calibrated, as factors on the scene's own values.
struct Knobs {
  double modulus = 1;   // E_c and Ē_c, both times this
  double ratio = 0;     // k_n/k_s of the grains (the bonds' ratio keeps its proportion to it)
  double strength = 1;  // every bond strength (means and spreads) times this
};

// What the scene's parallel-bond entry holds.
struct Entry {
  int index = -1;
  double modulus = 0, bond_modulus = 0, ratio = 1, bond_ratio = 1;
  std::vector<std::pair<std::string, double>> strengths;  // key → value [Pa]
};

Entry find_entry(const std::string& scene_file, const std::vector<std::string>& overrides, int index) {
  const TomlDoc doc = TomlDoc::load(scene_file, overrides);
  const Table t = doc.root().tables("contacts")[static_cast<std::size_t>(index)];
  Entry e;
  e.index = index;
  e.modulus = t.number("modulus", Unit::Pressure, Range::positive());
  e.bond_modulus = t.number("bond_modulus", Unit::Pressure, Range::positive());
  e.ratio = t.number("kn_ks_ratio", Unit::None, Range::positive(), 1.0);
  e.bond_ratio = t.number("bond_kn_ks_ratio", Unit::None, Range::positive(), 1.0);
  for (const char* k :
       {"bond_tensile_strength", "bond_tensile_strength_std", "bond_shear_strength", "bond_shear_strength_std"})
    if (t.has(k)) e.strengths.push_back({k, t.number(k, Unit::Pressure, Range::non_negative())});
  return e;
}

std::string set(const Entry& e, const std::string& key, double v) { return set_key(e.index, key, v); }

std::vector<std::string> knob_overrides(const Entry& e, const Knobs& k, double strength) {
  std::vector<std::string> o{set(e, "modulus", e.modulus * k.modulus),
                             set(e, "bond_modulus", e.bond_modulus * k.modulus), set(e, "kn_ks_ratio", k.ratio),
                             set(e, "bond_kn_ks_ratio", e.bond_ratio / e.ratio * k.ratio)};
  for (const auto& [key, v] : e.strengths) o.push_back(set(e, key, v * strength));
  return o;
}

// E/E_c as a function of k_n/k_s, Tang (6.2) for 2D and (6.3) for 3D: used only to predict how a change of the
// ratio moves E, so that E_c can be corrected for it in the same iteration.
double modulus_shape(int dimension, double ratio) {
  return dimension == 2 ? 1.57 - 0.42 * std::log(ratio) : 1.36 - 0.39 * std::log(ratio);
}

// One run of the calibration: what it used, what it gave, how long it took.
struct Trial {
  UniaxialResult result;
  RunResult run;
  std::string file;
};

// Tang §6.3 as a loop of runs: elastic runs (bonds made strong) until E and ν match, then full runs until UCS does.
class Calibration {
 public:
  Calibration(const std::string& scene_file, const std::vector<std::string>& overrides, int entry,
              const CalibrationTarget& target, const CalibrationOptions& options, std::FILE* log)
      : scene_file_(scene_file),
        overrides_(overrides),
        target_(target),
        options_(options),
        log_(log),
        entry_(find_entry(scene_file, overrides, entry)),
        base_(read_scene(TomlDoc::load(scene_file, overrides), scene_file)) {
    if (!base_.analysis<UniaxialAnalysis>())
      throw InputError(scene_file + ": calibrate needs a [uniaxial] table: it matches the E, ν and UCS it reports");
    std::vector<std::string> outputs{options_.output, options_.output + ".tmp"};
    for (int it = 1; it <= options_.max_iterations; ++it)
      for (const auto& f : run_files(run_file(it))) outputs.push_back(f);
    refuse_inputs_as_outputs(base_, outputs);
    knobs_.ratio = entry_.ratio;
    elastic_ = elastic_targets();
    // The elastic runs stop at half the target's elastic strain at the peak: far enough for the secant between
    // 25 % and 50 % of their last stress, and a fraction of a full test's steps.
    elastic_stop_ = strength_target() && elastic_targets() ? 0.5 * target.ucs / target.modulus : 5e-4;
  }

  CalibrationResult run() {
    std::fprintf(log_, "%3s %-8s %10s %7s %9s | %9s %7s %9s | %s\n", "it", "run", "E_c [GPa]", "kn/ks", "strength",
                 "E [GPa]", "nu", "UCS [MPa]", "wall [s]");
    Knobs ran = knobs_;  // what the last run used: the calibrated scene gets these, never untested values
    for (int it = 1; it <= options_.max_iterations; ++it) {
      ran = knobs_;
      const Trial t = trial(it);
      const UniaxialResult& u = t.result;
      res_.iterations = it;
      const bool e_ok = !elastic_targets() || (rel(u.modulus, target_.modulus) <= options_.tolerance &&
                                               rel(u.poisson, target_.poisson) <= options_.tolerance);
      if (!elastic_) res_.last = u;
      if (elastic_ && e_ok && strength_target()) {  // the stiffnesses are found: now the strengths, in full tests
        elastic_ = false;
        continue;
      }
      const bool s_ok = !strength_target() || (!elastic_ && rel(u.ucs, target_.ucs) <= options_.tolerance);
      if (e_ok && s_ok) {
        if (elastic_) res_.last = u;
        res_.converged = true;
        break;
      }
      if (!e_ok) adjust_stiffness(u);
      if (!elastic_ && strength_target() && rel(u.ucs, target_.ucs) > options_.tolerance)
        knobs_.strength *= target_.ucs / u.ucs;  // UCS in proportion to the bond strengths at fixed strength ratio
    }
    res_.overrides = knob_overrides(entry_, ran, ran.strength);
    write_scene(scene_file_, with_user_overrides(res_.overrides), options_.output);
    return res_;
  }

 private:
  bool elastic_targets() const { return !std::isnan(target_.modulus); }
  bool strength_target() const { return !std::isnan(target_.ucs); }

  // Run `it` with the current knobs (an elastic run: bonds 1000× stronger, stopped early), logged as a line.
  Trial trial(int it) {
    constexpr double strong = 1e3;  // bond strengths times this cannot break in the elastic runs
    std::vector<std::string> o = overrides_;
    const std::vector<std::string> knobs =
        knob_overrides(entry_, knobs_, elastic_ ? knobs_.strength * strong : knobs_.strength);
    o.insert(o.end(), knobs.begin(), knobs.end());
    Scene scene = read_scene(TomlDoc::load(scene_file_, o), scene_file_);
    if (elastic_)
      scene.stops = {StopSpec{scene.analysis<UniaxialAnalysis>()->axial_strain, StopSpec::Kind::MagnitudeAbove,
                              elastic_stop_, 0.0}};
    RunOptions ro;
    ro.output = run_file(it);
    Trial t{{}, run_scene(scene, ro), ro.output};
    t.result = uniaxial_result(ro.output);
    const UniaxialResult& u = t.result;
    char ucs[32] = "-";  // an elastic run has no peak
    if (!elastic_) std::snprintf(ucs, sizeof ucs, "%.4g", u.ucs * 1e-6);
    std::fprintf(log_, "%3d %-8s %10.4g %7.4g %9.4g | %9.4g %7.4g %9s | %.1f\n", it, elastic_ ? "elastic" : "full",
                 entry_.modulus * knobs_.modulus * 1e-9, knobs_.ratio, knobs_.strength, u.modulus * 1e-9, u.poisson,
                 ucs, t.run.wall_seconds);
    std::fflush(log_);
    if (!std::isfinite(u.modulus) || !std::isfinite(u.poisson) || (!elastic_ && !std::isfinite(u.ucs)))
      throw InputError(t.file + ": the uniaxial test gave no E, ν or UCS (" + t.run.status +
                       "); check that the scene loads the specimen to its peak");
    return t;
  }

  // ν through k_n/k_s on its logarithmic law (6.2)/(6.3), with the slope the last two runs measured when they tell
  // one; E through E_c (linear, 6.1), corrected for what the new ratio does to E/E_c.
  void adjust_stiffness(const UniaxialResult& u) {
    const double lnr = std::log(knobs_.ratio);
    if (std::isfinite(prev_lnr_) && std::abs(lnr - prev_lnr_) > 1e-3) {
      const double measured = (u.poisson - prev_nu_) / (lnr - prev_lnr_);
      if (measured > 0.02 && measured < 0.5) slope_ = measured;
    }
    prev_lnr_ = lnr, prev_nu_ = u.poisson;
    const double ratio = std::clamp(std::exp(lnr + (target_.poisson - u.poisson) / slope_), 0.25, 20.0);
    if (ratio == knobs_.ratio)
      throw InputError("calibrate: ν = " + std::to_string(target_.poisson) +
                       " is out of reach for this packing: "
                       "k_n/k_s at its bound " +
                       std::to_string(ratio) + " gives ν = " + std::to_string(u.poisson));
    const int d = base_.dimension;
    knobs_.modulus *= target_.modulus / u.modulus * modulus_shape(d, knobs_.ratio) / modulus_shape(d, ratio);
    knobs_.ratio = ratio;
  }

  std::string run_file(int it) const { return calibration::run_file(options_.output, it); }

  std::vector<std::string> with_user_overrides(const std::vector<std::string>& knobs) const {
    std::vector<std::string> all = overrides_;
    all.insert(all.end(), knobs.begin(), knobs.end());
    return all;
  }

  const std::string scene_file_;
  const std::vector<std::string> overrides_;
  const CalibrationTarget target_;
  const CalibrationOptions options_;
  std::FILE* log_;
  const Entry entry_;
  const Scene base_;
  Knobs knobs_;
  bool elastic_ = false;
  double elastic_stop_ = 5e-4;
  double slope_ = 0.11;  // dν/d ln(k_n/k_s), Tang (6.2) and (6.3); replaced by what the runs measure
  double prev_lnr_ = kNaN, prev_nu_ = kNaN;
  CalibrationResult res_;
};

}  // namespace

// Which procedure: the scene's calibrated [[contacts]] entry decides, and the targets must be ones it can reach.
CalibrationResult calibrate(const std::string& scene_file, const std::vector<std::string>& overrides,
                            const CalibrationTarget& target, const CalibrationOptions& options, std::FILE* log) {
  if (options.output.empty()) throw InputError("calibrate: give the calibrated scene's file with -o CALIBRATED.toml");
  const TomlDoc doc = TomlDoc::load(scene_file, overrides);
  const int bonded = contacts_entry(doc, "parallel_bond"), cpm = contacts_entry(doc, "cpm");
  if ((bonded >= 0) == (cpm >= 0))
    throw InputError(scene_file +
                     ": calibrate needs one [[contacts]] entry with model = \"parallel_bond\" (Tang §6.3) or "
                     "model = \"cpm\" (Šmilauer, \"Parameter calibration\")" +
                     (bonded >= 0 ? "; this scene has both: calibrate each material in its own scene" : ""));
  auto refuse = [&](double value, const char* name, const char* model, const char* allowed) {
    if (!std::isnan(value))
      throw InputError("--target " + std::string(name) + ": not a target for a " + model +
                       " scene (its targets: " + allowed + ")");
  };
  CalibrationOptions o = options;
  if (cpm >= 0) {
    refuse(target.ucs, "ucs", "cpm", "E, nu, ft, fc; its compressive strength is fc");
    if (std::isnan(o.tolerance)) o.tolerance = 0.03;
    return calibrate_cpm(scene_file, overrides, cpm, target, o, log);
  }
  refuse(target.tensile, "ft", "parallel_bond", "E with nu, ucs");
  refuse(target.compressive, "fc", "parallel_bond", "E with nu, ucs; its compressive strength is ucs");
  if (std::isnan(target.modulus) != std::isnan(target.poisson))
    throw InputError("--target: give E and nu together for a parallel_bond scene (both depend on E_c and k_n/k_s, "
                     "Tang §6.3)");
  if (!o.compression_scene.empty())
    throw InputError("--compression: only for cpm scenes with an fc target; a parallel_bond scene is calibrated in "
                     "its own compression test");
  if (std::isnan(o.tolerance)) o.tolerance = 0.05;
  return Calibration(scene_file, overrides, bonded, target, o, log).run();
}

namespace calibration {

int contacts_entry(const TomlDoc& doc, const std::string& model) {
  const std::vector<Table> contacts = doc.root().tables("contacts");
  int found = -1;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    if (contacts[i].string("model", "") != model) continue;
    if (found >= 0)
      contacts[i].fail("model", "calibrate works on one " + model + " phase pair; this scene has several [[contacts]] "
                                "with model = \"" + model + "\" (calibrate each material in its own scene)");
    found = static_cast<int>(i);
  }
  return found;
}

std::string set_key(int index, const std::string& key, double value) {
  char b[64];
  std::snprintf(b, sizeof b, "%.8g", value);
  return "contacts[" + std::to_string(index) + "]." + key + "=" + b;
}

std::string run_file(const std::string& output, int iteration, const std::string& suffix) {
  const std::filesystem::path out(output);
  return (out.parent_path() / (out.stem().string() + "_it" + std::to_string(iteration) + suffix + ".h5")).string();
}

void write_scene(const std::string& scene_file, const std::vector<std::string>& overrides, const std::string& output) {
  const std::string text = TomlDoc::load(scene_file, overrides).text();
  const std::string tmp = output + ".tmp";
  {
    std::ofstream f(tmp);
    f << text;
    if (!f) throw IoError(tmp + ": cannot write the calibrated scene");
  }
  std::filesystem::rename(tmp, output);
}

}  // namespace calibration

}  // namespace mc
