// A concrete from its strength class by the fib Model Code 2010 (§5.1): the mean compressive and tensile strengths,
// the fracture energy and the moduli that a calibration can take as its targets when no test of the concrete is at
// hand. SI units throughout (the code's relations are in MPa and N/m; converted here).
#pragma once
#include <string>
#include <vector>

namespace mc {

struct ModelCodeConcrete {
  std::string name;          // "C30/37"
  double f_ck = 0;           // characteristic cylinder strength [Pa]
  double f_ck_cube = 0;      // characteristic cube strength [Pa]
  double f_cm = 0;           // mean compressive strength f_ck + Δf, Δf = 8 MPa (5.1-1)
  double f_ctm = 0;          // mean tensile strength (5.1-3a/b)
  double f_ctk_min = 0;      // 0.7 f_ctm (5.1-4)
  double f_ctk_max = 0;      // 1.3 f_ctm (5.1-5)
  double fracture_energy = 0;  // G_F = 73 f_cm^0.18 [N/m] (5.1-9)
  double e_ci = 0;           // tangent modulus at the origin, E_c0 α_E (f_cm/10)^(1/3) (5.1-21)
  double e_c = 0;            // reduced modulus α_i E_ci, α_i = 0.8 + 0.2 f_cm/88 ≤ 1 (5.1-23, 5.1-24)
  double poisson = 0.2;      // §5.1.7.3: 0.14 to 0.26; 0.2 for design
  double alpha_e = 1.0;      // the aggregate's factor on E_ci (Table 5.1-6)
  std::string aggregate;     // "quartzite", "basalt", "limestone" or "sandstone"
};

// The code's strength classes, "C12/15" to "C120/140".
std::vector<std::string> model_code_classes();
// The aggregates of Table 5.1-6 and their α_E.
std::vector<std::pair<std::string, double>> model_code_aggregates();

// Throws InputError naming the class or aggregate and listing the allowed ones.
ModelCodeConcrete model_code_concrete(const std::string& strength_class, const std::string& aggregate = "quartzite");

// What `mesocrack concrete CLASS` prints: the values with their units and the calibrate targets they give.
std::string model_code_json(const ModelCodeConcrete& m);

}  // namespace mc
