// The command line's --set overrides of a scene file ("walls[1].velocity=5 mm/s"): applied to the parsed
// document before anything reads it, and written back into the text stored with the results.
#pragma once
#include <string>
#include <vector>

namespace mc::detail {

struct TomlState;

// Applies each override "key.path=value" to st.root in order and records its key path in st.set_paths.
// The value is TOML if it parses, else a bare string. Throws InputError naming the override.
void apply_overrides(TomlState& st, const std::vector<std::string>& overrides);

// st's document as TOML text, headed by a comment listing the overrides; it re-parses to the same values.
std::string serialise(const TomlState& st, const std::vector<std::string>& overrides);

}  // namespace mc::detail
