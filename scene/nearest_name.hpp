// Naming a misspelling: the known name a given one is nearest to, for "a misspelling of 'walls'?" in messages.
#pragma once
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace mc {

// Levenshtein's distance: the fewest single-letter insertions, deletions and changes from a to b.
std::size_t edit_distance(std::string_view a, std::string_view b);
// The name of `known` nearest to `given`, when it is within `most` edits and not `given` itself; else "".
std::string nearest_name(std::string_view given, const std::vector<std::string>& known, std::size_t most = 2);

}  // namespace mc
