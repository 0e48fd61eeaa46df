// A parsed document written back as TOML text, for the scene stored with a run when --set changed it. Each value
// is written once, so the time is linear in the document: toml11's own serializer tries the inline and the
// multi-line form of every table below every table, and took minutes for a table nested 30 deep. Internal to
// scene/.
#pragma once
#include <string>

#include "scene/toml_document.hpp"

namespace mc::detail {

// Plain keys first, then sub-tables as [a.b] sections and arrays of tables as [[a.b]] sections; arrays and tables
// inside arrays inline. Comments are kept above the keys and sections they belong to, the root's at the top.
// Floats are written with `float_digits` significant digits.
std::string write_toml(const Value& root, int float_digits);

}  // namespace mc::detail
