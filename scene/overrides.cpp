#include "scene/overrides.hpp"

#include <algorithm>
#include <optional>
#include <sstream>

#include "engine/errors.hpp"
#include "scene/text.hpp"
#include "scene/toml_document.hpp"
#include "scene/toml_nesting.hpp"
#include "scene/toml_writer.hpp"

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

// "walls[1]" -> {walls, 1}, "velocity" -> {velocity}; nothing when it is not a bare key with an optional index.
std::optional<Step> parse_step(const std::string& part) {
  static const std::string key_chars = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-";
  const auto end = part.find_first_not_of(key_chars);
  Step step{part.substr(0, end), std::nullopt};
  if (step.key.empty()) return std::nullopt;
  if (end == std::string::npos) return step;
  const std::string digits = part.substr(end + 1, part.size() - end - 2);  // between '[' and ']'
  const bool index = part[end] == '[' && part.back() == ']' && !digits.empty() && digits.size() <= 9 &&
                     digits.find_first_not_of("0123456789") == std::string::npos;
  if (!index) return std::nullopt;
  step.index = std::stoul(digits);
  return step;
}

// "walls[1].velocity" -> {walls, 1}, {velocity}; empty when the path is malformed. No std::regex: libstdc++'s
// recurses once per character, and a path may be as long as the command line allows.
std::vector<Step> parse_key_path(const std::string& path) {
  std::vector<Step> steps;
  std::istringstream in(path);
  for (std::string part; std::getline(in, part, '.');) {
    const auto step = parse_step(part);
    if (!step) return {};
    steps.push_back(*step);
  }
  if (path.empty() || path.back() == '.') return {};
  return steps;
}

// The tables and arrays around the value a path names: "walls[1].velocity" sits in walls and walls[1].
std::size_t nesting_of(const std::vector<Step>& steps) {
  return steps.size() - 1 + static_cast<std::size_t>(std::count_if(steps.begin(), steps.end(), [](const Step& s) {
           return s.index.has_value();
         }));
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
    if (first_non_utf8(spec_)) fail("not UTF-8 text; allowed: UTF-8, as in scene files");
    const auto eq = spec_.find('=');
    if (eq == std::string::npos) fail("expected key=value, e.g. --set contact.model=hertz_mindlin");
    const std::string path = trim(spec_.substr(0, eq));
    const auto steps = parse_key_path(path);
    if (steps.empty())
      fail("'" + shorten(printable(path)) + "' is not a key path such as material.density or walls[1].velocity");
    const std::string value = trim(spec_.substr(eq + 1));
    check_nesting(steps, value);
    Value* node = &st_.root;
    std::string walked;
    for (std::size_t i = 0; i < steps.size(); ++i) {
      if (!node->is_table()) fail("'" + shorten(printable(walked)) + "' is not a table");
      walked = join_key(walked, steps[i].key);
      node = step_into(node->as_table(), steps[i], walked, i + 1 == steps.size());
      if (steps[i].index) walked = index_key(walked, *steps[i].index);
    }
    assign(*node, override_value(value));
    st_.set_paths.push_back(walked);
  }

 private:
  // Plain keys are created when missing (a user may add a key the file lacks); array entries are not.
  Value* step_into(Value::table_type& table, const Step& s, const std::string& walked, bool last) {
    if (!s.index) {
      if (!last && table.count(s.key) == 0) table[s.key] = Value(Value::table_type{});
      return &table[s.key];
    }
    if (table.count(s.key) == 0 || !table.at(s.key).is_array())
      fail("'" + shorten(printable(walked)) + "' is not an array");
    auto& array = table.at(s.key).as_array();
    if (*s.index >= array.size())
      fail("index " + std::to_string(*s.index) + " is past the end of '" + shorten(printable(walked)) +
           "', which has " + std::to_string(array.size()) + (array.size() == 1 ? " entry" : " entries") +
           " (indices start at 0)");
    return &array[*s.index];
  }

  // The path and the value together nest no deeper than a scene file may (scene/toml_nesting.hpp).
  void check_nesting(const std::vector<Step>& steps, const std::string& value) const {
    const std::size_t path = nesting_of(steps);
    if (path <= kMaxNesting && !toml_nesting("v = " + value, kMaxNesting - path).too_deep) return;
    fail("the key path and its value nest tables and arrays more than " + std::to_string(kMaxNesting) +
         " levels deep; allowed: at most " + std::to_string(kMaxNesting));
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(st_.file + ": --set '" + shorten(printable(spec_)) + "': " + what);
  }

  TomlState& st_;
  std::string spec_;
};

// A comment line cannot hold a newline: written as \n.
std::string one_line(const std::string& s) {
  std::string out;
  for (const char c : s) out += c == '\n' ? std::string("\\n") : std::string(1, c);
  return out;
}

}  // namespace

void apply_overrides(TomlState& st, const std::vector<std::string>& overrides) {
  for (const auto& o : overrides) OverrideApplier(st, o).apply();
}

std::string serialise(const TomlState& st, const std::vector<std::string>& overrides) {
  Value root = st.root;
  std::vector<std::string> head{" Re-serialised by mesocrack with these --set overrides applied:"};
  for (const auto& o : overrides) head.push_back("   " + one_line(o));
  root.comments().insert(root.comments().begin(), head.begin(), head.end());
  // 15 digits print what the user typed (0.1, not 0.10000000000000001); 17 digits are always exact.
  const std::string short_form = write_toml(root, 15);
  return parse_scene_text(short_form, "re-serialised") == root ? short_form : write_toml(root, 17);
}

}  // namespace mc::detail
