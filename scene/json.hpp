// The few pieces of JSON that `summary` and the analyses write: numbers and strings.
#pragma once
#include <cmath>
#include <cstdio>
#include <string>

namespace mc {

// A number: 10 significant digits, null when not finite.
inline std::string json_number(double x) {
  if (!std::isfinite(x)) return "null";
  char b[32];
  std::snprintf(b, sizeof b, "%.10g", x);
  return b;
}

// A string, quoted and escaped; control characters become spaces.
inline std::string json_quote(const std::string& s) {
  std::string o = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\')
      o += '\\', o += c;
    else if (c == '\n')
      o += "\\n";
    else if (static_cast<unsigned char>(c) < 0x20)
      o += ' ';
    else
      o += c;
  }
  return o + "\"";
}

}  // namespace mc
