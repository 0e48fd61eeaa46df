#include "scene/key_reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <stdexcept>

#include "scene/nearest_name.hpp"

namespace mc {

namespace {

std::mutex asked_mutex;
std::set<const Key*>& asked() {
  static std::set<const Key*> s;
  return s;
}
void note(const Key& k) {
  const std::lock_guard<std::mutex> lock(asked_mutex);
  asked().insert(&k);
}

std::string str(std::string_view s) { return std::string(s); }

std::vector<std::string> words_of(const Key& k) {
  std::vector<std::string> w;
  for (const auto& x : k.words) w.push_back(str(x));
  return w;
}

// A Scatter key: `name` (the mean, or the Weibull scale λ) with either `name_std` (normal truncated to positive
// values) or `name_weibull_shape` (Weibull, Tang 8.4), not both.
void read_scatter(const Table& t, const Key& k, Scatter& s) {
  const std::string key = str(k.name), std_key = key + "_std", shape_key = key + "_weibull_shape";
  if (k.need == Need::Required || t.has(key)) s.mean = t.number(key, k.unit, Range::positive());
  const bool normal = t.has(std_key), weibull = t.has(shape_key);
  if (normal && weibull)
    t.fail(shape_key, "given together with " + std_key +
                          ": a bond parameter is drawn either from a normal distribution (" + key + " = mean, " +
                          std_key + ") or from a Weibull distribution (" + key + " = scale, " + shape_key +
                          "), not both");
  s.std = t.number(std_key, k.unit, Range::non_negative(), s.std);
  s.weibull_shape = t.number(shape_key, Unit::None, Range::positive(), s.weibull_shape);
}

void read_bound_key(const Table& t, const Key& k, void* out) {
  const std::string name = str(k.name);
  const bool required = k.need == Need::Required;
  switch (k.type) {
    case KeyType::Real: {
      double& v = member<double>(out, k);
      if (required || t.has(name)) {
        const double x = t.number(name, k.unit, k.range);
        v = k.tangent ? std::tan(x) : x;
      }
      return;
    }
    case KeyType::Integer: {
      if (k.int_bytes == sizeof(int)) {
        int& v = member<int>(out, k);
        v = static_cast<int>(required ? t.integer(name, k.range) : t.integer(name, k.range, v));
      } else {
        std::int64_t& v = member<std::int64_t>(out, k);
        v = required ? t.integer(name, k.range) : t.integer(name, k.range, v);
      }
      return;
    }
    case KeyType::Flag: {
      bool& v = member<bool>(out, k);
      v = required ? t.boolean(name) : t.boolean(name, v);
      return;
    }
    case KeyType::Word: {
      int& v = member<int>(out, k);
      const std::vector<std::string> w = words_of(k);
      const std::string s = required ? t.choice(name, w) : t.choice(name, w, w.at(static_cast<std::size_t>(v)));
      v = static_cast<int>(std::find(w.begin(), w.end(), s) - w.begin());
      return;
    }
    case KeyType::Text: {
      std::string& v = member<std::string>(out, k);
      v = required ? t.string(name) : t.string(name, v);
      return;
    }
    case KeyType::Reals: {
      auto& v = member<std::vector<double>>(out, k);
      if (required || t.has(name)) v = t.numbers(name, k.unit, k.range, static_cast<std::size_t>(std::max(0, k.count)));
      return;
    }
    case KeyType::Scatter:
      read_scatter(t, k, member<Scatter>(out, k));
      return;
  }
}

void check_alternatives(const Table& t, const Alternatives& a) {
  const std::string_view* first = nullptr;
  for (const auto& k : a.keys) {
    if (!t.has(str(k))) continue;
    if (first) t.fail(str(k), "given together with " + str(*first) + "; " + str(a.why));
    first = &k;
  }
  if (!first && a.one_required) t.fail(str(a.keys.front()), "missing; " + str(a.why));
}

std::string format8(double x) {
  char b[64];
  std::snprintf(b, sizeof b, "%.8g", x);
  return b;
}

}  // namespace

void read_bound_keys(const Table& t, const KeyTable& keys, void* out) {
  for (const Alternatives& a : keys.alternatives) check_alternatives(t, a);
  for (const Key& k : keys.keys) {
    if (k.by_hand()) continue;
    note(k);
    read_bound_key(t, k, out);
  }
  if (keys.check)
    if (const auto problem = keys.check(out)) t.fail(problem->key, problem->what);
}

// ---------------------------------------------------------------- KeyReader

const Key& KeyReader::key(std::string_view name, std::string_view when) const {
  const Key& k = keys_.at(name, when);
  note(k);
  refuse_misspelling_of(k);
  return k;
}


// A required key that is absent while the table holds a key it does not declare spelt nearly so: the misspelling
// is the error to name (reported as the right key missing, the user would look for the wrong thing), before the
// table's unknown keys are checked at its end.
void KeyReader::refuse_misspelling_of(const Key& k) const {
  if (k.need != Need::Required || t_.has(str(k.name))) return;
  for (const std::string& given : t_.keys()) {
    if (keys_.find(given) || edit_distance(given, k.name) > 2) continue;
    std::string allowed;
    for (const Key& d : keys_.keys) allowed += (allowed.empty() ? "" : ", ") + str(d.name);
    t_.fail(given, "no key of this table: a misspelling of '" + str(k.name) + "'? allowed here: " + allowed);
  }
}

bool KeyReader::has(std::string_view name) const { return t_.has(str(key(name).name)); }

std::optional<double> KeyReader::default_of(const Key& k) const {
  if (k.need == Need::Required) return std::nullopt;
  if (k.fallback) return k.fallback;
  if (k.by_hand() || !keys_.defaults) return std::nullopt;
  switch (k.type) {
    case KeyType::Real: {
      const double v = member<double>(keys_.defaults, k);
      return k.tangent ? std::atan(v) : v;
    }
    case KeyType::Integer:
      return static_cast<double>(k.int_bytes == sizeof(int) ? member<int>(keys_.defaults, k)
                                                            : member<std::int64_t>(keys_.defaults, k));
    case KeyType::Flag:
      return member<bool>(keys_.defaults, k) ? 1.0 : 0.0;
    default:
      return std::nullopt;
  }
}

double KeyReader::number(const Key& k) const {
  note(k);
  if (const auto d = default_of(k)) return t_.number(str(k.name), k.unit, k.range, *d);
  return t_.number(str(k.name), k.unit, k.range);
}

double KeyReader::required_number(std::string_view name) const {
  const Key& k = key(name);
  return t_.number(str(k.name), k.unit, k.range);
}

double KeyReader::number(const Key& k, double fallback) const {
  note(k);
  return t_.number(str(k.name), k.unit, k.range, fallback);
}

double KeyReader::number_within(std::string_view name, const Range& range) const {
  const Key& k = key(name);
  if (const auto d = default_of(k)) return t_.number(str(k.name), k.unit, range, *d);
  return t_.number(str(k.name), k.unit, range);
}

double KeyReader::number_within(std::string_view name, const Range& range, double fallback) const {
  const Key& k = key(name);
  return t_.number(str(k.name), k.unit, range, fallback);
}

std::int64_t KeyReader::integer_within(std::string_view name, const Range& range) const {
  const Key& k = key(name);
  if (const auto d = default_of(k)) return t_.integer(str(k.name), range, static_cast<std::int64_t>(*d));
  return t_.integer(str(k.name), range);
}

std::vector<double> KeyReader::numbers(std::string_view name, std::size_t n) const {
  const Key& k = key(name);
  return t_.numbers(str(k.name), k.unit, k.range, n);
}

std::int64_t KeyReader::integer(std::string_view name) const {
  const Key& k = key(name);
  if (const auto d = default_of(k)) return t_.integer(str(k.name), k.range, static_cast<std::int64_t>(*d));
  return t_.integer(str(k.name), k.range);
}

std::int64_t KeyReader::integer(std::string_view name, std::int64_t fallback) const {
  const Key& k = key(name);
  return t_.integer(str(k.name), k.range, fallback);
}

bool KeyReader::boolean(std::string_view name) const {
  const Key& k = key(name);
  if (const auto d = default_of(k)) return t_.boolean(str(k.name), *d != 0);
  return t_.boolean(str(k.name));
}

std::string KeyReader::choice(std::string_view name) const {
  const Key& k = key(name);
  if (k.need == Need::Required) return t_.choice(str(k.name), words_of(k));
  return t_.choice(str(k.name), words_of(k), str(k.shown_default));
}

std::string KeyReader::choice(std::string_view name, const std::string& fallback) const {
  const Key& k = key(name);
  return t_.choice(str(k.name), words_of(k), fallback);
}

std::string KeyReader::choice(std::string_view name, const std::vector<std::string>& allowed) const {
  return t_.choice(str(key(name).name), allowed);
}

std::string KeyReader::choice(std::string_view name, const std::vector<std::string>& allowed,
                              const std::string& fallback) const {
  return t_.choice(str(key(name).name), allowed, fallback);
}

std::string KeyReader::string(std::string_view name) const {
  const Key& k = key(name);
  if (k.need == Need::Required) return t_.string(str(k.name));
  return t_.string(str(k.name), str(k.shown_default));
}

std::string KeyReader::string(std::string_view name, const std::string& fallback) const {
  return t_.string(str(key(name).name), fallback);
}

void KeyReader::fail(std::string_view name, const std::string& what) const { t_.fail(str(key(name).name), what); }

void KeyReader::fail(const KeyTable& sub, const std::string& what) const { t_.fail(str(sub.key()), what); }

// ---------------------------------------------------------------- sub-tables

std::vector<Table> tables_of(const Table& parent, const KeyTable& keys) { return parent.tables(str(keys.key())); }

std::optional<Table> optional_table_of(const Table& parent, const KeyTable& keys) {
  return parent.optional_table(str(keys.key()));
}

Table table_of(const Table& parent, const KeyTable& keys) { return parent.table(str(keys.key())); }

// ---------------------------------------------------------------- writing back

std::string key_value_text(const Key& k, const void* obj) {
  switch (k.type) {
    case KeyType::Real: {
      const double v = member<double>(obj, k);
      return format8(k.tangent ? std::atan(v) : v);
    }
    case KeyType::Integer:
      return std::to_string(k.int_bytes == sizeof(int) ? member<int>(obj, k) : member<std::int64_t>(obj, k));
    case KeyType::Flag:
      return member<bool>(obj, k) ? "true" : "false";
    case KeyType::Word:
      return "\"" + str(k.words.at(static_cast<std::size_t>(member<int>(obj, k)))) + "\"";
    case KeyType::Text:
      return "\"" + member<std::string>(obj, k) + "\"";
    case KeyType::Reals: {
      std::string s = "[";
      for (const double x : member<std::vector<double>>(obj, k)) s += (s.size() > 1 ? ", " : "") + format8(x);
      return s + "]";
    }
    case KeyType::Scatter:
      return format8(member<Scatter>(obj, k).mean);
  }
  throw std::logic_error("key_value_text: unknown key type");
}

std::vector<std::string> changed_keys(const std::string& path, const KeyTable& keys, const void* from,
                                      const void* to) {
  std::vector<std::string> out;
  const std::string prefix = path.empty() ? "" : path + ".";
  for (const Key& k : keys.keys) {
    if (k.by_hand()) continue;
    const std::string name = prefix + str(k.name);
    if (k.type == KeyType::Scatter) {
      const Scatter &a = member<Scatter>(from, k), &b = member<Scatter>(to, k);
      if (!(a.mean == b.mean) && !(std::isnan(a.mean) && std::isnan(b.mean))) out.push_back(name + "=" + format8(b.mean));
      if (a.std != b.std) out.push_back(name + "_std=" + format8(b.std));
      if (a.weibull_shape != b.weibull_shape) out.push_back(name + "_weibull_shape=" + format8(b.weibull_shape));
      continue;
    }
    if (key_value_text(k, from) != key_value_text(k, to)) out.push_back(name + "=" + key_value_text(k, to));
  }
  return out;
}

// An example as a TOML value: a plain number or boolean as it is, anything else (a quantity with its unit, a word)
// quoted.
std::string example_value(std::string_view e) {
  const std::string s = str(e);
  if (s == "true" || s == "false") return s;
  char* end = nullptr;
  std::strtod(s.c_str(), &end);
  const bool number = !s.empty() && end == s.c_str() + s.size();
  return number ? s : "\"" + s + "\"";
}

std::string example_entry(const KeyTable& keys) {
  std::string out;
  for (const Key& k : keys.keys)
    if (!k.example.empty()) out += str(k.name) + " = " + example_value(k.example) + "\n";
  return out;
}

std::set<const Key*> keys_asked() {
  const std::lock_guard<std::mutex> lock(asked_mutex);
  return asked();
}

}  // namespace mc
