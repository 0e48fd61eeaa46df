// Šmilauer's "Parameter calibration" of the Concrete Particle Model (seed 002) as a loop of runs of the scene's
// uniaxial tension test, and of a compression test when f_c is a target:
//   elastic runs (never_damage, stopped early; "Measuring macroscopic elastic properties") until E and ν match:
//   k_T/k_N from ν by the microplane relation, k_N scaled by E*/E (radial scaling) with (25)'s k_T/k_N factor;
//   then full runs until every target matches: ε_0 scaled by f_t*/f_t (step 5: f_t = k_N ε_0 Ψ), tan φ from the
//   sampled f_c/f_t (step 4), the dimensionless c_T0/(k_T ε_0) and ε_f/ε_0 held (steps 1–2), and E, ν corrected
//   as in the elastic runs when the damage before the peak moved them.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <utility>

#include "contact_models/cpm_calibration.hpp"
#include "engine/errors.hpp"
#include "scene/model_registry.hpp"
#include "scene/scene.hpp"
#include "studies/calibration_run.hpp"
#include "studies/ranks.hpp"
#include "studies/runner.hpp"
#include "studies/stored_run.hpp"

namespace mc::calibration {

namespace {

namespace cc = cpm_calibration;

// The values the calibration moves; c_T0 follows from them.
struct CpmKnobs {
  double kn = 0, ratio = 0, eps0 = 0, tan_phi = 0;  // k_N [Pa], k_T/k_N, ε_0, tan φ
};

CpmKnobs knobs_of(const CpmParams& p) { return {p.modulus, p.kt_kn_ratio, p.crack_onset_strain, p.tan_friction}; }

// One run of an iteration: what its uniaxial test measured, and its wall time.
struct Ran {
  UniaxialResult result;
  double wall = 0;
};

// What one iteration measured: the tension test (E, ν, f_t) and, when f_c is a target, the compression test.
struct Measured {
  UniaxialResult tension;
  double fc = kNaN, wall = 0;
};

class CpmCalibration {
 public:
  CpmCalibration(const std::string& scene_file, const std::vector<std::string>& overrides, int entry,
                 const CalibrationTarget& target, const CalibrationOptions& options, std::FILE* log)
      : scene_file_(scene_file), overrides_(overrides), entry_(entry), target_(target), options_(options), log_(log) {
    const TomlDoc doc = TomlDoc::load(scene_file, overrides);
    const Scene base = read_scene(doc, scene_file);
    params_ = contact_params<Cpm>(doc, entry);
    knobs_ = knobs_of(params_);
    if (knobs_.ratio == 0)
      fail_contact_key<Cpm>(doc, entry, &CpmParams::kt_kn_ratio,
                            "is 0: calibrate holds c_T0/(k_T ε_0) (Šmilauer, calibration step 1), which needs k_T > 0");
    cohesion_ratio_ = params_.cohesion / (knobs_.ratio * knobs_.kn * knobs_.eps0);
    const auto* u = base.analysis<UniaxialAnalysis>();
    if (!u || !u->tension)
      throw InputError(scene_file +
                       ": calibrate runs a cpm scene as its uniaxial tension test (Šmilauer, \"Simulation setup\"): "
                       "give a scene with [uniaxial] loading = \"tension\", e.g. scenes/cpm_uniax_tension.toml");
    strain_ = u->axial_strain;
    check_targets();
    std::vector<std::string> outputs{options_.output, options_.output + ".tmp"};
    if (fc_target()) {
      compression_entry_ = check_compression_scene();
      outputs.push_back(compression_output());
      outputs.push_back(compression_output() + ".tmp");
    }
    for (int it = 1; it <= options_.max_iterations; ++it)
      for (const char* suffix : {"", "_compression"})
        for (const auto& f : run_files(run_file(options_.output, it, suffix))) outputs.push_back(f);
    refuse_unsafe_outputs(base, outputs);
    if (nu_target()) set_ratio(cc::kt_kn_from_poisson(target_.poisson));  // the microplane relation's first guess
    elastic_ = e_target() || nu_target();
    // Loaded to about the strain of the full test's peak, the elastic run's secant window (25–50 % of its last
    // stress) is that of the full test (25–50 % of the peak).
    elastic_stop_ = e_target() && ft_target() ? target_.tensile / target_.modulus : knobs_.eps0;
  }

  CalibrationResult run() {
    std::fprintf(log_, "%3s %-8s %9s %6s %9s %7s %10s | %7s %6s %9s %9s | %s\n", "it", "run", "k_N [GPa]", "kT/kN",
                 "eps0", "tan phi", "c_T0 [MPa]", "E [GPa]", "nu", "f_t [MPa]", "f_c [MPa]", "wall [s]");
    CpmKnobs ran = knobs_;  // what the last run used: the calibrated scene gets these, never untested values
    RunCost cost[2];  // of the elastic runs and of the full ones (to the peak: strain ε_0)
    for (int it = 1; it <= options_.max_iterations; ++it) {
      RunCost& c = cost[elastic_ ? 0 : 1];
      const double reach = elastic_ ? 1.0 : knobs_.eps0;
      if (c.beyond_bound(knobs_.kn, reach, elastic_ ? "elastic" : "full", log_)) break;
      ran = knobs_;
      const Measured m = elastic_ ? elastic_trial(it) : full_trial(it);
      c.ran(m.wall, knobs_.kn, reach);
      log_line(it, m);
      res_.iterations = it;
      if (elastic_) {
        if (elastic_ok(m.tension))
          elastic_ = false;  // the stiffnesses are found: the full tests check every target
        else
          adjust_stiffness(m.tension);
        continue;
      }
      res_.last = m.tension;
      if (elastic_ok(m.tension) && strengths_ok(m)) {
        res_.converged = true;
        break;
      }
      adjust(m);
    }
    res_.overrides = knob_overrides(entry_, params_, ran);
    write_scene(scene_file_, with_user_overrides(res_.overrides), options_.output);
    if (fc_target())
      write_scene(options_.compression_scene,
                  with_user_overrides(knob_overrides(compression_entry_, compression_params_, ran)),
                  compression_output());
    return res_;
  }

 private:
  bool e_target() const { return !std::isnan(target_.modulus); }
  bool nu_target() const { return !std::isnan(target_.poisson); }
  bool ft_target() const { return !std::isnan(target_.tensile); }
  bool fc_target() const { return !std::isnan(target_.compressive); }

  void check_targets() const {
    // ν = (1 − k_T/k_N)/(4 + k_T/k_N) reaches 1/4 only at k_T = 0, where c_T0 ∝ k_T ε_0 would vanish.
    if (nu_target() && target_.poisson >= 0.25)
      throw InputError("--target nu=" + std::to_string(target_.poisson) +
                       ": the CPM gives ν = (1 − k_T/k_N)/(4 + k_T/k_N) < 0.25 (k_T > 0; Šmilauer, \"Geometry and "
                       "elastic parameters\"); allowed: 0 < nu < 0.25");
    if (fc_target() && options_.compression_scene.empty())
      throw InputError(
          "--target fc: give the compression test with --compression SCENE.toml (the same specimen and "
          "cpm entry strained the other way, e.g. scenes/cpm_uniax_compression.toml)");
    if (!fc_target() && !options_.compression_scene.empty())
      throw InputError("--compression: only with an fc target (the compression test measures f_c)");
  }

  // The compression scene's cpm entry; it must be a compression test.
  int check_compression_scene() {
    const std::string& file = options_.compression_scene;
    const TomlDoc doc = TomlDoc::load(file, overrides_);
    const int entry = contacts_entry(doc, Cpm::name);
    if (entry < 0)
      throw InputError(file + ": --compression needs a scene with one [[contacts]] entry with model = \"cpm\"");
    const Scene s = read_scene(doc, file);
    const auto* u = s.analysis<UniaxialAnalysis>();
    if (!u || u->tension)
      throw InputError(file + ": --compression needs a scene with [uniaxial] loading = \"compression\"");
    compression_params_ = contact_params<Cpm>(doc, entry);
    return entry;
  }

  std::string compression_output() const {
    const std::filesystem::path out(options_.output);
    return (out.parent_path() / (out.stem().string() + "_compression" + out.extension().string())).string();
  }

  // The --set lines that give the scene's entry (whose parameters are `base`) the knobs `k`; elastic: damage off.
  std::vector<std::string> knob_overrides(int entry, const CpmParams& base, const CpmKnobs& k,
                                          bool elastic = false) const {
    CpmParams p = base;
    p.modulus = k.kn, p.kt_kn_ratio = k.ratio, p.crack_onset_strain = k.eps0, p.tan_friction = k.tan_phi;
    p.cohesion = cohesion(k);
    p.never_damage = p.never_damage || elastic;
    return contact_overrides<Cpm>(entry, base, p);
  }

  // Šmilauer, calibration steps 1–2: c_T0/(k_T ε_0) is held at the scene's value.
  double cohesion(const CpmKnobs& k) const { return cohesion_ratio_ * k.ratio * k.kn * k.eps0; }

  std::vector<std::string> with_user_overrides(const std::vector<std::string>& knobs) const {
    std::vector<std::string> all = overrides_;
    all.insert(all.end(), knobs.begin(), knobs.end());
    return all;
  }

  // A new k_T/k_N; with an E target k_N follows by (25)'s factor (2 + 3 k_T/k_N)/(4 + k_T/k_N), so that E stays.
  void set_ratio(double ratio) {
    if (e_target()) knobs_.kn *= cc::modulus_shape(knobs_.ratio) / cc::modulus_shape(ratio);
    knobs_.ratio = ratio;
  }

  RunResult run(const std::string& file, std::vector<std::string> o, int entry, const CpmParams& base, bool elastic,
                const std::string& output) const {
    const std::vector<std::string> knobs = knob_overrides(entry, base, knobs_, elastic);
    o.insert(o.end(), knobs.begin(), knobs.end());
    Scene scene = read_scene(TomlDoc::load(file, o), file);
    if (elastic) scene.stops = {StopSpec{strain_, StopSpec::Kind::MagnitudeAbove, elastic_stop_, 0.0}};
    RunOptions ro;
    ro.output = output;
    return run_scene(scene, ro);
  }

  // The tension test with damage off, stopped at elastic_stop_ (Šmilauer: ConcreteMat.neverDamage).
  Measured elastic_trial(int it) const {
    const std::string out = run_file(options_.output, it);
    const auto ran = share_values<Ran>(Ranks::world(), 1, [&](int) {
      const double wall = run(scene_file_, overrides_, entry_, params_, true, out).wall_seconds;
      return Ran{result_of(out, false), wall};
    });
    return Measured{ran[0].result, kNaN, ran[0].wall};
  }

  // The tension test and, with an f_c target, the compression test: independent runs, on two ranks of an MPI
  // launch at once.
  Measured full_trial(int it) const {
    const std::string out = run_file(options_.output, it), c = run_file(options_.output, it, "_compression");
    const auto ran = share_values<Ran>(Ranks::world(), fc_target() ? 2 : 1, [&](int k) {
      if (k == 0) {
        const double wall = run(scene_file_, overrides_, entry_, params_, false, out).wall_seconds;
        return Ran{result_of(out, true), wall};
      }
      const double wall =
          run(options_.compression_scene, overrides_, compression_entry_, compression_params_, false, c).wall_seconds;
      return Ran{result_of(c, true), wall};
    });
    Measured m{ran[0].result, kNaN, ran[0].wall};
    if (fc_target()) m.fc = ran[1].result.ucs, m.wall += ran[1].wall;
    return m;
  }

  static UniaxialResult result_of(const std::string& file, bool peak) {
    const UniaxialResult u = uniaxial_result(file);
    if (!std::isfinite(u.modulus) || !std::isfinite(u.poisson) || (peak && !std::isfinite(u.ucs)))
      throw InputError(file + ": the uniaxial test gave no E, ν or strength (" + read_stored_run(file).status +
                       "); check that the scene loads the specimen to its peak");
    return u;
  }

  void log_line(int it, const Measured& m) const {
    auto mpa = [](double v, char* b, std::size_t n) {
      if (std::isnan(v))
        std::snprintf(b, n, "-");
      else
        std::snprintf(b, n, "%.4g", v * 1e-6);
    };
    char ft[32], fc[32];
    mpa(elastic_ ? kNaN : m.tension.ucs, ft, sizeof ft);
    mpa(m.fc, fc, sizeof fc);
    std::fprintf(log_, "%3d %-8s %9.4g %6.4g %9.4g %7.4g %10.4g | %7.4g %6.4f %9s %9s | %.1f\n", it,
                 elastic_ ? "elastic" : "full", knobs_.kn * 1e-9, knobs_.ratio, knobs_.eps0, knobs_.tan_phi,
                 cohesion(knobs_) * 1e-6, m.tension.modulus * 1e-9, m.tension.poisson, ft, fc, m.wall);
    std::fflush(log_);
  }

  bool within(double value, double target) const {
    return std::isnan(target) || rel(value, target) <= options_.tolerance;
  }
  bool elastic_ok(const UniaxialResult& u) const {
    return within(u.modulus, target_.modulus) && within(u.poisson, target_.poisson);
  }
  bool strengths_ok(const Measured& m) const {
    return within(m.tension.ucs, target_.tensile) && within(m.fc, target_.compressive);
  }

  // ν through k_T/k_N: the microplane relation shifted by the offset the run measured from it; E through k_N by
  // radial scaling (Šmilauer: "the value of k_N is scaled by E*/E").
  void adjust_stiffness(const UniaxialResult& u) {
    if (nu_target() && !within(u.poisson, target_.poisson)) {
      const double want = target_.poisson - (u.poisson - cc::poisson_from_kt_kn(knobs_.ratio));
      if (want >= 0.25 || want <= 0)
        throw InputError("calibrate: ν = " + std::to_string(target_.poisson) +
                         " is out of reach for this packing: k_T/k_N = " + std::to_string(knobs_.ratio) +
                         " gave ν = " + std::to_string(u.poisson) +
                         ", and k_T/k_N in (0, 1] cannot move it far "
                         "enough");
      set_ratio(cc::kt_kn_from_poisson(want));
    }
    if (e_target()) knobs_.kn = cc::scale_to_target(knobs_.kn, u.modulus, target_.modulus);
  }

  void adjust(const Measured& m) {
    const double kn = knobs_.kn;
    if (!elastic_ok(m.tension)) adjust_stiffness(m.tension);
    // Step 5, radial scaling: f_t = k_N ε_0 Ψ, so the new k_N is compensated in ε_0 too.
    if (ft_target()) knobs_.eps0 *= target_.tensile / m.tension.ucs * kn / knobs_.kn;
    if (fc_target()) {
      const double ft = ft_target() ? target_.tensile : m.tension.ucs;
      samples_.push_back({knobs_.tan_phi, m.fc / m.tension.ucs});
      knobs_.tan_phi = next_tan_phi(target_.compressive / ft);
    }
  }

  // Step 4: tan φ for the strength ratio f_c/f_t, interpolated between the sampled runs that bracket it; until
  // two do, a step from the nearest sample with f_c/f_t taken proportional to tan φ (Fig. 22: f_c/f_t grows
  // with tan φ), at most a factor 2.
  double next_tan_phi(double ratio) const {
    std::vector<std::pair<double, double>> s = samples_;
    std::sort(s.begin(), s.end());
    std::vector<double> tan_phi, ratios;
    for (const auto& [p, r] : s) tan_phi.push_back(p), ratios.push_back(r);
    if (s.size() >= 2 && ratio >= *std::min_element(ratios.begin(), ratios.end()) &&
        ratio <= *std::max_element(ratios.begin(), ratios.end()))
      return cc::parameter_for(tan_phi, ratios, ratio, "tan phi");
    const auto nearest = *std::min_element(s.begin(), s.end(), [&](const auto& a, const auto& b) {
      return std::abs(a.second - ratio) < std::abs(b.second - ratio);
    });
    return nearest.first * std::clamp(ratio / nearest.second, 0.5, 2.0);
  }

  const std::string scene_file_;
  const std::vector<std::string> overrides_;
  const int entry_;
  const CalibrationTarget target_;
  const CalibrationOptions options_;
  std::FILE* log_;
  CpmParams params_, compression_params_;  // the entries as the scenes give them
  CpmKnobs knobs_;
  double cohesion_ratio_ = 0;  // c_T0/(k_T ε_0) of the scene
  std::string strain_;         // the tension test's axial strain history
  int compression_entry_ = -1;
  bool elastic_ = false;
  double elastic_stop_ = 0;
  std::vector<std::pair<double, double>> samples_;  // (tan φ, f_c/f_t) of the full runs
  CalibrationResult res_;
};

}  // namespace

CalibrationResult calibrate_cpm(const std::string& scene_file, const std::vector<std::string>& overrides, int entry,
                                const CalibrationTarget& target, const CalibrationOptions& options, std::FILE* log) {
  return CpmCalibration(scene_file, overrides, entry, target, options, log).run();
}

}  // namespace mc::calibration
