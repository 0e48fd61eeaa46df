// A run as its output file keeps it (finished, stopped, or killed mid-way): the scene it ran, re-read and
// validated, its histories and its status. What `summary`, the realizations and the calibration read.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "scene/analyses/uniaxial.hpp"
#include "scene/scene.hpp"

namespace mc {

struct StoredRun {
  Scene scene;
  Histories histories;
  std::map<std::string, std::string> units;  // each history's SI unit ("1": none)
  std::vector<LoggedCrack> cracks;  // the crack log; empty without one
  std::string status, status_message;
  std::int64_t particles = 0;
  // What generating the specimen measured (its /specimen attributes: packing_*, aggregate_*, bonds_* …).
  std::vector<std::pair<std::string, double>> specimen_facts;
};

// Throws IoError for a file that is not a mesocrack output file.
StoredRun read_stored_run(const std::string& output_file);

// The [uniaxial] results of a stored run; InputError when its scene declares no [uniaxial] analysis.
UniaxialResult uniaxial_result(const std::string& output_file);

}  // namespace mc
