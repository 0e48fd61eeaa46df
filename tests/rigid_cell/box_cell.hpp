// A box as a rigid cell for the mass-property tests: its six faces about a node, whose pyramids fill it.
#pragma once
#include <array>
#include <vector>

#include "rigid_cell/mass_properties.hpp"

namespace mc::test {

// The six faces of the box [lo, hi], each about `apex`.
inline std::vector<std::array<Vec<3>, 4>> box_faces(const Vec<3>& lo, const Vec<3>& hi, const Vec<3>& apex) {
  std::vector<std::array<Vec<3>, 4>> faces;
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    for (double side : {lo[k], hi[k]}) {
      std::array<Vec<3>, 4> f;
      const double u[4] = {lo[i], hi[i], hi[i], lo[i]}, v[4] = {lo[j], lo[j], hi[j], hi[j]};
      for (int c = 0; c < 4; ++c) {
        f[c][k] = side;
        f[c][i] = u[c];
        f[c][j] = v[c];
        f[c] -= apex;
      }
      faces.push_back(f);
    }
  }
  return faces;
}

// The box's mass properties about `node`.
inline rigid_cell::MassProperties<3> box_cell(const Vec<3>& lo, const Vec<3>& hi, const Vec<3>& node) {
  rigid_cell::MassProperties<3> m;
  for (const auto& f : box_faces(lo, hi, node)) m += rigid_cell::pyramid<3>(f);
  return m;
}

}  // namespace mc::test
