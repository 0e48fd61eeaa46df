#include "scene/model_registry.hpp"

#include <functional>
#include <memory>

#include "scene/model_keys.hpp"

namespace mc {

namespace {

struct Entry {
  std::string name;
  bool only_3d;
  std::function<ModelSpec(const Table&)> read;
};

template <class Model>
Entry entry() {
  return {Model::name, requires {Model::only_3d;
}
,
    [](const Table& t) {
      const typename Model::Params p = read_params<Model>(t);
      return ModelSpec{Model::name, BondModel<Model, 3>, requires {Model::yields;
    },
    [p] { return std::unique_ptr<ContactSetBase<2>>(new ContactSet<Model, 2>(p)); },
    [p] { return std::unique_ptr<ContactSetBase<3>>(new ContactSet<Model, 3>(p)); }
};
}
}
;
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

ModelSpec read_contact_model(const Table& t, const std::string& name, int dimension) {
  for (const Entry& e : registry()) {
    if (e.name != name) continue;
    if (e.only_3d && dimension == 2) {
      std::string allowed;
      for (const auto& n : contact_model_names(2)) allowed += (allowed.empty() ? "" : ", ") + n;
      t.fail("model", "the " + name +
                          " model is a law for spheres (its cross-sections, calibration and interaction "
                          "radius are 3D): use it with dimension = 3, or a 2D model (" +
                          allowed + ")");
    }
    return e.read(t);
  }
  t.fail("model", "unknown contact model");  // unreachable: the caller validated the name with choice()
}

}  // namespace mc
