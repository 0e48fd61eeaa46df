// The parallel-bonded 3D block of the throughput benchmark's scaling section, which split_scaling and access_floor
// time too: a dense random assembly (dense_assembly.hpp) with every pair whose gap is ≤ 0.1 R_min bonded by
// parallel bonds that do not break (the shared specimen's model), and the particles near the faces held in place of
// walls.
#pragma once
#include <cstddef>

#include "benchmarks/dense_assembly.hpp"
#include "benchmarks/throughput_world.hpp"

namespace mc::bench {

// The block on assembly `a`; `bonds`, when given, receives the number of bonds made.
inline World<3> bonded_block(const Assembly<3>& a, std::size_t* bonds = nullptr) {
  Material mat;
  mat.bonded = true;
  World<3> w = make_world<3>(a.x, a.r, mat);
  for (std::size_t i = 0; i < a.x.size(); ++i)
    if (a.edge[i]) w.particles.fix[i] = fix_all(3);
  w.init();
  const std::size_t made = w.install_bonds(0.1, 1);
  if (bonds) *bonds = made;
  return w;
}

// The block of about `target` particles, from the full-size jammed cell.
inline World<3> bonded_block(int target) { return bonded_block(tile(cell_for_dim<3>(false), kR0, target, false)); }

}  // namespace mc::bench
