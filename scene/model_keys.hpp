// The scene keys of each contact model ([[contacts]] entries): read_params<Model> reads and validates them
// into the model's Params. One specialisation per registered model (scene/model_registry.hpp), defined in
// scene/model_keys.cpp; the keys are listed in README.md, "[[contacts]]".
#pragma once
#include "contact_models/contact_bond.hpp"
#include "contact_models/cpm.hpp"
#include "contact_models/hertz_mindlin.hpp"
#include "contact_models/linear.hpp"
#include "contact_models/parallel_bond.hpp"
#include "contact_models/softening_bond.hpp"
#include "scene/toml_reader.hpp"

namespace mc {

template <class Model>
typename Model::Params read_params(const Table& t);

template <>
LinearParams read_params<Linear>(const Table& t);
template <>
HertzMindlinParams read_params<HertzMindlin>(const Table& t);
template <>
ParallelBondParams read_params<ParallelBond>(const Table& t);
template <>
ContactBondParams read_params<ContactBond>(const Table& t);
template <>
SofteningBondParams read_params<SofteningBond>(const Table& t);
template <>
CpmParams read_params<Cpm>(const Table& t);

}  // namespace mc
