#include "scene/overrides.hpp"

#include <optional>
#include <regex>
#include <sstream>

#include "engine/errors.hpp"
#include "scene/text.hpp"
#include "scene/toml_document.hpp"

namespace mc::detail {
namespace {

// An override's value is TOML when it parses as one (5, 2.5e9, true, "x", [1, 2]), else a bare string, so
// that --set contact.model=hertz_mindlin and --set walls[0].velocity="5 mm/s" both work.
Value override_value(const std::string& text) {
  try {
    const auto doc = parse_toml("v = " + text, "--set");
    if (doc.as_table().size() == 1) return doc.as_table().at("v");
  } catch (const toml::exception&) {
  }
  return Value(text);
}

struct Step {
  std::string key;
  std::optional<std::size_t> index;
};

// "walls[1].velocity" -> {walls, 1}, {velocity}; empty when the path is malformed.
std::vector<Step> parse_key_path(const std::string& path) {
  static const std::regex segment(R"(([A-Za-z0-9_-]+)(?:\[(\d{1,9})\])?)");
  std::vector<Step> steps;
  std::istringstream in(path);
  std::string part;
  std::smatch m;
  while (std::getline(in, part, '.')) {
    if (!std::regex_match(part, m, segment)) return {};
    steps.push_back({m[1].str(), m[2].matched ? std::optional<std::size_t>(std::stoul(m[2].str())) : std::nullopt});
  }
  if (path.empty() || path.back() == '.') return {};
  return steps;
}

// Replaces the value but keeps the comments written above it, which the re-serialised text keeps too.
void assign(Value& target, const Value& v) {
  auto comments = target.comments();
  target = v;
  target.comments() = std::move(comments);
}

// One override: walks its key path from the root and assigns the value at the end.
class OverrideApplier {
 public:
  OverrideApplier(TomlState& st, std::string spec) : st_(st), spec_(std::move(spec)) {}

  void apply() {
    const auto eq = spec_.find('=');
    if (eq == std::string::npos) fail("expected key=value, e.g. --set contact.model=hertz_mindlin");
    const std::string path = trim(spec_.substr(0, eq));
    const auto steps = parse_key_path(path);
    if (steps.empty()) fail("'" + path + "' is not a key path such as material.density or walls[1].velocity");
    Value* node = &st_.root;
    std::string walked;
    for (std::size_t i = 0; i < steps.size(); ++i) {
      if (!node->is_table()) fail("'" + walked + "' is not a table");
      walked = join_key(walked, steps[i].key);
      node = step_into(node->as_table(), steps[i], walked, i + 1 == steps.size());
      if (steps[i].index) walked = index_key(walked, *steps[i].index);
    }
    assign(*node, override_value(trim(spec_.substr(eq + 1))));
    st_.set_paths.push_back(walked);
  }

 private:
  // Plain keys are created when missing (a user may add a key the file lacks); array entries are not.
  Value* step_into(Value::table_type& table, const Step& s, const std::string& walked, bool last) {
    if (!s.index) {
      if (!last && table.count(s.key) == 0) table[s.key] = Value(Value::table_type{});
      return &table[s.key];
    }
    if (table.count(s.key) == 0 || !table.at(s.key).is_array()) fail("'" + walked + "' is not an array");
    auto& array = table.at(s.key).as_array();
    if (*s.index >= array.size())
      fail("index " + std::to_string(*s.index) + " is past the end of '" + walked + "', which has " +
           std::to_string(array.size()) + (array.size() == 1 ? " entry" : " entries") + " (indices start at 0)");
    return &array[*s.index];
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(st_.file + ": --set '" + spec_ + "': " + what);
  }

  TomlState& st_;
  std::string spec_;
};

}  // namespace

void apply_overrides(TomlState& st, const std::vector<std::string>& overrides) {
  for (const auto& o : overrides) OverrideApplier(st, o).apply();
}

std::string serialise(const TomlState& st, const std::vector<std::string>& overrides) {
  Value root = st.root;
  std::vector<std::string> head{" Re-serialised by mesocrack with these --set overrides applied:"};
  for (const auto& o : overrides) head.push_back("   " + std::regex_replace(o, std::regex("\n"), "\\n"));
  root.comments().insert(root.comments().begin(), head.begin(), head.end());
  // 15 digits print what the user typed (0.1, not 0.10000000000000001); 17 digits are always exact.
  const std::string short_form = toml::format(root, 80, 15);
  return parse_scene_text(short_form, "re-serialised") == root ? short_form : toml::format(root, 80, 17);
}

}  // namespace mc::detail
