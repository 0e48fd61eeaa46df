// Scene → World: the specimen (inline, sphere list, earlier output, or generated), phases and the contact
// model table, walls, boundary groups and the declared physics.
#pragma once
#include "scene/scene.hpp"
#include "engine/world.hpp"

namespace mc {

template <int D>
World<D> build_world(const Scene& scene);

}  // namespace mc
