#include "engine/keys.hpp"

#include <stdexcept>

namespace mc {

const Key* KeyTable::find(std::string_view n, std::string_view when) const {
  for (const Key& k : keys)
    if (k.name == n && (when.empty() || k.when == when)) return &k;
  return nullptr;
}

const Key& KeyTable::at(std::string_view n, std::string_view when) const {
  if (const Key* k = find(n, when)) return *k;
  throw std::logic_error("the key table '" + std::string(name) + "' declares no key '" + std::string(n) + "'" +
                         (when.empty() ? "" : " for " + std::string(when)));
}

const Key* KeyTable::filling(std::size_t offset) const {
  for (const Key& k : keys)
    if (k.at == offset) return &k;
  return nullptr;
}

std::string_view KeyTable::key() const {
  if (!location.empty()) return location;
  const auto dot = name.rfind('.');
  return dot == std::string_view::npos ? name : name.substr(dot + 1);
}

std::vector<Key> keys_at(const KeyTable& sub, std::size_t offset) {
  std::vector<Key> out = sub.keys;
  for (Key& k : out)
    if (!k.by_hand()) k.at += offset;
  return out;
}

std::vector<Key> joined(std::vector<Key> a, const std::vector<Key>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

}  // namespace mc
