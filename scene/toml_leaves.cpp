// TomlDoc::leaves(): the document as a flat list of key paths and values, for comparing two scenes key by key.
#include <toml.hpp>

#include "scene/toml_document.hpp"
#include "scene/toml_reader.hpp"

namespace mc {

namespace {

using detail::Value;

// An array whose entries are all tables is a [[table]] list: its entries are walked with index paths, so a
// difference is named at the key that differs, not at the whole list.
bool is_table_list(const Value& v) {
  if (!v.is_array() || v.as_array().empty()) return false;
  for (const auto& e : v.as_array())
    if (!e.is_table()) return false;
  return true;
}

void walk(const Value& v, const std::string& path, std::vector<TomlLeaf>& out) {
  if (v.is_table()) {
    for (const auto& [key, child] : v.as_table()) walk(child, detail::join_key(path, key), out);
  } else if (is_table_list(v)) {
    const auto& entries = v.as_array();
    for (std::size_t i = 0; i < entries.size(); ++i) walk(entries[i], detail::index_key(path, i), out);
  } else {
    Value bare = v;
    bare.comments().clear();  // a comment is not part of the value
    // 17 digits tell every two doubles apart; 15 print what the user typed (0.3, not 0.29999999999999999).
    out.push_back({path, toml::format(bare, 0, 17), toml::format(bare, 0, 15)});
  }
}

}  // namespace

std::vector<TomlLeaf> TomlDoc::leaves() const {
  std::vector<TomlLeaf> out;
  walk(state_->root, "", out);
  return out;
}

}  // namespace mc
