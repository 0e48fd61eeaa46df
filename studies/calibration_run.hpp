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

// Where the runs of a calibration writing the scene `output` go: <stem>_itK<suffix>.h5 beside it.
std::string run_file(const std::string& output, int iteration, const std::string& suffix = "");

// The scene `scene_file` with `overrides` applied (listed in its header comment), written to `output` whole or
// not at all.
void write_scene(const std::string& scene_file, const std::vector<std::string>& overrides, const std::string& output);

// Tang's procedure (§6.3; ch. 7 in tension) on the scene's parallel_bond or softening_bond entry `entry`
// (studies/calibration_bonded.cpp); options.tolerance is set.
CalibrationResult calibrate_bonded(const std::string& scene_file, const std::vector<std::string>& overrides, int entry,
                                   const CalibrationTarget& target, const CalibrationOptions& options, std::FILE* log);

// Šmilauer's procedure on the scene's cpm entry `entry` (studies/calibration_cpm.cpp); options.tolerance is set.
CalibrationResult calibrate_cpm(const std::string& scene_file, const std::vector<std::string>& overrides, int entry,
                                const CalibrationTarget& target, const CalibrationOptions& options, std::FILE* log);

}  // namespace mc::calibration
