// How deeply TOML text nests tables and arrays, measured by a flat scan before toml11 parses it. toml11's parser
// recurses once per level of [arrays] and {inline tables}, and copying, comparing, formatting and destroying a
// parsed value recurse once per level of any table, dotted keys included (a.b.c = 1 is three tables): a text
// nested 10 000 deep would overflow the stack in any of them. Internal to scene/.
#pragma once
#include <cstddef>
#include <optional>
#include <string_view>

namespace mc::detail {

// The deepest nesting a scene may use. Shipped scenes nest 3 deep (specimen.particles[0].x); 64 leaves room for
// any structure a person writes while keeping every recursion over a value to a few tens of kB of stack, far
// below the 8 MB of the main thread and the few MB of an OpenMP worker's.
inline constexpr std::size_t kMaxNesting = 64;

// Where the text first nests deeper than `limit`, and how deep the text nests at most.
struct Nesting {
  std::size_t deepest = 0;              // levels of tables and arrays below the root, each header and dot counted
  std::optional<std::size_t> too_deep;  // 1-based line where the depth first passes the limit (scanning stops)
};

// The scan knows TOML's strings, comments, headers, dotted keys, arrays and inline tables, and nothing else: it
// may over-count in text that is no valid TOML (which toml11 then refuses anyway), never under-count in text
// that is. The depth of a value is its header's keys, its own dotted key's parts and the brackets around it.
Nesting toml_nesting(std::string_view text, std::size_t limit = kMaxNesting);

}  // namespace mc::detail
