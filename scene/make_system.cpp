#include "scene/make_system.hpp"

#include "engine/errors.hpp"
#include "scene/explicit_system.hpp"
#ifdef MESOCRACK_RIGID_CELL
#include "scene/rigid_cell/rigid_cell_build.hpp"
#endif

namespace mc {

std::unique_ptr<System> make_system(const Scene& scene, const Exchange* exchange, double imbalance_limit) {
  if (scene.rigid_cell) {
#ifdef MESOCRACK_RIGID_CELL
    if (exchange && exchange->size() > 1)
      throw InputError(scene.file +
                       ": [rigid_cell]: a rigid-cell specimen runs in one process (its solver factorises "
                       "one matrix); run it without mpirun, or with mpirun -np 1");
    return make_rigid_cell_system(scene);
#else
    // Under mpirun too: telling this build to run the scene in one process would not help.
    throw InputError(scene.file +
                     ": [rigid_cell]: this mesocrack was built without the rigid-cell family; "
                     "configure with -DMESOCRACK_RIGID_CELL=ON");
#endif
  }
  if (scene.dimension == 2) return std::make_unique<ExplicitSystem<2>>(scene, exchange, imbalance_limit);
  return std::make_unique<ExplicitSystem<3>>(scene, exchange, imbalance_limit);
}

}  // namespace mc
