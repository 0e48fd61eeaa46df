// What the calibration procedures (Tang's for parallel and softening bonds, Šmilauer's for the CPM) share: the
// iteration runs' files beside the calibrated scene, and writing that scene. The calibrated entry's parameters are
// read, and written back as --set strings, through the model's key table (scene/model_registry.hpp). Internal to studies/calibration*.cpp.
#pragma once
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "scene/toml_reader.hpp"
#include "studies/calibration.hpp"

namespace mc::calibration {

inline double rel(double value, double target) { return std::abs(value / target - 1.0); }

// A run costs its steps: the critical step falls as 1/√k (Tang 3.24), so a run to a strain ε takes ε √k times as
// many (against another run of the same kind, at the same loading rate). A target the specimen cannot give drives
// the stiffness without end (E = 1e20 Pa: the moduli × 3·10⁹, runs 5·10⁴ times as long); the procedures stop, not
// converged (exit 5), once their next run of a kind would take 30 times the first (and over a minute).
class RunCost {
 public:
  static constexpr double kMostGrowth = 30, kLeastBoundSeconds = 60;
  // A run of this kind took `seconds` at stiffness scale k, loaded to strain scale ε (any consistent measures).
  void ran(double seconds, double k, double strain);
  // False before any run; else whether a run at (k, ε) would take beyond the bound, said on `log` if so.
  bool beyond_bound(double k, double strain, const char* kind, std::FILE* log) const;

 private:
  double first_ = 0, last_ = 0, k_ = 0, strain_ = 0;
};

// Where the runs of a calibration writing the scene `output` go: <stem>_itK<suffix>.h5 beside it.
std::string run_file(const std::string& output, int iteration, const std::string& suffix = "");

// The scene `scene_file` with `overrides` applied (listed in its header comment), written to `output` whole or
// not at all; a `note` goes first, as a comment.
void write_scene(const std::string& scene_file, const std::vector<std::string>& overrides, const std::string& output,
                 const std::string& note = "");

// Tang's procedure (§6.3; ch. 7 in tension) on the scene's parallel_bond or softening_bond entry `entry`
// (studies/calibration_bonded.cpp); options.tolerance is set.
CalibrationResult calibrate_bonded(const std::string& scene_file, const std::vector<std::string>& overrides, int entry,
                                   const CalibrationTarget& target, const CalibrationOptions& options, std::FILE* log);

// The rigid-cell family's procedure on the scene's facet_damage entry `entry` (studies/calibration_rigid_cell.cpp).
CalibrationResult calibrate_rigid_cell(const std::string& scene_file, const std::vector<std::string>& overrides,
                                       int entry, const CalibrationTarget& target, const CalibrationOptions& options,
                                       std::FILE* log);

// Šmilauer's procedure on the scene's cpm entry `entry` (studies/calibration_cpm.cpp); options.tolerance is set.
CalibrationResult calibrate_cpm(const std::string& scene_file, const std::vector<std::string>& overrides, int entry,
                                const CalibrationTarget& target, const CalibrationOptions& options, std::FILE* log);

}  // namespace mc::calibration
