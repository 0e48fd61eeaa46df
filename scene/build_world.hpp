// Scene → World: the specimen (inline, sphere list, earlier output, or generated), its mesostructure and the
// particles' heterogeneity, the contact-model table, walls, boundary groups and the declared physics. What the
// scene knows of the particles beyond their physics (ids, groups, what generating them measured, outlines for
// drawing) goes to SpecimenInfo, not into the world.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "engine/world.hpp"
#include "scene/scene.hpp"

namespace mc {

struct SpecimenInfo {
  std::vector<std::int64_t> ids;         // the specimen's own particle ids (a sphere list's first column), per index
  std::vector<std::vector<int>> groups;  // members of the scene's [[groups]], in its order
  std::vector<std::pair<std::string, double>> facts;  // what generating the specimen measured
  // Aggregate outlines in the picture plane (2D: x–y; 3D: the section through the specimen's middle along y,
  // as (x, z)), for drawing.
  std::vector<std::vector<std::array<double, 2>>> outlines;
};

template <int D>
World<D> build_world(const Scene& scene, SpecimenInfo& info);

}  // namespace mc
