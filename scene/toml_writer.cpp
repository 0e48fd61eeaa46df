#include "scene/toml_writer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace mc::detail {
namespace {

// A basic string with TOML's escapes.
std::string basic_string(const std::string& s) {
  static const char* hex = "0123456789abcdef";
  std::string out = "\"";
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\')
      out += std::string("\\") + c;
    else if (c == '\n')
      out += "\\n";
    else if (c == '\t')
      out += "\\t";
    else if (c == '\r')
      out += "\\r";
    else if (u < 0x20 || u == 0x7f)
      out += std::string("\\u00") + hex[u >> 4] + hex[u & 15];
    else
      out += c;
  }
  return out + "\"";
}

std::string key_text(const std::string& key) {
  const bool bare = !key.empty() && key.find_first_not_of(
                                        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                                        "0123456789_-") == std::string::npos;
  return bare ? key : basic_string(key);
}

std::string float_text(double x, int digits) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  std::string s = buf;
  if (s.find_first_of(".e") == std::string::npos) s += ".0";  // else it would read back as an integer
  return s;
}

bool is_array_of_tables(const Value& v) {
  return v.is_array() && !v.as_array().empty() &&
         std::all_of(v.as_array().begin(), v.as_array().end(), [](const Value& e) { return e.is_table(); });
}

class Writer {
 public:
  explicit Writer(int digits) : digits_(digits) {}

  std::string document(const Value& root) {
    if (!root.comments().empty()) {
      comments(root);
      out_ += "\n";  // a blank line: the comments are the file's, not its first key's
    }
    body(root, "");
    return out_;
  }

 private:
  void comments(const Value& v) {
    for (const auto& c : v.comments()) out_ += "#" + c + "\n";
  }

  std::string inline_value(const Value& v) const {
    if (v.is_string()) return basic_string(v.as_string().str);
    if (v.is_floating()) return float_text(v.as_floating(), digits_);
    if (v.is_array()) {
      std::string s = "[";
      for (const auto& e : v.as_array()) s += (s.size() > 1 ? ", " : "") + inline_value(e);
      return s + "]";
    }
    if (v.is_table()) {
      std::string s = "{";
      for (const auto& [k, e] : v.as_table()) s += (s.size() > 1 ? ", " : "") + key_text(k) + " = " + inline_value(e);
      return s + "}";
    }
    return toml::format(v);  // integers, booleans, dates: no recursion
  }

  // A table's plain keys, then its sub-tables and arrays of tables, each as sections below `path`.
  void body(const Value& table, const std::string& path) {
    for (const auto& [k, v] : table.as_table()) {
      if (v.is_table() || is_array_of_tables(v)) continue;
      comments(v);
      out_ += key_text(k) + " = " + inline_value(v) + "\n";
    }
    for (const auto& [k, v] : table.as_table()) {
      const std::string sub = path.empty() ? key_text(k) : path + "." + key_text(k);
      if (v.is_table()) {
        out_ += "\n";
        comments(v);
        out_ += "[" + sub + "]\n";
        body(v, sub);
      } else if (is_array_of_tables(v)) {
        for (const auto& e : v.as_array()) {
          out_ += "\n";
          comments(e);
          out_ += "[[" + sub + "]]\n";
          body(e, sub);
        }
      }
    }
  }

  int digits_;
  std::string out_;
};

}  // namespace

std::string write_toml(const Value& root, int float_digits) { return Writer(float_digits).document(root); }

}  // namespace mc::detail
