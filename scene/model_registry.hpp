// The contact models a scene can name: one list, RegisteredModels. The registry reads a [[contacts]] entry's
// keys with read_params<Model> (scene/model_keys.cpp) and makes the model's contact sets; the names and the
// dimensions each model is available in come from the models themselves (Model::name, Model::only_3d).
// Adding a model: its header/source pair in contact_models/, a read_params specialisation, and its type here.
#pragma once
#include <string>
#include <tuple>
#include <vector>

#include "contact_models/contact_bond.hpp"
#include "contact_models/cpm.hpp"
#include "contact_models/hertz_mindlin.hpp"
#include "contact_models/linear.hpp"
#include "contact_models/parallel_bond.hpp"
#include "contact_models/softening_bond.hpp"
#include "scene/scene.hpp"
#include "scene/toml_reader.hpp"

namespace mc {

using RegisteredModels = std::tuple<Linear, HertzMindlin, ParallelBond, ContactBond, SofteningBond, Cpm>;

// The names of every registered model, and of those available in a scene of this dimension, in registry order.
std::vector<std::string> contact_model_names();
std::vector<std::string> contact_model_names(int dimension);

// Reads the [[contacts]] entry `t` for the model `name` (one of contact_model_names(), which the caller checked
// with Table::choice); a model not available in this dimension is refused, naming those that are.
ModelSpec read_contact_model(const Table& t, const std::string& name, int dimension);

}  // namespace mc
