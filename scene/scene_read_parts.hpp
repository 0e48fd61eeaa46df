// The parts of reading a scene (scene/scene_read.cpp and the files it splits into): one function per table,
// and the few helpers they share. Internal to scene/.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "scene/key_reader.hpp"
#include "scene/scene.hpp"
#include "scene/scene_keys.hpp"
#include "scene/toml_reader.hpp"

namespace mc::scene_read {

// A vector of `dim` numbers of the key's unit, required / optional (empty when absent).
std::vector<double> vec(const KeyReader& k, std::string_view key, int dim);
std::vector<double> opt_vec(const KeyReader& k, std::string_view key, int dim);
// The range of particle ids and tags: whole numbers from 0 to 2^53 (exact in a double).
inline constexpr Range kIds = Range::closed(0, 9007199254740992.0);
// A list of `n` particle ids or tags (n = 0: any length), whole numbers.
std::vector<std::int64_t> ids(const KeyReader& k, std::string_view key, std::size_t n);
// A box's low corner lies below its high corner in every direction, else fail naming hi_key.
void check_box(const KeyReader& k, std::string_view lo_key, const std::vector<double>& lo, std::string_view hi_key,
               const std::vector<double>& hi);
// The index of the phase named by `key`.
int phase_index(const KeyReader& k, std::string_view key, const std::vector<PhaseSpec>& phases);
// A file named in a scene is relative to the scene file's folder.
std::string relative_to(const std::string& scene_file, const std::string& path);

void read_specimen(const Table& root, Scene& s);       // scene/specimen_read.cpp
void read_mesostructure(const Table& root, Scene& s);  // scene/specimen_read.cpp
void read_walls(const Table& root, Scene& s);          // scene/boundary_read.cpp
void read_groups(const Table& root, Scene& s);         // scene/boundary_read.cpp
// A group driven at a velocity holds each axis it moves along (scene/boundary_read.cpp).
void check_driven_axes(const KeyReader& k, const GroupSpec& g, int d);
void read_physics(const Table& root, Scene& s);    // scene/boundary_read.cpp
void read_observers(const Table& root, Scene& s);  // scene/observers_read.cpp
// An opening probe's sides (particles or groups) and direction (scene/observers_read.cpp).
void read_opening(const KeyReader& k, const Scene& s, ProbeSpec& p);
// A scene with a [rigid_cell] table: its facet laws, cell specimen, mesostructure, plates and load step.
void read_rigid_cell(const Table& root, Scene& s);  // scene/rigid_cell_read.cpp
// [[rigid_cell.fibres]], after the specimen: a fibre at most `longest` (the specimen's longest extent) [m].
void read_fibres(const std::vector<Table>& tables, double longest, Scene& s);  // scene/fibres_read.cpp
// Each wall under opening control names an opening probe (after read_observers).
void check_opening_walls(const Table& root, const Scene& s);  // scene/observers_read.cpp

}  // namespace mc::scene_read
