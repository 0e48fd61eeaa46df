// The system a scene runs on: the one place where a solver family is chosen (today the explicit particle world;
// a second family adds its branch here, docs/ARCHITECTURE.md, "Add a solver family").
#pragma once
#include <memory>

#include "engine/exchange.hpp"
#include "engine/system.hpp"
#include "scene/scene.hpp"

namespace mc {

// Builds the system (a generated specimen is generated here). The scene must outlive it. With an exchange of more
// than one process, the processes run one specimen split across them (the explicit family; ExplicitSystem), and
// draw their regions afresh when the most loaded owns more than (1 + imbalance_limit) times the mean (0: never).
std::unique_ptr<System> make_system(const Scene& scene, const Exchange* exchange = nullptr, double imbalance_limit = 0);

}  // namespace mc
