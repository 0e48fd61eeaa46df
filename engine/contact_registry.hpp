// The contact models a scene can name. Adding a model: its header/source pair, a reader `X_model(Table)`,
// and one line in contact_registry.cpp.
#pragma once
#include <memory>

#include "engine/contact_set.hpp"
#include "engine/scene.hpp"
#include "engine/toml_reader.hpp"

namespace mc {

template <class Model>
ModelSpec model_spec(const typename Model::Params& p) {
  return {Model::name, requires { Model::bondable; }, requires { Model::yields; }, requires { Model::only_3d; }, [p] { return std::unique_ptr<ContactSetBase<2>>(new ContactSet<Model, 2>(p)); },
          [p] { return std::unique_ptr<ContactSetBase<3>>(new ContactSet<Model, 3>(p)); }};
}

ModelSpec linear_model(const Table& t);
ModelSpec hertz_mindlin_model(const Table& t);
ModelSpec parallel_bond_model(const Table& t);
ModelSpec contact_bond_model(const Table& t);
ModelSpec softening_bond_model(const Table& t);
ModelSpec cpm_model(const Table& t);

}  // namespace mc
