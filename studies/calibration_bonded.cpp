// Tang's calibration of a bonded-particle specimen as a loop of runs of the scene's uniaxial test. Parallel bonds
// in compression (§6.3): elastic runs (bonds made strong) until E and ν match, then full runs until UCS does.
// Parallel or softening bonds in tension (ch. 7: "the micro-parameters of DEM model are calibrated by performing
// virtual tensile tests on each component phase"): the same elastic runs, then full runs until f_t and, for
// softening bonds, G_f match. In tension the unbonded grain contacts open, so E differs from compression's.
#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "engine/errors.hpp"
#include "scene/model_registry.hpp"
#include "scene/scene.hpp"
#include "scene/toml_reader.hpp"
#include "studies/calibration_run.hpp"
#include "studies/ranks.hpp"
#include "studies/runner.hpp"

namespace mc::calibration {

namespace {

// The micro-parameters being calibrated, as factors on the scene's own values.
struct Knobs {
  double modulus = 1;    // the moduli (E_c; a parallel bond's Ē_c and its spread) times this
  double ratio = 0;      // k_n/k_s of the grains (a parallel bond's ratio keeps its proportion to it)
  double strength = 1;   // every bond strength (means and spreads) times this
  double ductility = 1;  // softening bonds: U_p,max k_n / F_c^n times this (see softening_factor)
};

// The scene's bonded entry, as the scene gives it: the values the knobs scale.
struct Entry {
  int index = -1;
  bool softening = false;  // softening_bond (Tang 3.42–3.48); else parallel_bond (3.37–3.41)
  ParallelBondParams parallel;
  SofteningBondParams soft;
  // The grains' springs: a softening bond's are the ball springs (k_n = 2tE_c, 3.38), its only modulus.
  const LinearParams& contact() const { return softening ? soft.contact : parallel.contact; }
};

Entry find_entry(const TomlDoc& doc, int index) {
  Entry e;
  e.index = index;
  e.softening = contacts_entry(doc, SofteningBond::name) == index;
  if (e.softening)
    e.soft = contact_params<SofteningBond>(doc, index);
  else
    e.parallel = contact_params<ParallelBond>(doc, index);
  return e;
}

void scale(Scatter& s, double factor) { s.mean *= factor, s.std *= factor; }

// The softening parameter's factor that keeps the bond's shape at ductility ρ when the strengths are times s and
// the moduli times m. A softening bond's strengths fall linearly to zero at U_p,max (3.48), with U_p,max = 2 G_f A /
// F_c^n for a G_f; its shape is U_p,max over the elastic displacement at the strength, F_c^n/k_n. With G_f times
// ρ s²/m (U_p,max times ρ s/m) that ratio is times ρ alone, and every force and displacement of a quasi-static
// test scales as s and s/m: f_t ∝ s, G_f ∝ s²/m, and Hillerborg's l_ch = E G_f / f_t² depends on ρ only.
double softening_factor(const Knobs& k, bool energy) {
  return k.ductility * std::pow(k.strength, energy ? 2 : 1) / k.modulus;
}

// The knobs as --set strings; the strengths are times `strength` (an elastic run's are made strong).
std::vector<std::string> knob_overrides(const Entry& e, const Knobs& k, double strength) {
  if (e.softening) {
    SofteningBondParams p = e.soft;
    p.contact.modulus *= k.modulus;
    p.contact.kn_ks_ratio = k.ratio;
    scale(p.bond_normal_strength, strength), scale(p.bond_shear_strength, strength);
    p.bond_fracture_energy *= softening_factor(k, true);  // the one of the two that is given (the other is 0)
    p.bond_plastic_limit *= softening_factor(k, false);
    return contact_overrides<SofteningBond>(e.index, e.soft, p);
  }
  ParallelBondParams p = e.parallel;
  p.contact.modulus *= k.modulus;
  scale(p.bond_modulus, k.modulus);
  p.contact.kn_ks_ratio = k.ratio;
  p.bond_kn_ks_ratio = e.parallel.bond_kn_ks_ratio / e.parallel.contact.kn_ks_ratio * k.ratio;
  scale(p.bond_tensile_strength, strength), scale(p.bond_shear_strength, strength);
  return contact_overrides<ParallelBond>(e.index, e.parallel, p);
}

// E/E_c as a function of k_n/k_s, Tang (6.2) for 2D and (6.3) for 3D: used only to predict how a change of the
// ratio moves E, so that E_c can be corrected for it in the same iteration (measured in compression; in tension
// it is a first guess that the next run corrects).
double modulus_shape(int dimension, double ratio) {
  return dimension == 2 ? 1.57 - 0.42 * std::log(ratio) : 1.36 - 0.39 * std::log(ratio);
}

// One run of the calibration: what it used, what it gave, how long it took.
struct Trial {
  UniaxialResult result;
  double wall_seconds = 0;
};

// A slope dy/dx measured between successive points: update() records a point and, when it lies more than
// min_step from the previous one along x and the slope between them within (lo, hi), takes that slope; until
// then the slope given at construction holds.
class Secant {
 public:
  explicit Secant(double slope) : slope_(slope) {}
  double update(double x, double y, double min_step, double lo, double hi) {
    if (std::isfinite(x_) && std::abs(x - x_) > min_step) {
      const double s = (y - y_) / (x - x_);
      if (s > lo && s < hi) slope_ = s;
    }
    x_ = x, y_ = y;
    return slope_;
  }

 private:
  double slope_, x_ = kNaN, y_ = kNaN;
};

// Tang's procedure as a loop of runs: elastic runs (bonds made strong) until E and ν match, then full runs until
// the strength (UCS, or f_t) and G_f do, correcting E and ν too if the bonds that break before the peak move them.
class Calibration {
 public:
  Calibration(const std::string& scene_file, const std::vector<std::string>& overrides, int entry,
              const CalibrationTarget& target, const CalibrationOptions& options, std::FILE* log)
      : scene_file_(scene_file),
        overrides_(overrides),
        target_(target),
        options_(options),
        log_(log),
        base_(read_scene(TomlDoc::load(scene_file, overrides), scene_file)),
        entry_(find_entry(TomlDoc::load(scene_file, overrides), entry)) {
    const auto* u = base_.analysis<UniaxialAnalysis>();
    if (!u)
      throw InputError(scene_file +
                       ": calibrate needs a [uniaxial] table: it matches the E, ν and strength it reports");
    tension_ = u->tension;
    check_targets();
    std::vector<std::string> outputs{options_.output, options_.output + ".tmp"};
    for (int it = 1; it <= options_.max_iterations; ++it)
      for (const auto& f : run_files(run_file(it))) outputs.push_back(f);
    refuse_unsafe_outputs(base_, outputs);
    knobs_.ratio = entry_.contact().kn_ks_ratio;
    elastic_ = e_target();
    // The elastic runs stop at half the target's elastic strain at the peak in compression: far enough for the
    // secant between 25 % and 50 % of their last stress, and a fraction of a full test's steps. In tension at
    // that strain itself (as the CPM's, studies/calibration_cpm.cpp): the supports start at full speed, and their
    // secant window is then the full test's, read as long after the start. Without both targets: 5e-4 in
    // compression, 1e-4 (of the order of f_t/E of a concrete) in tension.
    elastic_stop_ = peak_target() && e_target() ? (tension_ ? 1.0 : 0.5) * peak() / target.modulus
                    : tension_                  ? 1e-4
                                                : 5e-4;
  }

  CalibrationResult run() {
    log_header();
    Knobs ran = knobs_;  // what the last run used: the calibrated scene gets these, never untested values
    RunCost cost[2];     // of the elastic runs and of the full ones (to the peak: strain strength/modulus)
    for (int it = 1; it <= options_.max_iterations; ++it) {
      RunCost& c = cost[elastic_ ? 0 : 1];
      const double reach = elastic_ ? 1.0 : knobs_.strength / knobs_.modulus;
      if (c.beyond_bound(knobs_.modulus, reach, elastic_ ? "elastic" : "full", log_)) break;
      ran = knobs_;
      const Trial t = trial(it);
      c.ran(t.wall_seconds, knobs_.modulus, reach);
      const UniaxialResult& u = t.result;
      res_.iterations = it;
      const bool e_ok = elastic_ok(u);
      if (!elastic_) res_.last = u;
      if (elastic_ && e_ok && peak_target()) {  // the stiffnesses are found: now the strengths, in full tests
        elastic_ = false;
        continue;
      }
      if (e_ok && (elastic_ || strengths_ok(u))) {
        if (elastic_) res_.last = u;
        res_.converged = true;
        break;
      }
      if (!e_ok) adjust_stiffness(u);
      if (!elastic_) adjust_strength(u);
    }
    res_.overrides = knob_overrides(entry_, ran, ran.strength);
    write_scene(scene_file_, with_user_overrides(res_.overrides), options_.output);
    return res_;
  }

 private:
  bool e_target() const { return !std::isnan(target_.modulus); }
  bool nu_target() const { return !std::isnan(target_.poisson); }
  bool gf_target() const { return !std::isnan(target_.fracture_energy); }
  // The strength the test measures: UCS in compression, f_t in tension.
  double peak() const { return tension_ ? target_.tensile : target_.ucs; }
  bool peak_target() const { return !std::isnan(peak()); }

  bool within(double value, double target) const {
    return std::isnan(target) || rel(value, target) <= options_.tolerance;
  }
  bool elastic_ok(const UniaxialResult& u) const {
    return within(u.modulus, target_.modulus) && within(u.poisson, target_.poisson);
  }
  bool strengths_ok(const UniaxialResult& u) const {
    return within(u.ucs, peak()) && within(u.fracture_energy, target_.fracture_energy);
  }

  // What each model and loading can be calibrated to; InputError naming the first target that does not fit.
  void check_targets() const {
    const std::string model = entry_.softening ? "softening_bond" : "parallel_bond";
    if (entry_.softening && !tension_)
      throw InputError(scene_file_ +
                       ": calibrate runs a softening_bond scene as its uniaxial tension test (Tang ch. 7: \"virtual "
                       "tensile tests on each component phase\"); give [uniaxial] loading = \"tension\"");
    const std::string allowed = !tension_          ? "E with nu, ucs"
                                : entry_.softening ? "E, nu with E, ft, Gf with ft"
                                                   : "E, nu with E, ft";
    auto refuse = [&](double value, const std::string& name, const std::string& why) {
      if (!std::isnan(value))
        throw InputError("--target " + name + ": not a target for a " + model + " scene in " +
                         (tension_ ? "tension" : "compression") + " (its targets: " + allowed + ")" + why);
    };
    refuse(target_.compressive, "fc", tension_ ? "; fc is a cpm target" : "; its compressive strength is ucs");
    if (tension_) {
      refuse(target_.ucs, "ucs", "; in tension its strength is ft");
      if (!entry_.softening)
        refuse(target_.fracture_energy, "Gf",
               "; a parallel bond breaks brittle, with no softening to fit G_f to: Gf is a target of softening_bond "
               "scenes");
      if (nu_target() && !e_target())
        throw InputError("--target: give E with nu (both depend on E_c and k_n/k_s, Tang §6.3)");
      if (gf_target() && std::isnan(target_.tensile))
        throw InputError(
            "--target: give ft with Gf (a softening bond's G_f moves with the square of its strength; "
            "the ductility is fitted to l_ch = E G_f / f_t²)");
    } else {
      refuse(target_.tensile, "ft", "; its strength in compression is ucs");
      refuse(target_.fracture_energy, "Gf", "; G_f is measured in tension");
      if (e_target() != nu_target())
        throw InputError(
            "--target: give E and nu together for a parallel_bond scene in compression (both depend on "
            "E_c and k_n/k_s, Tang §6.3)");
    }
    if (!options_.compression_scene.empty())
      throw InputError("--compression: only for cpm scenes with an fc target; a " + model +
                       " scene is calibrated in its own uniaxial test");
  }

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
    // One run: on rank 0 of an MPI launch, the others waiting for its numbers (Ranks::share).
    const Trial t = share_values<Trial>(Ranks::world(), 1, [&](int) {
      const RunResult run = run_scene(scene, ro);
      const Trial ran{uniaxial_result(ro.output), run.wall_seconds};
      const UniaxialResult& u = ran.result;
      if (!std::isfinite(u.modulus) || !std::isfinite(u.poisson) || (!elastic_ && !std::isfinite(u.ucs)))
        throw InputError(ro.output + ": the uniaxial test gave no E, ν or strength (" + run.status +
                         "); check that the scene loads the specimen to its peak");
      if (!elastic_ && gf_target() && !std::isfinite(u.fracture_energy))
        throw InputError(ro.output + ": the tension test gave no G_f (" + run.status +
                         "): it needs the stress to fall to 0.2 f_t after the peak; let the run go on that far (e.g. "
                         "[[run.stop]] post_peak_fraction = 0.15 on uniaxial.stress)");
      return ran;
    })[0];
    log_line(it, t);
    return t;
  }

  void log_header() const {
    std::fprintf(log_, "%3s %-8s %10s %7s %9s", "it", "run", "E_c [GPa]", "kn/ks", "strength");
    if (entry_.softening) std::fprintf(log_, " %9s", "ductility");
    std::fprintf(log_, " | %9s %7s %9s", "E [GPa]", "nu", tension_ ? "f_t [MPa]" : "UCS [MPa]");
    if (tension_) std::fprintf(log_, " %9s", "G_f [N/m]");
    std::fprintf(log_, " | %s\n", "wall [s]");
  }

  void log_line(int it, const Trial& t) const {
    const UniaxialResult& u = t.result;
    char peak[32] = "-", gf[32] = "-";  // an elastic run has no peak and no softening
    if (!elastic_) std::snprintf(peak, sizeof peak, "%.4g", u.ucs * 1e-6);
    if (!elastic_) std::snprintf(gf, sizeof gf, "%.4g", u.fracture_energy);
    std::fprintf(log_, "%3d %-8s %10.4g %7.4g %9.4g", it, elastic_ ? "elastic" : "full",
                 entry_.contact().modulus * knobs_.modulus * 1e-9, knobs_.ratio, knobs_.strength);
    if (entry_.softening) std::fprintf(log_, " %9.4g", knobs_.ductility);
    std::fprintf(log_, " | %9.4g %7.4g %9s", u.modulus * 1e-9, u.poisson, peak);
    if (tension_) std::fprintf(log_, " %9s", gf);
    std::fprintf(log_, " | %.1f\n", t.wall_seconds);
    std::fflush(log_);
  }

  // ν through k_n/k_s on its logarithmic law (6.2)/(6.3), with the slope the last two runs measured when they tell
  // one; E through E_c (linear, 6.1), corrected for what the new ratio does to E/E_c.
  void adjust_stiffness(const UniaxialResult& u) {
    double ratio = knobs_.ratio;
    if (nu_target()) {
      const double lnr = std::log(knobs_.ratio);
      const double slope = nu_slope_.update(lnr, u.poisson, 1e-3, 0.02, 0.5);
      ratio = std::clamp(std::exp(lnr + (target_.poisson - u.poisson) / slope), 0.25, 20.0);
      if (ratio == knobs_.ratio)
        throw InputError("calibrate: ν = " + std::to_string(target_.poisson) +
                         " is out of reach for this packing: k_n/k_s at its bound " + std::to_string(ratio) +
                         " gives ν = " + std::to_string(u.poisson));
    }
    const int d = base_.dimension;
    knobs_.modulus *= target_.modulus / u.modulus * modulus_shape(d, knobs_.ratio) / modulus_shape(d, ratio);
    knobs_.ratio = ratio;
  }

  // A full run's strength and G_f. At a fixed ductility the strength is proportional to the bond strengths (every
  // force of the test scales with them), so they are scaled by target/measured (Tang §6.3 for UCS). With a G_f
  // target the ductility ρ first moves l_ch = E G_f / f_t², which depends on ρ alone (softening_factor): a secant
  // step in ln ρ on ln l_ch, with the slope the last two full runs measured (1 until they do: G_f in proportion to
  // the bonds' G_f). A more ductile bond network is also stronger, f_t/s ∝ ρ^a (a measured likewise, 0 until
  // then), so the strength step undoes what the new ρ will add.
  void adjust_strength(const UniaxialResult& u) {
    const double rho = knobs_.ductility;
    double a = 0;  // d ln(f_t/s) / d ln ρ
    if (gf_target()) {
      const double lnr = std::log(rho);
      const double lch = u.modulus * u.fracture_energy / (u.ucs * u.ucs);
      const double modulus = e_target() ? target_.modulus : u.modulus;
      const double want = modulus * target_.fracture_energy / (target_.tensile * target_.tensile);
      const double b = lch_slope_.update(lnr, std::log(lch), 0.02, 0.1, 3.0);
      a = strength_slope_.update(lnr, std::log(u.ucs / knobs_.strength), 0.02, -1.0, 1.0);
      // At most a factor 4 a step: far from the target the slope of ln l_ch on ln ρ is not yet known.
      knobs_.ductility = rho * std::exp(std::clamp(std::log(want / lch) / b, -std::log(4.0), std::log(4.0)));
    }
    if (!within(u.ucs, peak()) || knobs_.ductility != rho)
      knobs_.strength *= peak() / u.ucs * std::pow(rho / knobs_.ductility, a);
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
  const Scene base_;  // read first: the scene reader checks the entry's keys before find_entry reads them
  const Entry entry_;
  bool tension_ = false;
  Knobs knobs_;
  bool elastic_ = false;
  double elastic_stop_ = 5e-4;
  Secant nu_slope_{0.11};       // dν/d ln(k_n/k_s), Tang (6.2) and (6.3); then what the runs measure
  Secant lch_slope_{1.0};       // d ln l_ch / d ln ρ
  Secant strength_slope_{0.0};  // d ln(f_t/s) / d ln ρ
  CalibrationResult res_;
};

}  // namespace

CalibrationResult calibrate_bonded(const std::string& scene_file, const std::vector<std::string>& overrides, int entry,
                                   const CalibrationTarget& target, const CalibrationOptions& options, std::FILE* log) {
  return Calibration(scene_file, overrides, entry, target, options, log).run();
}

}  // namespace mc::calibration
