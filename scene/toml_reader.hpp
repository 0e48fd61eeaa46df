// The validated reader for scene files (TOML). Every value reaches the engine through a Table accessor that
// checks type, unit and range, so a bad scene fails with one line naming the file, the key (full dotted path,
// e.g. `walls[2].velocity`), the value and what is allowed. Nothing is clamped, and unknown keys are errors:
// a misspelt optional key would otherwise be silently replaced by its default.
// All errors are mc::InputError. Units and ranges are in scene/units.hpp, the --set overrides in
// scene/overrides.hpp.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "scene/units.hpp"

namespace mc {

namespace detail {
struct TomlState;
struct Field;
}  // namespace detail

// A view of one TOML table at a key path. Reading a key (or asking has()) marks it as known; finish() then
// rejects the keys nobody asked for. Views are cheap to copy and share the document's bookkeeping.
class Table {
 public:
  const std::string& path() const;  // "" for the root, "material", "walls[1]"
  bool has(const std::string& key) const;
  std::vector<std::string> keys() const;  // keys present, in file order

  double number(const std::string& key, Unit u, Range r) const;
  double number(const std::string& key, Unit u, Range r, double fallback) const;
  // An array of numbers (each may be a unit string); n = 0 accepts any length.
  std::vector<double> numbers(const std::string& key, Unit u, Range r, std::size_t n) const;
  std::int64_t integer(const std::string& key, Range r) const;
  std::int64_t integer(const std::string& key, Range r, std::int64_t fallback) const;
  bool boolean(const std::string& key) const;
  bool boolean(const std::string& key, bool fallback) const;
  std::string choice(const std::string& key, const std::vector<std::string>& allowed) const;
  std::string choice(const std::string& key, const std::vector<std::string>& allowed,
                     const std::string& fallback) const;
  std::string string(const std::string& key) const;  // free text, e.g. a file path
  std::string string(const std::string& key, const std::string& fallback) const;

  Table table(const std::string& key) const;
  std::optional<Table> optional_table(const std::string& key) const;
  std::vector<Table> tables(const std::string& key) const;  // [[key]] array of tables; empty if absent

  // For checks across keys: throws "file: key 'path.key' = <value>: <what>".
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;
  // Throws for the first key of this table (not recursing) that was never read or asked for.
  void finish() const;
  // Before anything is read: throws, as finish() would, for the first key not among `names` and spelt within two
  // letters of one of them (a misspelt table would otherwise fail later through what it broke).
  void refuse_misspellings(const std::vector<std::string>& names) const;

 private:
  friend class TomlDoc;
  Table(std::shared_ptr<detail::TomlState> state, std::size_t visit);
  detail::Field field(const std::string& key) const;  // looks the key up and marks it as known
  Table child(const detail::Field& f) const;          // the view of a sub-table, registered for finish_all
  std::shared_ptr<detail::TomlState> state_;
  std::size_t visit_;  // index of this table's entry in the state's list of visited tables
};

// One value of a document: its key path, and its TOML text exact (to compare) and as a user would write it.
struct TomlLeaf {
  std::string path, exact, shown;
};

// A parsed scene file with the command line's --set overrides applied.
class TomlDoc {
 public:
  // overrides: "a.b.c=value" or "walls[1].velocity=5 mm/s"; the value is TOML if it parses, else a bare string.
  static TomlDoc load(const std::string& file, const std::vector<std::string>& overrides = {});
  static TomlDoc parse_text(const std::string& text, const std::string& name,
                            const std::vector<std::string>& overrides = {});

  Table root() const;
  // The exact input: the file text itself, or, with overrides, the document re-serialised (with a comment
  // listing the overrides). Stored in the output file; it re-parses to the same values.
  const std::string& text() const;
  // What reading the document found suspicious but allowed (a number without a unit far from its key's usual
  // values), one line each, in the order read.
  std::vector<std::string> warnings() const;
  // Every value with its full key path, in file order; entries of [[table]] lists by index ("walls[1].kn").
  // For comparing two scenes key by key.
  std::vector<TomlLeaf> leaves() const;
  // finish() for every table visited; a sub-table never visited is an unknown key of its parent.
  void finish_all() const;

 private:
  explicit TomlDoc(std::shared_ptr<detail::TomlState> state);
  std::shared_ptr<detail::TomlState> state_;
};

}  // namespace mc
