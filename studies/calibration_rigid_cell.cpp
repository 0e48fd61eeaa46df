// The rigid-cell family's calibration as a loop of runs of the scene's direct tension test (a box between two
// plates, one [rigid_cell.sections] plane across it and a [rigid_cell.strain] box away from the plates):
//   elastic runs (the facets' f_t × 1000 and G_t × 10⁶, three load steps) until E and ν match: E = σ/ε along the
//   section's axis, ν = −ε_lateral/ε over the strain box; the facet law's nominal E and ν ((3.8): from E₀ and α,
//   or the modulus and poisson_ratio given) moved, E by E*/E (the stiffness scales at a fixed α), ν by a secant
//   on the measured ν;
//   then full runs, to the scene's post-peak stop, until f_t (the section's largest stress) and G_F (the dissipated
//   energy over the section's area) match: the facets' f_t by f_t*/f_t and G_t by G_F*/G_F.
// The facets' G_t is per unit facet area and the crack band (3.20) keeps a facet's dissipation independent of its
// size, but the macroscopic G_F also holds the crack's tortuosity and the damage around it, which depend on l_min:
// the calibrated scene says at which l_min it was found.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "engine/errors.hpp"
#include "rigid_cell/facet_law.hpp"
#include "scene/model_registry.hpp"
#include "scene/rigid_cell_histories.hpp"
#include "scene/scene.hpp"
#include "studies/calibration_run.hpp"
#include "studies/ranks.hpp"
#include "studies/runner.hpp"
#include "studies/stored_run.hpp"

namespace mc::calibration {

namespace {

constexpr double kCellStrong = 1e3;           // f_t times this: no facet damages in the elastic runs
constexpr double kCellMostMove = 4;           // a knob moves by at most this factor a run
constexpr double kCellIncompleteStop = 0.05;  // a full run must end below this fraction of its peak stress

// The facet law's values the calibration moves: its nominal E and ν (by (3.8) from E₀ and α, or as given), f_t, G_t.
struct CellKnobs {
  double E = 0, nu = 0, ft = 0, gt = 0;
};

struct CellMeasured {
  double E = kNaN, nu = kNaN, ft = kNaN, gf = kNaN, wall = 0;
};

class RigidCellCalibration {
 public:
  RigidCellCalibration(const std::string& scene_file, const std::vector<std::string>& overrides, int entry,
                       const CalibrationTarget& target, const CalibrationOptions& options, std::FILE* log)
      : file_(scene_file), overrides_(overrides), entry_(entry), target_(target), options_(options), log_(log) {
    const Scene base = read_scene(TomlDoc::load(scene_file, overrides), scene_file);
    d_ = base.dimension;
    const RigidCellSpec& r = *base.rigid_cell;
    if (r.facets.size() != 1)
      throw InputError(scene_file + ": calibrate fits one facet law; this scene has " +
                       std::to_string(r.facets.size()) + " [[contacts]] entries: calibrate each material alone");
    const FacetLawSpec& f = r.facets[0];
    macro_form_ = f.E0 == 0;
    const rigid_cell::Elastic e = macro_form_ ? rigid_cell::Elastic{f.modulus, f.poisson_ratio}
                                              : rigid_cell::macroscopic(d_, f.E0, f.alpha);
    knobs_ = {e.E, e.nu, f.tensile_strength, f.fracture_energy};
    if (r.sections.empty() || !r.strain || r.specimen.shape != CellSpecimenSpec::Shape::Box)
      throw InputError(scene_file +
                       ": calibrate runs a rigid-cell scene as a direct tension test: a box (specimen shape = "
                       "\"box\") with a [rigid_cell.sections] plane across it for σ and a [rigid_cell.strain] box "
                       "away from the plates for ε, e.g. scenes/rigid_cell_calibration_tension_2d.toml");
    axis_ = r.sections[0].axis;
    section_ = section_history_name(r.sections[0]);
    area_ = 1;  // 2D: per metre of thickness
    for (int k = 0; k < d_; ++k)
      if (k != axis_) area_ *= r.specimen.size[static_cast<std::size_t>(k)];
    l_min_ = r.specimen.l_min;
    check_targets(base);
    std::vector<std::string> outputs{options_.output, options_.output + ".tmp"};
    for (int it = 1; it <= options_.max_iterations; ++it)
      for (const auto& out : run_files(run_file(options_.output, it))) outputs.push_back(out);
    refuse_unsafe_outputs(base, outputs);
  }

  CalibrationResult run() {
    std::fprintf(log_, "%3s %-8s %9s %6s %9s %9s | %7s %6s %9s %9s | %s\n", "it", "run", "E* [GPa]", "nu*",
                 "f_t [MPa]", "G_t [N/m]", "E [GPa]", "nu", "f_t [MPa]", "G_F [N/m]", "wall [s]");
    bool elastic = !std::isnan(target_.modulus) || !std::isnan(target_.poisson);
    const bool full = !std::isnan(target_.tensile) || !std::isnan(target_.fracture_energy);
    CellKnobs ran = knobs_;
    RunCost cost[2];
    for (int it = 1; it <= options_.max_iterations; ++it) {
      RunCost& c = cost[elastic ? 0 : 1];
      // Static load steps: a run's steps follow the opening it must reach (w ∝ G_t/f_t), not the stiffness.
      const double reach = elastic ? 1.0 : knobs_.gt / knobs_.ft;
      if (c.beyond_bound(1.0, reach, elastic ? "elastic" : "full", log_)) break;
      ran = knobs_;
      const CellMeasured m = trial(it, elastic);
      c.ran(m.wall, 1.0, reach);
      log_line(it, elastic, m);
      res_.iterations = it;
      if (elastic) {
        if (within(m.E, target_.modulus) && within(m.nu, target_.poisson)) {
          if (!full) {
            res_.converged = true;
            break;
          }
          elastic = false;
        } else if (!adjust_elastic(m)) {
          break;
        }
        continue;
      }
      if (within(m.ft, target_.tensile) && within(m.gf, target_.fracture_energy)) {
        res_.converged = true;
        break;
      }
      adjust_strengths(m);
    }
    res_.overrides = overrides_of(ran);
    std::vector<std::string> all = overrides_;
    all.insert(all.end(), res_.overrides.begin(), res_.overrides.end());
    std::ostringstream note;
    note << "calibrated at l_min = " << l_min_ * 1e3 << " mm: the macroscopic G_F holds the crack's tortuosity, "
         << "which depends on the cell size; at another l_min calibrate again with --set specimen.l_min=...";
    write_scene(file_, all, options_.output, note.str());
    return res_;
  }

 private:
  std::string file_;
  std::vector<std::string> overrides_;
  int entry_;
  CalibrationTarget target_;
  CalibrationOptions options_;
  std::FILE* log_;
  int d_ = 2, axis_ = 0;
  bool macro_form_ = false;
  std::string section_;
  double area_ = 0, l_min_ = 0;
  CellKnobs knobs_;
  std::vector<std::pair<double, double>> nu_tried_;  // (nominal ν, measured ν) of the elastic runs
  CalibrationResult res_;

  double nu_top() const { return d_ == 2 ? 1.0 / 3.0 : 0.25; }

  void check_targets(const Scene& base) const {
    auto refuse = [](double value, const std::string& name, const std::string& why) {
      if (!std::isnan(value))
        throw InputError("--target " + name + ": not a target for a rigid-cell scene (its targets: E, nu, ft, Gf)" +
                         why);
    };
    refuse(target_.ucs, "ucs", "; it is calibrated in direct tension");
    refuse(target_.compressive, "fc", "; it is calibrated in direct tension");
    if (!std::isnan(target_.poisson) && !(target_.poisson > -1 && target_.poisson < nu_top()))
      throw InputError("--target nu=" + std::to_string(target_.poisson) + ": a rigid-cell model in " +
                       std::to_string(d_) + "D reaches ν in (-1, " + (d_ == 2 ? "1/3" : "1/4") +
                       ") only (Květoň (3.8), α > 0)");
    const bool full = !std::isnan(target_.tensile) || !std::isnan(target_.fracture_energy);
    if (full && !(knobs_.ft > 0))
      throw InputError(file_ + ": the facets are elastic (no tensile strength): give them a strength and a "
                       "fracture energy to start from");
    if (!std::isnan(target_.fracture_energy)) {
      const bool stops = std::any_of(base.stops.begin(), base.stops.end(), [](const StopSpec& s) {
        return s.kind == StopSpec::Kind::PostPeak && s.value <= kCellIncompleteStop;
      });
      if (!stops)
        throw InputError(file_ + ": a Gf target needs the full run to end once the load has fallen to at most " +
                         std::to_string(kCellIncompleteStop) +
                         " of its peak ([[run.stop]] post_peak_fraction): the energy dissipated is G_F only then");
    }
  }

  bool within(double value, double target) const {
    return std::isnan(target) || rel(value, target) <= options_.tolerance;
  }

  // The entry's --set lines for these knobs; E and ν back through (3.8) when the scene gives E₀ and α.
  std::vector<std::string> overrides_of(const CellKnobs& k) const {
    if (macro_form_) return facet_law_overrides(entry_, false, k.E, k.nu, k.ft, k.gt);
    const rigid_cell::FacetParams p = rigid_cell::mesoscopic(d_, k.E, k.nu);
    return facet_law_overrides(entry_, true, p.E0, p.alpha, k.ft, k.gt);
  }

  CellMeasured trial(int it, bool elastic) const {
    const std::string out = run_file(options_.output, it);
    const auto ran = share_values<CellMeasured>(Ranks::world(), 1, [&](int) {
      std::vector<std::string> o = overrides_;
      CellKnobs k = knobs_;
      if (elastic) k.ft *= kCellStrong, k.gt *= kCellStrong * kCellStrong;  // the crack band's f_t²/G_t kept
      for (const auto& s : overrides_of(k)) o.push_back(s);
      if (elastic) o.push_back("run.steps=3");
      Scene scene = read_scene(TomlDoc::load(file_, o), file_);
      if (elastic) scene.stops.clear();
      RunOptions ro;
      ro.output = out;
      const double wall = run_scene(scene, ro).wall_seconds;
      CellMeasured m = measure(out, elastic);
      m.wall = wall;
      return m;
    });
    return ran[0];
  }

  CellMeasured measure(const std::string& out, bool elastic) const {
    const StoredRun run = read_stored_run(out);
    const auto& h = run.histories;
    auto normal_strain = [&](int k) { return std::string("strain.") + strain_component_names(d_)[k]; };
    auto series = [&](const std::string& name) -> const std::vector<double>& {
      const auto i = h.find(name);
      if (i == h.end() || i->second.size() < 2)
        throw InputError(out + ": the run recorded no history '" + name + "' (" + run.status + ")");
      return i->second;
    };
    const auto& sigma = series(section_);
    const auto& eps = series(normal_strain(axis_));
    CellMeasured m;
    if (elastic) {
      double lateral = 0;
      for (int k = 0; k < d_; ++k)
        if (k != axis_) lateral += series(normal_strain(k)).back() / (d_ - 1);
      m.E = sigma.back() / eps.back();
      m.nu = -lateral / eps.back();
      return m;
    }
    const auto peak = std::max_element(sigma.begin(), sigma.end());
    m.ft = *peak;
    if (!std::isnan(target_.fracture_energy)) {
      if (!(std::abs(sigma.back()) <= kCellIncompleteStop * m.ft))
        throw InputError(out + ": the full run ended (" + run.status + ") at " +
                         std::to_string(sigma.back() / m.ft) +
                         " of its peak stress, before the crack had parted: its dissipated energy is not yet G_F; "
                         "give it more load steps (run.steps) or longer ones (timestep.fixed)");
      m.gf = series("energy.dissipated").back() / area_;
    }
    return m;
  }

  // E through the nominal E (the stiffness scales at a fixed α); ν by a secant through the runs' (nominal, measured)
  // pairs, the first step at unit slope. False (not converged) when ν would need a nominal value beyond (3.8)'s.
  bool adjust_elastic(const CellMeasured& m) {
    if (!std::isnan(target_.poisson)) {
      nu_tried_.emplace_back(knobs_.nu, m.nu);
      double slope = 1;
      if (nu_tried_.size() >= 2) {
        const auto& [n0, m0] = nu_tried_[nu_tried_.size() - 2];
        const auto& [n1, m1] = nu_tried_.back();
        if (std::abs(m1 - m0) > 1e-12 && std::abs(n1 - n0) > 1e-12) slope = (m1 - m0) / (n1 - n0);
      }
      const double next = knobs_.nu + (target_.poisson - m.nu) / slope;
      const double top = nu_top() - 1e-3;
      if (!(next > -0.99 && next < top)) {
        std::fprintf(log_,
                     "stopped: ν = %.4g would need the facets' nominal ν = %.4g, beyond what α > 0 gives (%.4g, "
                     "Květoň (3.8)); this tessellation and its plates cannot reach it\n",
                     target_.poisson, next, nu_top());
        return false;
      }
      knobs_.nu = next;
    }
    if (!std::isnan(target_.modulus)) knobs_.E *= std::clamp(target_.modulus / m.E, 1 / kCellMostMove, kCellMostMove);
    return true;
  }

  void adjust_strengths(const CellMeasured& m) {
    if (!std::isnan(target_.tensile)) knobs_.ft *= std::clamp(target_.tensile / m.ft, 1 / kCellMostMove, kCellMostMove);
    if (!std::isnan(target_.fracture_energy))
      knobs_.gt *= std::clamp(target_.fracture_energy / m.gf, 1 / kCellMostMove, kCellMostMove);
  }

  void log_line(int it, bool elastic, const CellMeasured& m) const {
    auto num = [](double v, double scale) {
      char b[32];
      if (std::isnan(v))
        std::snprintf(b, sizeof b, "-");
      else
        std::snprintf(b, sizeof b, "%.4g", v * scale);
      return std::string(b);
    };
    std::fprintf(log_, "%3d %-8s %9.4g %6.4f %9.4g %9.4g | %7s %6s %9s %9s | %.1f\n", it, elastic ? "elastic" : "full",
                 knobs_.E * 1e-9, knobs_.nu, knobs_.ft * 1e-6, knobs_.gt, num(m.E, 1e-9).c_str(),
                 num(m.nu, 1).c_str(), num(m.ft, 1e-6).c_str(), num(m.gf, 1).c_str(), m.wall);
    std::fflush(log_);
  }
};

}  // namespace

CalibrationResult calibrate_rigid_cell(const std::string& scene_file, const std::vector<std::string>& overrides,
                                       int entry, const CalibrationTarget& target, const CalibrationOptions& options,
                                       std::FILE* log) {
  return RigidCellCalibration(scene_file, overrides, entry, target, options, log).run();
}

}  // namespace mc::calibration
