// String helpers shared by the scene reader's files (units, overrides, the reader's messages).
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace mc::detail {

// "a, b or c" with last_sep " or "; "a, b, c" with ", ".
inline std::string join_list(const std::vector<std::string>& items, const std::string& last_sep) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) out += (i + 1 == items.size()) ? last_sep : ", ";
    out += items[i];
  }
  return out;
}

// s without its leading and trailing spaces and tabs.
inline std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  return b == std::string::npos ? "" : s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

}  // namespace mc::detail
