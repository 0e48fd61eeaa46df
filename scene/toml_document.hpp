// The parsed scene document as the reader and the --set overrides share it: toml11 values in file order, and
// the bookkeeping of which tables were visited and which of their keys were asked for. Internal to
// scene/toml_reader.cpp and scene/overrides.cpp; the rest of the code sees only Table and TomlDoc.
#pragma once
#include <algorithm>
#include <cstddef>
#include <deque>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include <toml.hpp>

namespace mc::detail {

// toml11 3.7 stores tables in std::unordered_map unless told otherwise and has no ordered map of its own
// (its docs suggest tsl::ordered_map, which is not installed). This insertion-ordered map keeps the file's
// key order for keys(), unknown-key reports and the re-serialised text. Small tables are searched linearly; from
// kIndexFrom keys on, a hash index beside the entries finds a key at once, so a table of n keys is built in O(n)
// (a scene may hold 10^5 keys in one table, or 10^5 [[specimen.particles]] entries in one array).
template <class Key, class T, class... Unused>
class OrderedMap {
 public:
  using key_type = Key;
  using mapped_type = T;
  using value_type = std::pair<Key, T>;  // not pair<const Key, T>: std::vector needs assignable elements
  using iterator = typename std::vector<value_type>::iterator;
  using const_iterator = typename std::vector<value_type>::const_iterator;
  using size_type = std::size_t;

  iterator begin() { return items_.begin(); }
  iterator end() { return items_.end(); }
  const_iterator begin() const { return items_.begin(); }
  const_iterator end() const { return items_.end(); }
  size_type size() const { return items_.size(); }

  iterator find(const Key& k) { return begin() + static_cast<std::ptrdiff_t>(position(k)); }
  const_iterator find(const Key& k) const { return begin() + static_cast<std::ptrdiff_t>(position(k)); }
  size_type count(const Key& k) const { return find(k) == end() ? 0 : 1; }
  T& at(const Key& k) { return checked(find(k))->second; }
  const T& at(const Key& k) const { return checked(find(k))->second; }
  T& operator[](const Key& k) { return insert(value_type(k, T{})).first->second; }

  std::pair<iterator, bool> insert(const value_type& kv) {
    const auto it = find(kv.first);
    if (it != end()) return {it, false};
    items_.push_back(kv);
    if (items_.size() == kIndexFrom) {
      for (std::size_t i = 0; i < items_.size(); ++i) index_.emplace(items_[i].first, i);
    } else if (items_.size() > kIndexFrom) {
      index_.emplace(kv.first, items_.size() - 1);
    }
    return {std::prev(end()), true};
  }

  // Order-insensitive, like the maps toml11 expects: the serialiser writes sub-tables after plain keys.
  friend bool operator==(const OrderedMap& a, const OrderedMap& b) {
    return a.size() == b.size() && std::all_of(a.begin(), a.end(), [&](const auto& kv) {
             const auto it = b.find(kv.first);
             return it != b.end() && it->second == kv.second;
           });
  }

 private:
  // Below this many keys a linear search is as fast as hashing and spares every small table an index.
  static constexpr std::size_t kIndexFrom = 16;

  // The key's place in items_, or items_.size() when absent. Keys are never erased or changed (toml11 only
  // inserts), so the index stays valid.
  std::size_t position(const Key& k) const {
    if (items_.size() >= kIndexFrom) {
      const auto it = index_.find(k);
      return it == index_.end() ? items_.size() : it->second;
    }
    const auto it = std::find_if(items_.begin(), items_.end(), [&](const auto& kv) { return kv.first == k; });
    return static_cast<std::size_t>(it - items_.begin());
  }
  template <class It>
  It checked(It it) const {
    if (it == items_.end()) throw std::out_of_range("toml table: no such key");
    return it;
  }
  std::vector<value_type> items_;
  std::unordered_map<Key, std::size_t> index_;  // key -> place in items_, once there are kIndexFrom keys
};

using Value = toml::basic_value<toml::preserve_comments, OrderedMap, std::vector>;

// A table the code has looked at, and the keys it asked for there.
struct Visit {
  std::string path;
  const Value* table;
  std::vector<std::string> known;           // keys the code asked for, in asking order: the "allowed here" list
  std::unordered_set<std::string> asked{};  // the same keys, to check each key of a large table at once

  void ask(const std::string& key) {
    if (asked.insert(key).second) known.push_back(key);
  }
  bool was_asked(const std::string& key) const { return asked.count(key) > 0; }
};

// The document and its bookkeeping, shared by a TomlDoc and every Table view of it.
struct TomlState {
  std::string file;
  std::string text;
  Value root;
  std::vector<std::string> set_paths;                     // full key paths given by --set, to say so in messages
  std::deque<Visit> visits;                               // a deque: Table::path() hands out references into it
  std::unordered_map<std::string, std::size_t> visit_of;  // path -> its entry in visits
  mutable std::vector<std::string> warnings;               // values read that look like a mistake (read_number)

  std::size_t visit(const std::string& path, const Value& table) {
    const auto [it, added] = visit_of.emplace(path, visits.size());
    if (added) visits.push_back({path, &table, {}});
    return it->second;
  }
};

// "walls[1]" + "velocity" -> "walls[1].velocity"; a key of the root is its own path.
inline std::string join_key(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

// "walls" + 1 -> "walls[1]": the path of an array entry.
inline std::string index_key(const std::string& path, std::size_t i) { return path + "[" + std::to_string(i) + "]"; }

// The offset of the first byte that is not part of valid UTF-8, if any.
std::optional<std::size_t> first_non_utf8(const std::string& text);
// Throws InputError "name:line: ..." at the first byte that is not UTF-8 text.
void check_utf8(const std::string& text, const std::string& name);
// Throws InputError "name:line: ..." when the text nests tables and arrays deeper than kMaxNesting.
void check_nesting(const std::string& text, const std::string& name);
// TOML text -> Value; throws toml::exception, whose message spans several lines, or check_utf8's or check_nesting's
// InputError.
Value parse_toml(const std::string& text, const std::string& name);
// The same, but a syntax error is an InputError of one line: "name:line: TOML syntax error: ...".
Value parse_scene_text(const std::string& text, const std::string& name);

}  // namespace mc::detail
