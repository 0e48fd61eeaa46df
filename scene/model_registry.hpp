// The contact models a scene can name: one list, RegisteredModels. The registry reads a [[contacts]] entry's keys
// through the model's own key table (Model::keys(), beside its Params) and makes the model's contact sets; the names
// and the dimensions each model is available in come from the models themselves (Model::name, Model::only_3d).
// Adding a model: its header/source pair in contact_models/, and its type here.
#pragma once
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "contact_models/contact_bond.hpp"
#include "contact_models/cpm.hpp"
#include "contact_models/hertz_mindlin.hpp"
#include "contact_models/linear.hpp"
#include "contact_models/parallel_bond.hpp"
#include "contact_models/rolling_resistance.hpp"
#include "contact_models/softening_bond.hpp"
#include "scene/key_reader.hpp"
#include "scene/scene.hpp"
#include "scene/scene_keys.hpp"
#include "scene/toml_reader.hpp"

namespace mc {

using RegisteredModels =
    std::tuple<Linear, HertzMindlin, RollingResistance, ParallelBond, ContactBond, SofteningBond, Cpm>;

// The names of every registered model, and of those available in a scene of this dimension, in registry order.
std::vector<std::string> contact_model_names();
std::vector<std::string> contact_model_names(int dimension);
// The key tables of every registered model, in registry order.
std::vector<const KeyTable*> contact_model_keys();

// Reads the [[contacts]] entry `k` for the model `name` (one of contact_model_names(), which the caller checked
// with choice); a model not available in this dimension is refused, naming those that are.
ModelSpec read_contact_model(const KeyReader& k, const std::string& name, int dimension);

// The index of the one [[contacts]] entry of the scene whose model is `model`; −1 when there is none, InputError
// (naming the entry) when there are several.
int contacts_entry(const TomlDoc& doc, const std::string& model);

// The parameters of the scene's [[contacts]] entry `entry`, read as a `Model` through its key table.
template <class Model>
typename Model::Params contact_params(const TomlDoc& doc, int entry) {
  return read_keys<typename Model::Params>(tables_of(doc.root(), contacts_keys()).at(static_cast<std::size_t>(entry)),
                                           Model::keys());
}

// Fails as the scene reader does, naming the key of the entry that fills member m of the model's parameters: for
// what a study requires of them ("file: key 'contacts[0].kt_kn_ratio' = 0: ...").
template <class Model, class T>
[[noreturn]] void fail_contact_key(const TomlDoc& doc, int entry, T Model::Params::*m, const std::string& what) {
  const KeyTable& keys = Model::keys();
  const Key* k = keys.filling(offset_of(m));
  if (!k) throw std::logic_error("fail_contact_key: no key of " + std::string(keys.name) + " fills the member");
  KeyReader(tables_of(doc.root(), contacts_keys()).at(static_cast<std::size_t>(entry)), keys).fail(k->name, what);
}

// The --set lines that give a rigid-cell scene's facet_damage entry `entry` its elastic constants, f_t and G_t: E₀
// and α when `by_facets` (the scene gives those), else the macroscopic modulus and poisson_ratio (Květoň (3.8)).
std::vector<std::string> facet_law_overrides(int entry, bool by_facets, double stiffness, double ratio,
                                             double tensile_strength, double fracture_energy);

// The --set lines "contacts[entry].key=value" that change the entry's parameters from `from` to `to`.
template <class Model>
std::vector<std::string> contact_overrides(int entry, const typename Model::Params& from,
                                           const typename Model::Params& to) {
  return changed_keys("contacts[" + std::to_string(entry) + "]", Model::keys(), &from, &to);
}

}  // namespace mc
