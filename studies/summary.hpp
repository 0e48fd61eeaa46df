// `mesocrack summary`: the key results of a run as one JSON object, computed from the histories in its output
// file (so it works on a finished run, a stopped one, and one killed mid-way): the scene's [[summary]]
// reductions, each analysis's block, and the last value of every history.
#pragma once
#include <string>

namespace mc {

std::string summary_json(const std::string& output_file);

}  // namespace mc
