// Tang's calibration of a parallel-bonded specimen (§6.3) as a loop of runs of the scene's uniaxial compression
// test: elastic runs (bonds made strong) until E and ν match, then full runs until UCS does.
#include <algorithm>
#include <cmath>

#include "engine/errors.hpp"
#include "scene/scene.hpp"
#include "scene/toml_reader.hpp"
#include "studies/calibration_run.hpp"
#include "studies/runner.hpp"

namespace mc::calibration {

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

CalibrationResult calibrate_bonded(const std::string& scene_file, const std::vector<std::string>& overrides, int entry,
                                   const CalibrationTarget& target, const CalibrationOptions& options,
                                   std::FILE* log) {
  return Calibration(scene_file, overrides, entry, target, options, log).run();
}

}  // namespace mc::calibration
