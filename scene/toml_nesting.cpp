#include "scene/toml_nesting.hpp"

#include <algorithm>
#include <vector>

namespace mc::detail {
namespace {

// One pass over the text, character by character, never recursing. The depth of a point is the number of tables
// and arrays around it, the root not counted: `[a.b]` puts its keys 2 deep, `[[a]]` 2 (the array and its entry),
// `x.y = 1` its 1 one deep, `x = [{y = 1}]` its 1 two deep.
class NestingScan {
 public:
  NestingScan(std::string_view text, std::size_t limit) : s_(text), limit_(limit) {}

  Nesting run() {
    while (i_ < s_.size() && !result_.too_deep) step(s_[i_]);
    return result_;
  }

 private:
  // Where the scan is on a line: before anything (a '[' opens a header), in a header, in a key (a '.' nests),
  // or in a value (brackets nest).
  enum class Mode { LineStart, Header, Key, Value };
  struct Open {
    bool inline_table;
    std::size_t depth;  // the depth outside the bracket
  };

  void step(char c) {
    if (c == '"' || c == '\'') return skip_string(c);
    if (c == '#') return skip_comment();
    ++i_;
    if (c == '\n') return new_line();
    switch (mode_) {
      case Mode::LineStart: return line_start(c);
      case Mode::Header: return header(c);
      case Mode::Key:
      case Mode::Value: return key_or_value(c);
    }
  }

  void line_start(char c) {
    if (c == ' ' || c == '\t' || c == '\r') return;
    if (c == '[') {  // a header: its keys start from the root
      mode_ = Mode::Header;
      depth_ = 0;
      return deeper(1);
    }
    mode_ = Mode::Key;
    key_or_value(c);
  }

  // `[a.b]` or `[[a.b]]`: its keys become the depth of the lines below it. Every '[' counts (a third one is no
  // TOML, but counting it cannot under-count); a ']' ends the header, and what follows on its line is read as a
  // value, so that brackets there count too.
  void header(char c) {
    if (c == '[' || c == '.') return deeper(1);
    if (c == ']') end_header();
  }

  void end_header() {
    header_depth_ = depth_;
    mode_ = Mode::Value;
  }

  void key_or_value(char c) {
    if (c == '.' && mode_ == Mode::Key) return deeper(1);
    if (c == '=' && mode_ == Mode::Key) mode_ = Mode::Value;
    if (c == '[' || c == '{') return open(c == '{');
    if ((c == ']' || c == '}') && !open_.empty()) return close();
    if (c == ',' && !open_.empty()) return next_entry();
  }

  void open(bool inline_table) {
    open_.push_back({inline_table, depth_});
    mode_ = inline_table ? Mode::Key : Mode::Value;
    deeper(1);
  }

  void close() {
    depth_ = open_.back().depth;
    open_.pop_back();
    mode_ = Mode::Value;
  }

  // After a ',' in an array comes the next value; in an inline table, the next key.
  void next_entry() {
    depth_ = open_.back().depth + 1;
    mode_ = open_.back().inline_table ? Mode::Key : Mode::Value;
  }

  // Arrays span lines; anything else ends with its line, and the next line starts at the header's depth.
  void new_line() {
    ++line_;
    if (mode_ == Mode::Header) end_header();
    if (!open_.empty()) return;
    mode_ = Mode::LineStart;
    depth_ = header_depth_;
  }

  void deeper(std::ptrdiff_t levels) {
    depth_ = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(depth_) + levels);
    result_.deepest = std::max(result_.deepest, depth_);
    if (depth_ > limit_) result_.too_deep = line_;
  }

  void skip_comment() {
    const auto end = s_.find('\n', i_);
    i_ = end == std::string_view::npos ? s_.size() : end;
  }

  // "basic" and 'literal' strings end at their line (toml11 refuses one left open there, before it reads on);
  // """multi-line""" and '''multi-line''' ones at their closing triple. A backslash escapes the next character in
  // basic strings only.
  void skip_string(char quote) {
    if (mode_ == Mode::LineStart) mode_ = Mode::Key;  // a quoted key
    const std::string_view triple = quote == '"' ? R"(""")" : "'''";
    const bool multi_line = s_.substr(i_, 3) == triple;
    i_ += multi_line ? 3 : 1;
    while (i_ < s_.size()) {
      const char c = s_[i_];
      if (c == '\n' && !multi_line) return;  // the newline is the scan's again
      if (c == '\n') ++line_;
      if (c == '\\' && quote == '"' && i_ + 1 < s_.size() && s_[i_ + 1] != '\n') {
        i_ += 2;
        continue;
      }
      if (c == quote && (!multi_line || s_.substr(i_, 3) == triple)) {
        i_ += multi_line ? 3 : 1;
        return;
      }
      ++i_;
    }
  }

  std::string_view s_;
  std::size_t limit_;
  std::size_t i_ = 0;
  std::size_t line_ = 1;
  Mode mode_ = Mode::LineStart;
  std::size_t depth_ = 0;
  std::size_t header_depth_ = 0;
  std::vector<Open> open_;
  Nesting result_;
};

}  // namespace

Nesting toml_nesting(std::string_view text, std::size_t limit) { return NestingScan(text, limit).run(); }

}  // namespace mc::detail
