// `mesocrack summary`: the key results of a run as one JSON object, computed from the histories in its output
// file (so it works on a finished run, a stopped one, and one killed mid-way).
#pragma once
#include <map>
#include <string>
#include <vector>

#include "engine/dim.hpp"

namespace mc {

struct UniaxialSpec;

// What a virtual uniaxial compression test gives (Tang §5.2); NaN where the curve does not tell.
struct UniaxialResult {
  double modulus = kNaN;            // E [Pa], secant between 25 % and 50 % of the peak
  double poisson = kNaN;            // ν
  double ucs = kNaN;                // peak axial stress [Pa]: f_c, or in tension f_t
  double strain_at_peak = kNaN;
  double initiation_stress = kNaN;  // when the cracks reach 1 % of their count at the peak [Pa]
  double cracks_at_peak = kNaN, cracks_tensile = kNaN, cracks_shear = kNaN;
  bool cracks_by_yield = false;     // no break at all: the first yields (damage onsets) were counted instead
  // In tension (Šmilauer Fig. 19): G_f [J/m²], the gauge length [m] and the strain where the stress fell to 0.2 f_t.
  double fracture_energy = kNaN, gauge_length = kNaN, strain_at_02ft = kNaN;
};

// From the histories of a run (name → series) / from its output file.
UniaxialResult uniaxial_result(const UniaxialSpec& u, std::map<std::string, std::vector<double>>& histories);
UniaxialResult uniaxial_result(const std::string& output_file);

std::string summary_json(const std::string& output_file);
// A number for JSON: 10 significant digits, null when not finite.
std::string json_number(double x);

}  // namespace mc
