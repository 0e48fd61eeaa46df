// Reader for plain particle lists: one particle per line, `id x y z r tag` in SI units, `#` starts a comment
// (whole line or end of line), blank lines are skipped. A 2D file has discs: either the same six columns with
// z = 0, or five columns `id x y r tag`. The dimension is the caller's (template argument), not guessed.
//
// Every bad line fails with one InputError naming the file, the line number, the offending text and what is
// allowed, e.g. `n10k.spheres:17: radius '-1' must be > 0`. A file that cannot be read is an IoError naming
// the path and the OS reason.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "engine/dim.hpp"

namespace mc {

template <int D>
struct SphereList {
  std::vector<Vec<D>> x;         // centres [m]
  std::vector<double> radius;    // [m], > 0
  std::vector<int> tag;          // the file's group tag (e.g. 0 interior, 1 and 2 boundary layers)
  std::vector<std::int64_t> id;  // the file's ids, unique and >= 0, in file order

  int size() const { return static_cast<int>(x.size()); }
};

// Reads the file at `path`. D = 3: six fields per line. D = 2: five fields, or six with z = 0.
template <int D>
SphereList<D> read_sphere_list(const std::string& path);

// The same from text already in memory; `name` stands for the file in messages.
template <int D>
SphereList<D> parse_sphere_list(std::string_view text, const std::string& name);

extern template SphereList<2> read_sphere_list<2>(const std::string&);
extern template SphereList<3> read_sphere_list<3>(const std::string&);
extern template SphereList<2> parse_sphere_list<2>(std::string_view, const std::string&);
extern template SphereList<3> parse_sphere_list<3>(std::string_view, const std::string&);

}  // namespace mc
