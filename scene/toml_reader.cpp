#include "scene/toml_reader.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <deque>
#include <numbers>
#include <regex>
#include <sstream>
#include <string_view>
#include <utility>

#include <toml.hpp>

#include "engine/errors.hpp"

namespace mc {
namespace detail {

// toml11 3.7 stores tables in std::unordered_map unless told otherwise and has no ordered map of its own
// (its docs suggest tsl::ordered_map, which is not installed). This insertion-ordered map keeps the file's
// key order for keys(), unknown-key reports and the re-serialised text. Lookup is linear: scene tables are small.
template <class Key, class T, class... Unused>
class OrderedMap {
 public:
  using key_type = Key;
  using mapped_type = T;
  using value_type = std::pair<Key, T>;  // not pair<const Key, T>: std::vector needs assignable elements
  using iterator = typename std::vector<value_type>::iterator;
  using const_iterator = typename std::vector<value_type>::const_iterator;
  using size_type = std::size_t;

  OrderedMap() = default;
  template <class It>
  OrderedMap(It first, It last) {
    for (; first != last; ++first) insert(*first);
  }

  iterator begin() { return items_.begin(); }
  iterator end() { return items_.end(); }
  const_iterator begin() const { return items_.begin(); }
  const_iterator end() const { return items_.end(); }
  size_type size() const { return items_.size(); }
  bool empty() const { return items_.empty(); }

  iterator find(const Key& k) { return std::find_if(begin(), end(), [&](const auto& kv) { return kv.first == k; }); }
  const_iterator find(const Key& k) const {
    return std::find_if(begin(), end(), [&](const auto& kv) { return kv.first == k; });
  }
  size_type count(const Key& k) const { return find(k) == end() ? 0 : 1; }
  T& at(const Key& k) { return checked(find(k))->second; }
  const T& at(const Key& k) const { return checked(find(k))->second; }
  T& operator[](const Key& k) { return insert(value_type(k, T{})).first->second; }

  std::pair<iterator, bool> insert(const value_type& kv) {
    const auto it = find(kv.first);
    if (it != end()) return {it, false};
    items_.push_back(kv);
    return {std::prev(end()), true};
  }
  template <class... Args>
  std::pair<iterator, bool> emplace(Args&&... args) {
    return insert(value_type(std::forward<Args>(args)...));
  }

  // Order-insensitive, like the maps toml11 expects: the serialiser writes sub-tables after plain keys.
  friend bool operator==(const OrderedMap& a, const OrderedMap& b) {
    return a.size() == b.size() && std::all_of(a.begin(), a.end(), [&](const auto& kv) {
             const auto it = b.find(kv.first);
             return it != b.end() && it->second == kv.second;
           });
  }

 private:
  template <class It>
  It checked(It it) const {
    if (it == items_.end()) throw std::out_of_range("toml table: no such key");
    return it;
  }
  std::vector<value_type> items_;
};

using Value = toml::basic_value<toml::preserve_comments, OrderedMap, std::vector>;

struct Visit {
  std::string path;
  const Value* table;
  std::vector<std::string> known;  // keys the code asked for, in asking order: the "allowed here" list
};

struct TomlState {
  std::string file;
  std::string text;
  Value root;
  std::vector<std::string> set_paths;  // full key paths given by --set, to say so in messages
  std::deque<Visit> visits;            // a deque: Table::path() hands out references into it

  std::size_t visit(const std::string& path, const Value& table) {
    const auto it = std::find_if(visits.begin(), visits.end(), [&](const Visit& v) { return v.path == path; });
    if (it != visits.end()) return static_cast<std::size_t>(it - visits.begin());
    visits.push_back({path, &table, {}});
    return visits.size() - 1;
  }
};

// One key being read: where it is, and its value (nullptr when absent). Builds every error message.
struct Field {
  const TomlState& st;
  std::string key;  // full dotted path, e.g. "walls[1].velocity"
  const Value* value;

  Field element(std::size_t i) const { return {st, key + "[" + std::to_string(i) + "]", &value->as_array().at(i)}; }
  std::string label() const;
  [[noreturn]] void missing(const std::string& hint) const;
  [[noreturn]] void bad(const std::string& what) const;
  [[noreturn]] void out_of_range(const Range& r, Unit u, double si) const;
};

}  // namespace detail

namespace {

using detail::Field;
using detail::Value;
constexpr double kInf = std::numeric_limits<double>::infinity();

// ---------------------------------------------------------------- units

struct UnitDef {
  std::string_view name;
  Unit kind;
  int pow10;  // decimal prefix, applied to the exponent so that "5 mm/s" gives exactly 0.005
  double mul = 1.0;
  double div = 1.0;
};

constexpr UnitDef kUnits[] = {
    {"m", Unit::Length, 0},        {"cm", Unit::Length, -2},          {"mm", Unit::Length, -3},
    {"um", Unit::Length, -6},      {"s", Unit::Time, 0},              {"ms", Unit::Time, -3},
    {"us", Unit::Time, -6},        {"min", Unit::Time, 0, 60.0},      {"h", Unit::Time, 0, 3600.0},
    {"kg", Unit::Mass, 0},         {"g", Unit::Mass, -3},             {"t", Unit::Mass, 3},
    {"N", Unit::Force, 0},         {"kN", Unit::Force, 3},            {"MN", Unit::Force, 6},
    {"N*m", Unit::Moment, 0},      {"N m", Unit::Moment, 0},          {"kN*m", Unit::Moment, 3},
    {"kN m", Unit::Moment, 3},     {"Pa", Unit::Pressure, 0},         {"kPa", Unit::Pressure, 3},
    {"MPa", Unit::Pressure, 6},    {"GPa", Unit::Pressure, 9},        {"kg/m3", Unit::Density, 0},
    {"g/cm3", Unit::Density, 3},   {"t/m3", Unit::Density, 3},        {"m/s", Unit::Velocity, 0},
    {"mm/s", Unit::Velocity, -3},  {"mm/min", Unit::Velocity, -3, 1.0, 60.0},
    {"um/s", Unit::Velocity, -6},  {"m/s2", Unit::Acceleration, 0},   {"N/m", Unit::Stiffness, 0},
    {"kN/m", Unit::Stiffness, 3},  {"MN/m", Unit::Stiffness, 6},      {"GN/m", Unit::Stiffness, 9},
    {"N/mm", Unit::Stiffness, 3},  {"J", Unit::Energy, 0},            {"N*m", Unit::Energy, 0},
    {"mJ", Unit::Energy, -3},      {"rad", Unit::Angle, 0},           {"deg", Unit::Angle, 0, std::numbers::pi, 180.0},
    {"1/s", Unit::Rate, 0},        {"/s", Unit::Rate, 0},             {"Hz", Unit::Frequency, 0},
    {"kHz", Unit::Frequency, 3},   {"%", Unit::None, -2},
    // Last: a unit of two kinds ("N/m") is named in messages by its first, the stiffness.
    {"J/m2", Unit::EnergyPerArea, 0}, {"N/m", Unit::EnergyPerArea, 0},
};

struct KindDef {
  std::string_view noun;  // with its article, for "is a length, not an acceleration"
  std::string_view si;
  std::string_view number_example;
  std::string_view string_example;
};

const KindDef& kind_def(Unit u) {
  static constexpr KindDef defs[] = {
      {"a dimensionless number", "", "0.5", "50 %"},
      {"a length", "m", "0.002", "2 mm"},
      {"a time", "s", "1e-6", "1 us"},
      {"a mass", "kg", "0.5", "500 g"},
      {"a force", "N", "1000", "1 kN"},
      {"a moment", "N m", "10", "10 N*m"},
      {"a pressure", "Pa", "3e10", "30 GPa"},
      {"a density", "kg/m3", "2600", "2.6 g/cm3"},
      {"a velocity", "m/s", "0.005", "5 mm/s"},
      {"an acceleration", "m/s2", "9.81", "9.81 m/s2"},
      {"a stiffness", "N/m", "1e6", "1 MN/m"},
      {"an energy", "J", "0.001", "1 mJ"},
      {"an angle", "rad", "0.785", "45 deg"},
      {"a rate", "1/s", "0.1", "0.1 /s"},
      {"a frequency", "Hz", "1000", "1 kHz"},
      {"an energy per area", "J/m2", "100", "100 N/m"},
  };
  return defs[static_cast<int>(u)];
}

std::string join_list(const std::vector<std::string>& items, const std::string& last_sep) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) out += (i + 1 == items.size()) ? last_sep : ", ";
    out += items[i];
  }
  return out;
}

std::string allowed_units(Unit u) {
  if (u == Unit::None) return "a plain number or %";
  std::vector<std::string> names;
  for (const auto& d : kUnits)
    if (d.kind == u) names.emplace_back(d.name);
  return join_list(names, " or ");
}

// "a number in kg/m3, e.g. 2600 or "2.6 g/cm3"": the hint of a missing key.
std::string number_hint(Unit u) {
  const auto& k = kind_def(u);
  const std::string in = u == Unit::None ? "" : " in " + std::string(k.si);
  return "a number" + in + ", e.g. " + std::string(k.number_example) + " or \"" + std::string(k.string_example) + "\"";
}

std::string expected_number(Unit u) {
  const auto& k = kind_def(u);
  if (u == Unit::None) return "expected a number (or a percentage such as \"50 %\")";
  return "expected a number in " + std::string(k.si) + " (or a string with a unit such as \"" +
         std::string(k.string_example) + "\")";
}

const UnitDef* find_unit(std::string_view name, std::optional<Unit> kind) {
  for (const auto& d : kUnits)
    if (d.name == name && (!kind || d.kind == *kind)) return &d;
  return nullptr;
}

std::string unit_mismatch(const std::string& unit, Unit u) {
  const UnitDef* other = find_unit(unit, std::nullopt);
  const std::string noun(kind_def(u).noun);
  const std::string is = other ? "is " + std::string(kind_def(other->kind).noun) + ", not " + noun : "is not " + noun;
  return "unit '" + unit + "' " + is + "; use " + allowed_units(u);
}

// ---------------------------------------------------------------- formatting

std::string format_number(double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c == '\n' ? std::string("\\n") : std::string(1, c);
  }
  return out + "\"";
}

// A value as the user would write it, on one line (messages are one line).
std::string show_full(const Value& v) {
  if (v.is_string()) return quoted(v.as_string().str);
  if (v.is_floating()) {
    const std::string s = format_number(v.as_floating());
    return s.find_first_not_of("-0123456789") == std::string::npos ? s + ".0" : s;
  }
  if (v.is_array()) {
    std::vector<std::string> parts;
    for (const auto& e : v.as_array()) parts.push_back(show_full(e));
    return "[" + join_list(parts, ", ") + "]";
  }
  if (v.is_table()) {
    std::vector<std::string> parts;
    for (const auto& [k, e] : v.as_table()) parts.push_back(k + " = " + show_full(e));
    return "{" + join_list(parts, ", ") + "}";
  }
  return toml::format(v);  // integers, booleans, dates
}

std::string show(const Value& v) {
  constexpr std::size_t max_chars = 80;
  const std::string s = show_full(v);
  return s.size() <= max_chars ? s : s.substr(0, max_chars) + "...";
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  return b == std::string::npos ? "" : s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

std::string join_key(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }

// ---------------------------------------------------------------- reading values

// The decimal exponent is shifted rather than the value multiplied, so a quantity converts exactly as if
// the user had written it in SI ("0.01 mm/s" == 1e-5, "30 GPa" == 3e10).
double scaled(std::string num, const UnitDef& d) {
  int exponent = 0;
  if (const auto e = num.find_first_of("eE"); e != std::string::npos) {
    const char* first = num.data() + e + 1 + (num[e + 1] == '+');
    if (std::from_chars(first, num.data() + num.size(), exponent).ec != std::errc{}) return kInf;
    num.resize(e);
  }
  num += "e" + std::to_string(exponent + d.pow10);
  double x = 0.0;
  // Out of double range: report as non-finite rather than keep from_chars' untouched 0.
  if (std::from_chars(num.data(), num.data() + num.size(), x).ec != std::errc{}) return kInf;
  return x * d.mul / d.div;
}

// "30 GPa" -> 3e10 for Unit::Pressure; a string without a unit is taken as SI.
double quantity(const Field& f, const std::string& text, Unit u) {
  const std::string s = trim(text);
  if (s.empty()) f.bad(expected_number(u));
  const char* first = s.data() + (s[0] == '+');  // from_chars refuses a leading '+'
  const char* last = s.data() + s.size();
  double ignored = 0.0;
  const auto [end, ec] = std::from_chars(first, last, ignored);
  if (ec == std::errc::invalid_argument) f.bad(expected_number(u));
  const std::string unit = trim(std::string(end, last));
  static constexpr UnitDef si{"", Unit::None, 0};
  const UnitDef* def = unit.empty() ? &si : find_unit(unit, u);
  if (!def) f.bad(unit_mismatch(unit, u));
  return scaled(std::string(first, end), *def);
}

double read_number(const Field& f, Unit u, const Range& r) {
  const Value& v = *f.value;
  double x = 0.0;
  if (v.is_integer()) {
    x = static_cast<double>(v.as_integer());
  } else if (v.is_floating()) {
    x = v.as_floating();
  } else if (v.is_string()) {
    x = quantity(f, v.as_string().str, u);
  } else {
    f.bad(expected_number(u));
  }
  if (!std::isfinite(x)) f.bad("expected a finite number" + (u == Unit::None ? "" : " in " + std::string(kind_def(u).si)));
  if (!r.contains(x)) f.out_of_range(r, u, x);
  return x;
}

std::string array_hint(Unit u, std::size_t n) {
  const std::string count = n > 0 ? std::to_string(n) + " " : "";
  const std::string in = u == Unit::None ? "" : " in " + std::string(kind_def(u).si);
  return "an array of " + count + "numbers" + in;
}

std::int64_t read_integer(const Field& f, const Range& r) {
  if (!f.value->is_integer()) f.bad("expected an integer");
  const auto n = f.value->as_integer();
  if (!r.contains(static_cast<double>(n))) f.out_of_range(r, Unit::None, static_cast<double>(n));
  return n;
}

bool read_boolean(const Field& f) {
  if (!f.value->is_boolean()) f.bad("expected true or false");
  return f.value->as_boolean();
}

std::string read_string(const Field& f) {
  if (!f.value->is_string()) f.bad("expected a string");
  return f.value->as_string().str;
}

std::string read_choice(const Field& f, const std::vector<std::string>& allowed) {
  const std::string list = join_list(allowed, ", ");
  if (!f.value->is_string()) f.bad("expected a string, one of: " + list);
  const std::string& s = f.value->as_string().str;
  if (std::find(allowed.begin(), allowed.end(), s) == allowed.end()) f.bad("allowed: " + list);
  return s;
}

// ---------------------------------------------------------------- parsing and overrides

[[noreturn]] void cannot_read(const std::string& file, int err) {
  throw InputError("cannot read scene file '" + file + "': " + std::strerror(err));
}

std::string read_file(const std::string& file) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(file.c_str(), "rb"), &std::fclose);
  if (!f) cannot_read(file, errno);
  std::string text;
  char buf[1 << 16];
  while (const std::size_t n = std::fread(buf, 1, sizeof buf, f.get())) text.append(buf, n);
  if (std::ferror(f.get())) cannot_read(file, errno);  // e.g. EISDIR: fopen accepts a directory
  return text;
}

// toml11 reports a syntax error on several lines (message, source lines with ^--- notes, hints); messages here
// are one line, so fold it: "message; line 2 'b = = 2': here; Hint: ...".
std::string fold_toml_message(const std::string& what) {
  static const std::regex prefix(R"(^\[error\] (toml::\w+: )?)");
  static const std::regex source(R"(^\s*(\d+) \| (.*)$)");
  static const std::regex note(R"(^\s*\| [\s~^-]*(\S.*)$)");
  std::istringstream in(what);
  std::string line, code;
  std::getline(in, line);
  std::string out = std::regex_replace(line, prefix, "");
  if (!out.empty() && out.back() == '.') out.pop_back();  // a "; note" follows
  std::smatch m;
  while (std::getline(in, line)) {
    if (std::regex_match(line, m, source)) {
      code = "line " + m[1].str() + " '" + trim(m[2].str()) + "'";
    } else if (std::regex_match(line, m, note)) {
      out += "; " + code + ": " + m[1].str();
    } else if (line.rfind("Hint: ", 0) == 0) {
      out += "; " + line;
    }
  }
  return out;
}

Value toml_parse(const std::string& text, const std::string& name) {
  std::istringstream in(text);
  return toml::parse<toml::preserve_comments, detail::OrderedMap, std::vector>(in, name);
}

Value parse_toml(const std::string& text, const std::string& name) {
  try {
    return toml_parse(text, name);
  } catch (const toml::exception& e) {
    throw InputError(name + ":" + std::to_string(e.location().line()) + ": TOML syntax error: " +
                     fold_toml_message(e.what()));
  }
}

// An override's value is TOML when it parses as one (5, 2.5e9, true, "x", [1, 2]), else a bare string, so
// that --set contact.model=hertz_mindlin and --set walls[0].velocity="5 mm/s" both work.
Value override_value(const std::string& text) {
  try {
    const auto doc = toml_parse("v = " + text, "--set");
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

class OverrideApplier {
 public:
  OverrideApplier(detail::TomlState& st, std::string spec) : st_(st), spec_(std::move(spec)) {}

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
      if (steps[i].index) walked += "[" + std::to_string(*steps[i].index) + "]";
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

  detail::TomlState& st_;
  std::string spec_;
};

// The document with its overrides, as TOML text, headed by a comment listing the overrides.
std::string serialise(Value root, const std::vector<std::string>& overrides) {
  std::vector<std::string> head{" Re-serialised by mesocrack with these --set overrides applied:"};
  for (const auto& o : overrides) head.push_back("   " + std::regex_replace(o, std::regex("\n"), "\\n"));
  root.comments().insert(root.comments().begin(), head.begin(), head.end());
  // 15 digits print what the user typed (0.1, not 0.10000000000000001); 17 digits are always exact.
  const std::string short_form = toml::format(root, 80, 15);
  return parse_toml(short_form, "re-serialised") == root ? short_form : toml::format(root, 80, 17);
}

}  // namespace

// ---------------------------------------------------------------- Field

namespace detail {

std::string Field::label() const {
  const bool from_set = std::find(st.set_paths.begin(), st.set_paths.end(), key) != st.set_paths.end();
  return "key '" + key + "'" + (from_set ? " (from --set)" : "");
}

void Field::missing(const std::string& hint) const {
  throw InputError(st.file + ": missing key '" + key + "' (" + hint + ")");
}

void Field::bad(const std::string& what) const {
  throw InputError(st.file + ": " + label() + " = " + show(*value) + ": " + what);
}

void Field::out_of_range(const Range& r, Unit u, double si) const {
  const std::string unit(kind_def(u).si);
  // A quantity with a unit is compared in SI: show the converted value next to what was written.
  const std::string converted = value->is_string() ? " (" + format_number(si) + (unit.empty() ? "" : " " + unit) + ")" : "";
  throw InputError(st.file + ": " + label() + " = " + show(*value) + converted +
                   " is out of range: allowed " + r.describe(unit));
}

}  // namespace detail

// ---------------------------------------------------------------- Range

bool Range::contains(double v) const {
  return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
}

std::string Range::describe(const std::string& unit) const {
  const auto bound = [&](double x) { return format_number(x) + (unit.empty() ? "" : " " + unit); };
  const bool has_lo = lo > -kInf;
  const bool has_hi = hi < kInf;
  if (has_lo && has_hi)
    return bound(lo) + (lo_open ? " < " : " <= ") + "value" + (hi_open ? " < " : " <= ") + bound(hi);
  if (has_lo) return std::string("value ") + (lo_open ? "> " : ">= ") + bound(lo);
  if (has_hi) return std::string("value ") + (hi_open ? "< " : "<= ") + bound(hi);
  return "any value";
}

// ---------------------------------------------------------------- Table

Table::Table(std::shared_ptr<detail::TomlState> state, std::size_t visit) : state_(std::move(state)), visit_(visit) {}

detail::Field Table::field(const std::string& key) const {
  auto& visit = state_->visits[visit_];
  if (std::find(visit.known.begin(), visit.known.end(), key) == visit.known.end()) visit.known.push_back(key);
  const auto& table = visit.table->as_table();
  const auto it = table.find(key);
  return {*state_, join_key(visit.path, key), it == table.end() ? nullptr : &it->second};
}

Table Table::child(const detail::Field& f) const { return Table(state_, state_->visit(f.key, *f.value)); }

const std::string& Table::path() const { return state_->visits[visit_].path; }

bool Table::has(const std::string& key) const { return field(key).value != nullptr; }

std::vector<std::string> Table::keys() const {
  std::vector<std::string> out;
  for (const auto& kv : state_->visits[visit_].table->as_table()) out.push_back(kv.first);
  return out;
}

double Table::number(const std::string& key, Unit u, Range r) const {
  const auto f = field(key);
  if (!f.value) f.missing(number_hint(u));
  return read_number(f, u, r);
}

double Table::number(const std::string& key, Unit u, Range r, double fallback) const {
  const auto f = field(key);
  return f.value ? read_number(f, u, r) : fallback;
}

std::vector<double> Table::numbers(const std::string& key, Unit u, Range r, std::size_t n) const {
  const auto f = field(key);
  if (!f.value) f.missing(array_hint(u, n));
  if (!f.value->is_array()) f.bad("expected " + array_hint(u, n));
  const std::size_t size = f.value->as_array().size();
  if (n > 0 && size != n) f.bad("expected " + array_hint(u, n) + ", got " + std::to_string(size));
  std::vector<double> out;
  for (std::size_t i = 0; i < size; ++i) out.push_back(read_number(f.element(i), u, r));
  return out;
}

std::int64_t Table::integer(const std::string& key, Range r) const {
  const auto f = field(key);
  if (!f.value) f.missing("an integer");
  return read_integer(f, r);
}

std::int64_t Table::integer(const std::string& key, Range r, std::int64_t fallback) const {
  const auto f = field(key);
  return f.value ? read_integer(f, r) : fallback;
}

bool Table::boolean(const std::string& key) const {
  const auto f = field(key);
  if (!f.value) f.missing("true or false");
  return read_boolean(f);
}

bool Table::boolean(const std::string& key, bool fallback) const {
  const auto f = field(key);
  return f.value ? read_boolean(f) : fallback;
}

std::string Table::choice(const std::string& key, const std::vector<std::string>& allowed) const {
  const auto f = field(key);
  if (!f.value) f.missing("one of: " + join_list(allowed, ", "));
  return read_choice(f, allowed);
}

std::string Table::choice(const std::string& key, const std::vector<std::string>& allowed,
                          const std::string& fallback) const {
  const auto f = field(key);
  return f.value ? read_choice(f, allowed) : fallback;
}

std::string Table::string(const std::string& key) const {
  const auto f = field(key);
  if (!f.value) f.missing("a string");
  return read_string(f);
}

std::string Table::string(const std::string& key, const std::string& fallback) const {
  const auto f = field(key);
  return f.value ? read_string(f) : fallback;
}

Table Table::table(const std::string& key) const {
  const auto f = field(key);
  if (!f.value) f.missing("a table");
  if (!f.value->is_table()) f.bad("expected a table");
  return child(f);
}

std::optional<Table> Table::optional_table(const std::string& key) const {
  if (!has(key)) return std::nullopt;
  return table(key);
}

std::vector<Table> Table::tables(const std::string& key) const {
  const auto f = field(key);
  if (!f.value) return {};
  // The section header the user should write: the key path without array indices.
  static const std::regex index(R"(\[\d+\])");
  const std::string header = std::regex_replace(f.key, index, "");
  if (!f.value->is_array()) f.bad("expected an array of tables ([[" + header + "]] sections)");
  std::vector<Table> out;
  for (std::size_t i = 0; i < f.value->as_array().size(); ++i) {
    const auto e = f.element(i);
    if (!e.value->is_table()) e.bad("expected a table ([[" + header + "]] section)");
    out.push_back(child(e));
  }
  return out;
}

void Table::fail(const std::string& key, const std::string& what) const {
  const auto f = field(key);
  if (!f.value) throw InputError(state_->file + ": " + f.label() + ": " + what);
  f.bad(what);
}

void Table::finish() const {
  const auto& visit = state_->visits[visit_];
  for (const auto& kv : visit.table->as_table()) {
    if (std::find(visit.known.begin(), visit.known.end(), kv.first) != visit.known.end()) continue;
    const detail::Field f{*state_, join_key(visit.path, kv.first), &kv.second};
    const std::string allowed = visit.known.empty() ? "no keys are allowed here" : "allowed here: " + join_list(visit.known, ", ");
    throw InputError(state_->file + ": unknown " + f.label() + "; " + allowed);
  }
}

// ---------------------------------------------------------------- TomlDoc

TomlDoc::TomlDoc(std::shared_ptr<detail::TomlState> state) : state_(std::move(state)) {}

TomlDoc TomlDoc::load(const std::string& file, const std::vector<std::string>& overrides) {
  return parse_text(read_file(file), file, overrides);
}

TomlDoc TomlDoc::parse_text(const std::string& text, const std::string& name, const std::vector<std::string>& overrides) {
  auto st = std::make_shared<detail::TomlState>();
  st->file = name;
  st->root = parse_toml(text, name);
  for (const auto& o : overrides) OverrideApplier(*st, o).apply();
  st->text = overrides.empty() ? text : serialise(st->root, overrides);
  st->visit("", st->root);  // the root is always checked by finish_all, even if nobody asked for it
  return TomlDoc(std::move(st));
}

Table TomlDoc::root() const { return Table(state_, 0); }

const std::string& TomlDoc::text() const { return state_->text; }

void TomlDoc::finish_all() const {
  for (std::size_t i = 0; i < state_->visits.size(); ++i) Table(state_, i).finish();
}

}  // namespace mc
