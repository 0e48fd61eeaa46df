// Where each fibre crosses the facets between rigid cells (Květoň §5.4: the virtual facet of area π d_f²/4 at the
// crossing point). A fibre is followed from its end a through the cells it passes: the cell holding a is the one of
// the nearest node (a Voronoi cell), and the fibre leaves a convex cell through the first of its facets' planes it
// meets outwards. So a fibre costs its crossings times the facets of a cell, whatever the specimen's size, and the
// crossings come in order along it.
#pragma once
#include <vector>

#include "rigid_cell/fibre_placement.hpp"
#include "rigid_cell/tessellation.hpp"

namespace mc::rigid_cell {

struct FibreCrossing {
  int fibre = -1;
  int facet = -1;      // a contact of the tessellation
  double at = 0;       // the distance from the fibre's end a to the crossing [m]
  double cosine = 0;   // u · n: the fibre's direction (a to b) against the facet's normal (its cell a to b)
  Vec<3> point = Vec<3>::Zero();
};

// Every fibre's crossings, fibre by fibre, each fibre's in order from its end a. Throws std::runtime_error naming
// the fibre when its walk through the cells does not end (a degenerate crossing through an edge or a vertex that
// round-off sends back and forth).
std::vector<FibreCrossing> fibre_crossings(const Tessellation<3>& t, const std::vector<Fibre>& fibres);

}  // namespace mc::rigid_cell
