#include "io/sphere_list.hpp"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <system_error>
#include <unordered_map>

#include "engine/errors.hpp"

namespace mc {

namespace {

// The offending text as it appears in a message: quoted, shortened if it is very long.
std::string quoted(std::string_view s) {
  std::string q(1, '\'');
  if (s.size() > 40) {
    q.append(s.substr(0, 37));
    q.append("...");
  } else {
    q.append(s);
  }
  q.push_back('\'');
  return q;
}

struct LineError {
  const std::string& name;
  std::size_t line;
  [[noreturn]] void operator()(const std::string& what) const {
    throw InputError(name + ":" + std::to_string(line) + ": " + what);
  }
};

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// A finite double filling the whole token. `field` names it in the message.
double number(std::string_view tok, const char* field, const LineError& fail) {
  std::string_view t = tok;
  if (t.size() > 1 && t[0] == '+' && t[1] != '-' && t[1] != '+') t.remove_prefix(1);  // from_chars refuses '+'
  double v = 0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (ec == std::errc::result_out_of_range)
    fail(std::string(field) + " " + quoted(tok) + " is out of the range of a double");
  if (ec != std::errc() || end != t.data() + t.size())
    fail(std::string(field) + " " + quoted(tok) + " is not a number");
  if (!std::isfinite(v)) fail(std::string(field) + " " + quoted(tok) + " must be a finite number");
  return v;
}

template <class T>
bool integer(std::string_view tok, T& v) {
  std::string_view t = tok;
  if (t.size() > 1 && t[0] == '+' && t[1] != '-' && t[1] != '+') t.remove_prefix(1);
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  return ec == std::errc() && end == t.data() + t.size();
}

}  // namespace

template <int D>
SphereList<D> parse_sphere_list(std::string_view text, const std::string& name) {
  static_assert(D == 2 || D == 3);
  SphereList<D> out;
  // A rough line count sizes the arrays once (about 70 characters per line in the usual files).
  const std::size_t guess = text.size() / 48 + 1;
  out.x.reserve(guess);
  out.radius.reserve(guess);
  out.tag.reserve(guess);
  out.id.reserve(guess);
  std::unordered_map<std::int64_t, std::size_t> line_of_id;
  line_of_id.reserve(guess);

  std::size_t pos = 0, line = 0;
  std::string_view tok[7];
  while (pos < text.size()) {
    ++line;
    std::size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos) eol = text.size();
    std::string_view s = text.substr(pos, eol - pos);
    pos = eol + 1;
    if (const std::size_t hash = s.find('#'); hash != std::string_view::npos) s = s.substr(0, hash);

    // Split on blanks; count every field so the message can say how many there were.
    int nf = 0;
    std::size_t i = 0;
    while (i < s.size()) {
      while (i < s.size() && is_space(s[i])) ++i;
      if (i == s.size()) break;
      const std::size_t b = i;
      while (i < s.size() && !is_space(s[i])) ++i;
      if (nf < 7) tok[nf] = s.substr(b, i - b);
      ++nf;
    }
    if (nf == 0) continue;  // blank or comment only

    const LineError fail{name, line};
    const bool five = D == 2 && nf == 5;
    if (!(nf == 6 || five)) {
      if constexpr (D == 3)
        fail("expected 6 fields 'id x y z r tag', found " + std::to_string(nf));
      else
        fail("expected 5 fields 'id x y r tag' or 6 fields 'id x y z r tag' with z = 0 (2D list), found " +
             std::to_string(nf));
    }

    std::int64_t id = 0;
    if (!integer(tok[0], id) || id < 0) fail("id " + quoted(tok[0]) + " must be an integer >= 0");

    Vec<D> x;
    x[0] = number(tok[1], "x", fail);
    x[1] = number(tok[2], "y", fail);
    int next = 3;
    if constexpr (D == 3) {
      x[2] = number(tok[3], "z", fail);
      next = 4;
    } else if (!five) {
      if (number(tok[3], "z", fail) != 0.0)
        fail("z " + quoted(tok[3]) + " must be 0 in a 2D list (the discs lie in the plane z = 0)");
      next = 4;
    }
    const double r = number(tok[next], "radius", fail);
    if (!(r > 0)) fail("radius " + quoted(tok[next]) + " must be > 0");
    int tag = 0;
    if (!integer(tok[next + 1], tag)) fail("tag " + quoted(tok[next + 1]) + " must be an integer");

    const auto [it, fresh] = line_of_id.emplace(id, line);
    if (!fresh)
      fail("id " + quoted(tok[0]) + " is already used on line " + std::to_string(it->second) + "; ids must be unique");

    out.x.push_back(x);
    out.radius.push_back(r);
    out.tag.push_back(tag);
    out.id.push_back(id);
  }
  if (out.x.empty())
    throw InputError(name + ": no particles (every line is blank or a comment); expected lines " +
                     (D == 3 ? std::string("'id x y z r tag'") : std::string("'id x y r tag' or 'id x y z r tag'")));
  return out;
}

template <int D>
SphereList<D> read_sphere_list(const std::string& path) {
  auto cannot_read = [&](int err) { throw IoError("cannot read particle list '" + path + "': " + std::strerror(err)); };
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!f) cannot_read(errno);
  std::string text;
  char buf[1 << 16];
  std::size_t got;
  while ((got = std::fread(buf, 1, sizeof buf, f.get())) > 0) text.append(buf, got);
  if (std::ferror(f.get())) cannot_read(errno);  // e.g. EISDIR: fopen accepts a directory
  return parse_sphere_list<D>(text, path);
}

template SphereList<2> read_sphere_list<2>(const std::string&);
template SphereList<3> read_sphere_list<3>(const std::string&);
template SphereList<2> parse_sphere_list<2>(std::string_view, const std::string&);
template SphereList<3> parse_sphere_list<3>(std::string_view, const std::string&);

}  // namespace mc
