#include "scene/make_system.hpp"

#include "scene/explicit_system.hpp"

namespace mc {

std::unique_ptr<System> make_system(const Scene& scene) {
  if (scene.dimension == 2) return std::make_unique<ExplicitSystem<2>>(scene);
  return std::make_unique<ExplicitSystem<3>>(scene);
}

}  // namespace mc
