// Scene text that tests build their small scenes from.
#pragma once
#include <string>

namespace mc::test {

// The head of a scene of one phase of grains ("g", 2600 kg/m³) with a linear contact of E_c = 50 MPa: the
// specimen, walls and the rest follow it.
inline std::string linear_grains(int dimension) {
  return "dimension = " + std::to_string(dimension) +
         "\n[[phases]]\nname = \"g\"\ndensity = 2600\n[[contacts]]\nphase_a = \"g\"\nmodel = \"linear\"\n"
         "modulus = \"50 MPa\"\n";
}

}  // namespace mc::test
