#include "scene/model_registry.hpp"

#include <cstdio>
#include <functional>
#include <memory>

namespace mc {

namespace {

struct Entry {
  std::string name;
  bool only_3d;
  const KeyTable* keys;
  std::function<ModelSpec(const Table&)> read;
};

template <class Model>
Entry entry() {
  constexpr bool only_3d = requires { Model::only_3d; };
  constexpr bool yields = requires { Model::yields; };
  auto read = [](const Table& t) {
    const auto p = read_keys<typename Model::Params>(t, Model::keys());
    return ModelSpec{Model::name, BondModel<Model, 3>, yields,
                     [p] { return std::unique_ptr<ContactSetBase<2>>(new ContactSet<Model, 2>(p)); },
                     [p] { return std::unique_ptr<ContactSetBase<3>>(new ContactSet<Model, 3>(p)); }};
  };
  return {Model::name, only_3d, &Model::keys(), read};
}

template <class... Models>
std::vector<Entry> entries(std::tuple<Models...>*) {
  return {entry<Models>()...};
}

const std::vector<Entry>& registry() {
  static const std::vector<Entry> r = entries(static_cast<RegisteredModels*>(nullptr));
  return r;
}

}  // namespace

std::vector<std::string> contact_model_names() { return contact_model_names(3); }

std::vector<std::string> contact_model_names(int dimension) {
  std::vector<std::string> names;
  for (const Entry& e : registry())
    if (dimension == 3 || !e.only_3d) names.push_back(e.name);
  return names;
}

std::vector<const KeyTable*> contact_model_keys() {
  std::vector<const KeyTable*> keys;
  for (const Entry& e : registry()) keys.push_back(e.keys);
  return keys;
}

ModelSpec read_contact_model(const KeyReader& k, const std::string& name, int dimension) {
  for (const Entry& e : registry()) {
    if (e.name != name) continue;
    if (e.only_3d && dimension == 2) {
      std::string allowed;
      for (const auto& n : contact_model_names(2)) allowed += (allowed.empty() ? "" : ", ") + n;
      k.fail("model", "the " + name +
                          " model is a law for spheres (its cross-sections, calibration and interaction "
                          "radius are 3D): use it with dimension = 3, or a 2D model (" +
                          allowed + ")");
    }
    return e.read(k.table());
  }
  k.fail("model", "unknown contact model");  // unreachable: the caller validated the name with choice()
}

int contacts_entry(const TomlDoc& doc, const std::string& model) {
  const std::vector<Table> contacts = tables_of(doc.root(), contacts_keys());
  int found = -1;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const KeyReader k(contacts[i], contacts_keys());
    if (k.string("model", "") != model) continue;
    if (found >= 0)
      k.fail("model", "calibrate works on one " + model +
                                    " phase pair; this scene has several [[contacts]] "
                                    "with model = \"" +
                                    model + "\" (calibrate each material in its own scene)");
    found = static_cast<int>(i);
  }
  return found;
}

std::vector<std::string> facet_law_overrides(int entry, bool by_facets, double stiffness, double ratio,
                                             double tensile_strength, double fracture_energy) {
  auto line = [&](const char* key, double value, const char* unit) {
    char b[64];
    std::snprintf(b, sizeof b, "%.10g%s%s", value, *unit ? " " : "", unit);
    return "contacts[" + std::to_string(entry) + "]." + key + "=" + b;
  };
  std::vector<std::string> out = {line(by_facets ? "E0" : "modulus", stiffness, "Pa"),
                                  line(by_facets ? "alpha" : "poisson_ratio", ratio, "")};
  if (tensile_strength > 0) {
    out.push_back(line("tensile_strength", tensile_strength, "Pa"));
    out.push_back(line("fracture_energy", fracture_energy, "N/m"));
  }
  return out;
}

}  // namespace mc
