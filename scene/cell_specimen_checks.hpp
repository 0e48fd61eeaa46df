// The checks of a cell specimen's outline and size that need no cell (scene/rigid_cell_read.cpp reads the table):
// a simple polygon, the coarsening's box, and room and memory for the cells random sequential addition would
// place. Internal to scene/.
#pragma once
#include <vector>

#include "scene/key_reader.hpp"
#include "scene/scene.hpp"

namespace mc::scene_read {

// No vertex twice, no edge crossing another; else fail naming vertices_x.
void refuse_repeated_or_crossing(const KeyReader& k, const std::vector<double>& x, const std::vector<double>& y);
// The specimen's bounding box, axis by axis (a 3D disc or polygon: z from 0 to the thickness) [m].
struct AxisRange {
  double lo = 0, hi = 0;
};
std::vector<AxisRange> specimen_bounds(const CellSpecimenSpec& c, int d);
// Its extent along each axis: what the random field's grid spans.
std::vector<double> specimen_extent(const CellSpecimenSpec& c, int d);
// l_max with its fine box and grading: l_max at least l_min, the box's corners D numbers each and in order; the box
// keys without l_max, or with given nodes, fail naming them.
void read_coarsening(const KeyReader& k, CellSpecimenSpec& c, int d);
// A specimen with no room for a node, or whose cells this machine cannot hold, fails naming l_min, with the estimate.
void check_cells_affordable(const KeyReader& k, const CellSpecimenSpec& c, int d);

}  // namespace mc::scene_read
