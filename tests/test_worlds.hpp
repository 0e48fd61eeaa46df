// Small worlds built in code for the physics tests (the scene files are tested separately).
#pragma once
#include <cstdint>
#include <memory>

#include "contact_models/hertz_mindlin.hpp"
#include "contact_models/linear.hpp"
#include "engine/world.hpp"

namespace mc::test {

// Deterministic uniform numbers in [0, 1) (splitmix64): the same on every platform and standard library.
struct Rng {
  std::uint64_t s;
  double operator()() {
    std::uint64_t z = (s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53;
  }
};

// A world whose single phase 0 interacts through one model; the domain is wide open.
template <int D, class Model>
World<D> single_model_world(const typename Model::Params& params) {
  World<D> w;
  w.sets.push_back(std::make_unique<ContactSet<Model, D>>(params));
  w.model_of = {{0}};
  w.domain_lo = Vec<D>::Constant(-1e3);
  w.domain_hi = Vec<D>::Constant(1e3);
  return w;
}

// Six infinite walls bounding the cube [lo, hi]³, normals inwards.
inline void add_box_walls(World<3>& w, double lo, double hi, const WallMaterial& wm) {
  for (int d = 0; d < 3; ++d) {
    const Vec<3> e = Vec<3>::Unit(d);
    w.walls.push_back(Wall<3>::plane(lo * e, e));
    w.walls.push_back(Wall<3>::plane(hi * e, -e));
    w.walls[w.walls.size() - 2].material = wm;
    w.walls.back().material = wm;
  }
}

}  // namespace mc::test
