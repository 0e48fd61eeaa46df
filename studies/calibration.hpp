// `mesocrack calibrate`: find the micro-parameters of a parallel-bonded specimen that give target macro-properties
// in its uniaxial compression test, by Tang's recipe (§6.3): with the bonds made strong, ν is matched through the
// stiffness ratio k_n/k_s and E through the contact modulus E_c (grain and bond changed together); then UCS
// through the bond strengths, all scaled by one factor so that their ratio and spread stay as given.
#pragma once
#include <cstdio>
#include <string>
#include <vector>

#include "studies/stored_run.hpp"  // UniaxialResult

namespace mc {

struct CalibrationTarget {
  double modulus = kNaN, poisson = kNaN, ucs = kNaN;  // NaN: not a target
};
// "E=30 GPa,nu=0.2,ucs=40 MPa" (any subset, any order; numbers without units are SI). Throws InputError.
CalibrationTarget parse_targets(const std::string& text);

struct CalibrationOptions {
  double tolerance = 0.05;  // relative, on each target
  int max_iterations = 12;
  std::string output;  // the calibrated scene (TOML); its runs go beside it as <stem>_itK.h5
};

struct CalibrationResult {
  bool converged = false;
  int iterations = 0;
  std::vector<std::string> overrides;  // what was changed, as --set strings
  UniaxialResult last;                 // of the last full test
};

CalibrationResult calibrate(const std::string& scene_file, const std::vector<std::string>& overrides,
                            const CalibrationTarget& target, const CalibrationOptions& options, std::FILE* log);

}  // namespace mc
