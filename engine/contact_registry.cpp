#include "engine/contact_registry.hpp"

#include <utility>

namespace mc {

namespace {
using Reader = ModelSpec (*)(const Table&);
const std::vector<std::pair<std::string, Reader>>& registry() {
  static const std::vector<std::pair<std::string, Reader>> r = {
      {"linear", linear_model},
      {"hertz_mindlin", hertz_mindlin_model},
      {"parallel_bond", parallel_bond_model},
      {"contact_bond", contact_bond_model},
      {"softening_bond", softening_bond_model},
      {"cpm", cpm_model},
  };
  return r;
}
}  // namespace

const std::vector<std::string>& contact_model_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const auto& [name, _] : registry()) n.push_back(name);
    return n;
  }();
  return names;
}

ModelSpec read_contact_model(const Table& t, const std::string& name) {
  for (const auto& [n, read] : registry())
    if (n == name) return read(t);
  t.fail("model", "unknown contact model");  // unreachable: the caller validated the name with choice()
}

}  // namespace mc
