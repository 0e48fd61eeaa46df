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

// s with its control characters written as escapes (\n, \t, \r, \x1b): a message quoting user text stays on
// one line and cannot move the terminal's cursor.
inline std::string printable(const std::string& s) {
  static const char* hex = "0123456789abcdef";
  std::string out;
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u != 0x7f)
      out += c;
    else if (c == '\n')
      out += "\\n";
    else if (c == '\t')
      out += "\\t";
    else if (c == '\r')
      out += "\\r";
    else
      out += std::string("\\x") + hex[u >> 4] + hex[u & 15];
  }
  return out;
}

// s cut to its first max_chars characters and "..." when longer: a message stays one readable line even when the
// input it quotes (a value, a key, a line of the file) is megabytes long.
inline std::string shorten(const std::string& s, std::size_t max_chars = 80) {
  if (s.size() <= max_chars) return s;
  std::size_t cut = max_chars;
  while (cut > 0 && (static_cast<unsigned char>(s[cut]) & 0xC0) == 0x80) --cut;  // not inside a UTF-8 character
  return s.substr(0, cut) + "...";
}

}  // namespace mc::detail
