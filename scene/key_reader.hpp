// Scene tables read through their key tables (engine/keys.hpp): every key a scene may hold is declared once, with
// its unit, range and default, and read from there. A table whose keys all fill members of a struct (a model's
// Params) is read whole by read_keys; a table whose keys depend on each other (walls by shape and motion) is read key
// by key through a KeyReader, each key's unit, range and default taken from its declaration. A reader that asks for a
// key its table does not declare is a programming error (std::logic_error). Every key asked for is noted, so a test
// can find the keys declared that no reader reads.
#pragma once
#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "engine/keys.hpp"
#include "scene/toml_reader.hpp"

namespace mc {

// Reads every key of `keys` that fills a member into the struct at `out` (of the table's type): each absent optional
// key keeps the struct's value (the default), each given one is checked against its unit and range; then the
// table's alternatives and its check. Keys read by hand are left to the caller.
void read_bound_keys(const Table& t, const KeyTable& keys, void* out);

template <class P>
P read_keys(const Table& t, const KeyTable& keys) {
  P p{};
  read_bound_keys(t, keys, &p);
  return p;
}

// One scene table read by hand, key by key, each as its declaration in `keys` says. Each accessor takes the key's
// name, or its declaration (key(name, when), for a key declared once per case).
class KeyReader {
 public:
  KeyReader(const Table& t, const KeyTable& keys) : t_(t), keys_(keys) {}
  const Table& table() const { return t_; }
  const KeyTable& keys() const { return keys_; }
  // The declaration, noted as asked for.
  const Key& key(std::string_view name, std::string_view when = {}) const;

  bool has(std::string_view key) const;
  // A number of the key's unit and range: required, or its default (the declared fallback, or a bound key's member in
  // the table's default-made struct), or `fallback`; a key with neither is read as required.
  double number(const Key& k) const;
  double number(const Key& k, double fallback) const;
  double number(std::string_view key) const { return number(this->key(key)); }
  double number(std::string_view key, double fallback) const { return number(this->key(key), fallback); }
  // A key that must be given here, whatever its default elsewhere (timestep.fixed of a rigid-cell scene).
  double required_number(std::string_view key) const;
  // Within `range`, which depends on the scene (the declared range is the widest it may be).
  double number_within(std::string_view key, const Range& range) const;
  double number_within(std::string_view key, const Range& range, double fallback) const;
  std::int64_t integer_within(std::string_view key, const Range& range) const;
  // `n` numbers of the key's unit and range (0: any number).
  std::vector<double> numbers(std::string_view key, std::size_t n) const;
  std::int64_t integer(std::string_view key) const;
  std::int64_t integer(std::string_view key, std::int64_t fallback) const;
  bool boolean(std::string_view key) const;  // required, or its declared fallback (≠ 0: true)
  // One of the key's declared words (required, or its shown default), or of `allowed` (names the scene itself
  // defines, such as its phases).
  std::string choice(std::string_view key) const;
  std::string choice(std::string_view key, const std::string& fallback) const;
  std::string choice(std::string_view key, const std::vector<std::string>& allowed) const;
  std::string choice(std::string_view key, const std::vector<std::string>& allowed, const std::string& fallback) const;
  std::string string(std::string_view key) const;  // required, or its shown default ("" when none)
  std::string string(std::string_view key, const std::string& fallback) const;
  [[noreturn]] void fail(std::string_view key, const std::string& what) const;
  [[noreturn]] void fail(const KeyTable& sub, const std::string& what) const;  // naming a sub-table of this one
  // The keys of the table that fill members of `out` (of the table's type), as read_bound_keys.
  void read_bound(void* out) const { read_bound_keys(t_, keys_, out); }
  void finish() const { t_.finish(); }

 private:
  void refuse_misspelling_of(const Key& k) const;
  std::optional<double> default_of(const Key& k) const;
  Table t_;
  const KeyTable& keys_;
};

// The sub-tables of `parent` that `keys` declares: [[name]] entries, or the [name] table (absent: nullopt, or
// required). The key of the parent is the table's name after its last dot ("run.stop": "stop").
std::vector<Table> tables_of(const Table& parent, const KeyTable& keys);
std::optional<Table> optional_table_of(const Table& parent, const KeyTable& keys);
Table table_of(const Table& parent, const KeyTable& keys);

// A bound key's value in the struct at `obj` as a scene writes it, to 8 significant digits (the calibrated scenes):
// "3.0000001e+10", "true", "\"logarithmic\"". Scatter keys: their mean.
std::string key_value_text(const Key& k, const void* obj);

// "path.key=value" for each bound key whose member differs between the structs `from` and `to` of the table's type
// (a Scatter: each of its three keys that differs), in the table's order: the --set lines of a calibration.
std::vector<std::string> changed_keys(const std::string& path, const KeyTable& keys, const void* from, const void* to);

// The table's examples as TOML lines, "key = value" for each key that gives one (a Scatter: its mean): an entry
// that reads, for the key reference and for the tests that need a model with sample parameters.
std::string example_entry(const KeyTable& keys);

// The keys asked for so far in this process (by the readers, and all keys of every table read whole).
std::set<const Key*> keys_asked();

}  // namespace mc
