// `mesocrack calibrate`: find the micro-parameters of a specimen that give target macro-properties in its
// uniaxial test (studies/calibration_bonded.cpp). A parallel-bonded specimen in compression follows Tang's recipe
// (§6.3): with the bonds made strong, ν is matched through the stiffness ratio k_n/k_s and E through the contact
// modulus E_c (grain and bond changed together); then UCS through the bond strengths, all scaled by one factor so
// that their ratio and spread stay as given. A parallel- or softening-bonded specimen in tension (Tang ch. 7's
// phases) follows the same steps to E, ν and f_t, and a softening bond's G_f through its ductility. A CPM specimen
// follows Šmilauer's "Parameter calibration" in tension (studies/calibration_cpm.cpp): k_T/k_N from ν, k_N from E,
// ε_0 from f_t, and tan φ from f_c/f_t in a compression test.
#pragma once
#include <cstdio>
#include <string>
#include <vector>

#include "studies/stored_run.hpp"  // UniaxialResult

namespace mc {

struct CalibrationTarget {
  double modulus = kNaN, poisson = kNaN;  // NaN: not a target
  double ucs = kNaN;                      // parallel bonds: the compressive strength of the compression test
  double tensile = kNaN;                  // f_t of the tension test (bonded or CPM)
  double compressive = kNaN;              // CPM: f_c of the compression test
  double fracture_energy = kNaN;          // softening bonds: G_f [J/m²] of the tension test
  // A concrete class of the fib Model Code 2010 ("C30/37", studies/model_code.hpp): the targets not given otherwise
  // that the scene's model can fit take the class's values (E_ci, ν = 0.2, f_ctm, f_cm, G_F).
  std::string concrete_class, aggregate = "quartzite";
};
// "E=30 GPa,nu=0.2,ucs=40 MPa", "E=35GPa,nu=0.16,ft=3.2MPa,Gf=170.4N/m", "E=30GPa,nu=0.2,ft=3MPa,fc=40MPa" or
// "class=C30/37[,aggregate=basalt]" (any subset, any order; numbers without units are SI). Which targets a scene
// can use depends on its model: calibrate() refuses the others. Throws InputError.
CalibrationTarget parse_targets(const std::string& text);

struct CalibrationOptions {
  double tolerance = kNaN;  // relative, on each target; NaN: the procedure's default (Tang 5 %, CPM 3 %)
  int max_iterations = 12;
  std::string output;  // the calibrated scene (TOML); its runs go beside it as <stem>_itK.h5
  // CPM with an f_c target: the compression test (the specimen and supports of the scene, loaded the other way).
  std::string compression_scene;
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
