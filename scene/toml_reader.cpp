#include "scene/toml_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <sstream>

#include "engine/errors.hpp"
#include "scene/nearest_name.hpp"
#include "scene/overrides.hpp"
#include "scene/text.hpp"
#include "scene/toml_document.hpp"
#include "scene/toml_nesting.hpp"

namespace mc {
namespace detail {

// One key being read: where it is, and its value (nullptr when absent). Builds every error message.
struct Field {
  const TomlState& st;
  std::string key;  // full dotted path, e.g. "walls[1].velocity"
  const Value* value;

  Field element(std::size_t i) const { return {st, index_key(key, i), &value->as_array().at(i)}; }
  std::string label() const;
  [[noreturn]] void missing(const std::string& hint) const;
  [[noreturn]] void bad(const std::string& what) const;
  [[noreturn]] void out_of_range(const Range& r, Unit u, double si) const;
};

}  // namespace detail

namespace {

using detail::array_hint, detail::expected_finite_number, detail::expected_number, detail::format_number,
    detail::number_hint, detail::quantity;
using detail::Field, detail::Value, detail::join_key, detail::join_list, detail::printable, detail::shorten,
    detail::trim;

// A string value as TOML writes it, control characters escaped.
std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return printable(out) + "\"";
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

std::string show(const Value& v) { return shorten(show_full(v)); }

// What a check says of a value: it may quote the user's words ("'x' is not a phase name"), so it is made printable
// and cut to a length that still holds any list of what is allowed.
std::string explained(const std::string& what) { return shorten(printable(what), 600); }

// The section header the user should write for a key path: "walls[1].faces" -> "walls.faces".
std::string without_indices(const std::string& path) {
  std::string out;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const auto close = path.find_first_not_of("0123456789", i + 1);
    if (path[i] == '[' && close != std::string::npos && close > i + 1 && path[close] == ']') {
      i = close;
      continue;
    }
    out += path[i];
  }
  return out;
}

double read_number(const Field& f, Unit u, const Range& r) {
  const Value& v = *f.value;
  double x = 0.0;
  if (v.is_integer()) {
    x = static_cast<double>(v.as_integer());
  } else if (v.is_floating()) {
    x = v.as_floating();
  } else if (v.is_string()) {
    const auto q = quantity(v.as_string().str, u);
    if (!q.error.empty()) f.bad(q.error);
    x = q.si;
  } else {
    f.bad(expected_number(u));
  }
  if (!std::isfinite(x)) f.bad(expected_finite_number(u));
  if (!r.contains(x)) f.out_of_range(r, u, x);
  if (!v.is_string())
    if (const std::string why = detail::unusual_bare_number(x, u, r); !why.empty())
      f.st.warnings.push_back(f.st.file + ": " + f.label() + " = " + show(v) + " " + why);
  return x;
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

// A file that cannot be read is a file error (exit 3), like every other file the command opens.
[[noreturn]] void cannot_read(const std::string& file, int err) {
  throw IoError("cannot read scene file '" + file + "': " + std::strerror(err));
}

// The largest scene file read. Reading parses about 1 MB/s into about 50 times its size in memory (measured by
// benchmarks/scene_reading), so 128 MB takes two minutes and 6 GB; beyond it is no scene but a mistake, such as
// /dev/zero, which would otherwise fill the memory. Particles by the million belong in a sphere_list file.
constexpr std::size_t kMaxSceneBytes = std::size_t{128} << 20;

std::string read_file(const std::string& file) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(file.c_str(), "rb"), &std::fclose);
  if (!f) cannot_read(file, errno);
  std::string text;
  char buf[1 << 16];
  while (const std::size_t n = std::fread(buf, 1, sizeof buf, f.get())) {
    text.append(buf, n);
    if (text.size() > kMaxSceneBytes)
      throw InputError("scene file '" + file + "' is larger than " + std::to_string(kMaxSceneBytes >> 20) +
                       " MB; allowed: at most " + std::to_string(kMaxSceneBytes >> 20) +
                       " MB (list many particles in a sphere_list file)");
  }
  if (std::ferror(f.get())) cannot_read(file, errno);  // e.g. EISDIR: fopen accepts a directory
  return text;
}

// "[error] toml::parse_array: message" -> "message".
std::string without_toml_prefix(const std::string& line) {
  const std::string error = "[error] ", toml = "toml::";
  std::string s = line.rfind(error, 0) == 0 ? line.substr(error.size()) : line;
  if (s.rfind(toml, 0) != 0) return s;
  const auto colon = s.find(": ");
  const bool word = colon != std::string::npos && std::all_of(s.begin() + toml.size(), s.begin() + colon, [](char c) {
                      return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
                    });
  return word ? s.substr(colon + 2) : s;
}

// " 12 | dimension = = 3" -> "line 12 'dimension = = 3'" (the code shortened), or "" for another kind of line.
std::string source_line(const std::string& line) {
  const auto digits = line.find_first_not_of(" \t");
  const auto bar = line.find_first_not_of("0123456789", digits);
  if (digits == std::string::npos || bar == digits || bar == std::string::npos || line.compare(bar, 3, " | ") != 0)
    return "";
  return "line " + line.substr(digits, bar - digits) + " '" + shorten(printable(trim(line.substr(bar + 3)))) + "'";
}

// "    |      ^--- expected a value" -> "expected a value", or "" for another kind of line.
std::string note_line(const std::string& line) {
  const auto bar = line.find_first_not_of(" \t");
  if (bar == std::string::npos || line.compare(bar, 2, "| ") != 0) return "";
  const auto note = line.find_first_not_of(" \t~^-", bar + 2);
  return note == std::string::npos ? "" : shorten(printable(line.substr(note)));
}

// toml11 reports a syntax error on several lines (message, source lines with ^--- notes, hints); messages here
// are one line, so fold it: "message; line 2 'b = = 2': here; Hint: ...". Plain string handling, no std::regex:
// libstdc++'s regex recurses once per character matched, and a source line may be megabytes long.
std::string fold_toml_message(const std::string& what) {
  std::istringstream in(what);
  std::string line, code;
  std::getline(in, line);
  std::string out = shorten(printable(without_toml_prefix(line)));
  if (!out.empty() && out.back() == '.') out.pop_back();  // a "; note" follows
  while (std::getline(in, line)) {
    if (const std::string c = source_line(line); !c.empty()) {
      code = c;
    } else if (const std::string n = note_line(line); !n.empty()) {
      out += "; " + code + ": " + n;
    } else if (line.rfind("Hint: ", 0) == 0) {
      out += "; " + shorten(printable(line));
    }
  }
  return out;
}

}  // namespace

namespace detail {

namespace {

// The length of the valid UTF-8 sequence at s[i], or 0 when it is not one (RFC 3629: no overlong forms, no
// surrogates, nothing above U+10FFFF).
std::size_t utf8_length(const std::string& s, std::size_t i) {
  const auto byte = [&](std::size_t k) { return k < s.size() ? static_cast<unsigned char>(s[k]) : 0u; };
  const auto cont = [&](std::size_t k, unsigned lo = 0x80, unsigned hi = 0xBF) {
    return byte(k) >= lo && byte(k) <= hi;
  };
  const unsigned b = byte(i);
  if (b < 0x80) return 1;
  if (b >= 0xC2 && b <= 0xDF) return cont(i + 1) ? 2 : 0;
  if (b >= 0xE0 && b <= 0xEF) {
    const unsigned lo = b == 0xE0 ? 0xA0 : 0x80, hi = b == 0xED ? 0x9F : 0xBF;
    return cont(i + 1, lo, hi) && cont(i + 2) ? 3 : 0;
  }
  if (b >= 0xF0 && b <= 0xF4) {
    const unsigned lo = b == 0xF0 ? 0x90 : 0x80, hi = b == 0xF4 ? 0x8F : 0xBF;
    return cont(i + 1, lo, hi) && cont(i + 2) && cont(i + 3) ? 4 : 0;
  }
  return 0;
}

}  // namespace

std::optional<std::size_t> first_non_utf8(const std::string& text) {
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = utf8_length(text, i);
    if (n == 0) return i;
    i += n;
  }
  return std::nullopt;
}

// TOML files are UTF-8, and toml11 misreads other bytes (a broken sequence inside a quoted key made it build a
// string of negative length: std::length_error instead of a syntax error).
void check_utf8(const std::string& text, const std::string& name) {
  const auto at = first_non_utf8(text);
  if (!at) return;
  static const char* hex = "0123456789abcdef";
  const auto b = static_cast<unsigned char>(text[*at]);
  const auto line_start = text.rfind('\n', *at) == std::string::npos ? 0 : text.rfind('\n', *at) + 1;
  const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(*at), '\n');
  throw InputError(name + ":" + std::to_string(line) + ": byte 0x" + hex[b >> 4] + hex[b & 15] + " at column " +
                   std::to_string(*at - line_start + 1) + " is not UTF-8 text; allowed: UTF-8 (TOML files are UTF-8)");
}

void check_nesting(const std::string& text, const std::string& name) {
  if (const auto line = toml_nesting(text).too_deep)
    throw InputError(name + ":" + std::to_string(*line) + ": tables and arrays nest deeper than " +
                     std::to_string(kMaxNesting) + " levels here (headers, dotted keys, [ ] and { } each add one); " +
                     "allowed: at most " + std::to_string(kMaxNesting));
}

Value parse_toml(const std::string& text, const std::string& name) {
  check_utf8(text, name);
  check_nesting(text, name);
  std::istringstream in(text);
  return toml::parse<toml::preserve_comments, OrderedMap, std::vector>(in, name);
}

Value parse_scene_text(const std::string& text, const std::string& name) {
  try {
    return parse_toml(text, name);
  } catch (const toml::exception& e) {
    throw InputError(name + ":" + std::to_string(e.location().line()) +
                     ": TOML syntax error: " + fold_toml_message(e.what()));
  }
}

std::string Field::label() const {
  const bool from_set = std::find(st.set_paths.begin(), st.set_paths.end(), key) != st.set_paths.end();
  return "key '" + shorten(printable(key)) + "'" + (from_set ? " (from --set)" : "");
}

void Field::missing(const std::string& hint) const {
  throw InputError(st.file + ": missing key '" + key + "' (" + hint + ")");
}

void Field::bad(const std::string& what) const {
  throw InputError(st.file + ": " + label() + " = " + show(*value) + ": " + explained(what));
}

void Field::out_of_range(const Range& r, Unit u, double si) const {
  const std::string unit = si_unit(u);
  // A quantity with a unit is compared in SI: show the converted value next to what was written.
  const std::string converted =
      value->is_string() ? " (" + format_number(si) + (unit.empty() ? "" : " " + unit) + ")" : "";
  throw InputError(st.file + ": " + label() + " = " + show(*value) + converted + " is out of range: allowed " +
                   describe(r, unit));
}

}  // namespace detail

// ---------------------------------------------------------------- Table

Table::Table(std::shared_ptr<detail::TomlState> state, std::size_t visit) : state_(std::move(state)), visit_(visit) {}

detail::Field Table::field(const std::string& key) const {
  auto& visit = state_->visits[visit_];
  visit.ask(key);
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
  const std::string header = without_indices(f.key);
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
  if (!f.value) throw InputError(state_->file + ": " + f.label() + ": " + explained(what));
  f.bad(what);
}

namespace {
// ": a misspelling of 'walls'?" when `given` is within two letters of a known name (one in a short name: 'y' is no
// misspelling of 'x'), else "".
std::string misspelling_of(const std::string& given, const std::vector<std::string>& known) {
  const std::string near = nearest_name(given, known, std::min<std::size_t>(2, given.size() / 3));
  return near.empty() ? "" : ": a misspelling of '" + near + "'?";
}
}  // namespace

void Table::finish() const {
  const auto& visit = state_->visits[visit_];
  for (const auto& kv : visit.table->as_table()) {
    if (visit.was_asked(kv.first)) continue;
    const Field f{*state_, join_key(visit.path, kv.first), &kv.second};
    const std::string allowed =
        visit.known.empty() ? "no keys are allowed here" : "allowed here: " + join_list(visit.known, ", ");
    throw InputError(state_->file + ": unknown " + f.label() + misspelling_of(kv.first, visit.known) + "; " + allowed);
  }
}

void Table::refuse_misspellings(const std::vector<std::string>& names) const {
  const auto& visit = state_->visits[visit_];
  for (const auto& kv : visit.table->as_table()) {
    if (std::find(names.begin(), names.end(), kv.first) != names.end()) continue;
    const std::string near = misspelling_of(kv.first, names);
    if (near.empty()) continue;
    const Field f{*state_, join_key(visit.path, kv.first), &kv.second};
    throw InputError(state_->file + ": unknown " + f.label() + near + "; allowed here: " + join_list(names, ", "));
  }
}

// ---------------------------------------------------------------- TomlDoc

TomlDoc::TomlDoc(std::shared_ptr<detail::TomlState> state) : state_(std::move(state)) {}

TomlDoc TomlDoc::load(const std::string& file, const std::vector<std::string>& overrides) {
  return parse_text(read_file(file), file, overrides);
}

TomlDoc TomlDoc::parse_text(const std::string& text, const std::string& name,
                            const std::vector<std::string>& overrides) {
  auto st = std::make_shared<detail::TomlState>();
  st->file = name;
  st->root = detail::parse_scene_text(text, name);
  detail::apply_overrides(*st, overrides);
  st->text = overrides.empty() ? text : detail::serialise(*st, overrides);
  st->visit("", st->root);  // the root is always checked by finish_all, even if nobody asked for it
  return TomlDoc(std::move(st));
}

Table TomlDoc::root() const { return Table(state_, 0); }

const std::string& TomlDoc::text() const { return state_->text; }

std::vector<std::string> TomlDoc::warnings() const {
  std::vector<std::string> w;
  for (const auto& m : state_->warnings)
    if (std::find(w.begin(), w.end(), m) == w.end()) w.push_back(m);  // a key read twice is warned about once
  return w;
}

void TomlDoc::finish_all() const {
  for (std::size_t i = 0; i < state_->visits.size(); ++i) Table(state_, i).finish();
}

}  // namespace mc
