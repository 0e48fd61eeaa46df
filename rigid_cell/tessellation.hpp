// The rigid cells of a specimen: the Voronoi tessellation of its nodes (Květoň §3.1), bounded by the specimen's
// surface through mirror images of the nodes near it (specimen_shape.hpp). The Delaunay triangulation comes from
// CGAL (exact predicates); each Voronoi face is the dual of a Delaunay edge, its vertices the circumcentres of the
// Delaunay simplices around that edge.
#pragma once
#include <vector>

#include "rigid_cell/mass_properties.hpp"
#include "rigid_cell/specimen_shape.hpp"

namespace mc::rigid_cell {

template <int D>
struct Cell {
  Vec<D> node;
  MassProperties<D> mass;  // per unit density, about the node
};

// A face between two cells (a contact, b ≥ 0) or between a cell and the specimen's surface (b = -1).
template <int D>
struct Facet {
  int a = -1, b = -1;
  double area = 0;  // [m²]; 2D: the segment's length × 1 m
  Vec<D> centroid = Vec<D>::Zero();
  Vec<D> normal = Vec<D>::Zero();  // from a's node towards b's (or towards a's mirror image)
  double length = 0;               // L: the distance between the two nodes (a's node and its image on the surface)
  std::vector<Vec<D>> vertices;    // in order around the face (2D: its two ends)
};

template <int D>
struct Tessellation {
  std::vector<Cell<D>> cells;
  std::vector<Facet<D>> facets;  // the contacts first, then the surface faces
  std::size_t contacts = 0;      // how many facets join two cells
  double volume() const {
    double v = 0;
    for (const auto& c : cells) v += c.mass.volume;
    return v;
  }
};

// Throws InputError naming the node when a node lies outside the shape or two nodes coincide (closer than 1e-9 of
// the specimen's size).
template <int D>
void check_nodes(const std::vector<Vec<D>>& nodes, const SpecimenShape<D>& shape);

// Throws InputError as check_nodes, and naming the cell when one is left unbounded (a node too far from its mirror
// images: reach too short).
// `reach`: nodes nearer the surface than this are mirrored; twice the largest cell's radius is always enough.
template <int D>
Tessellation<D> tessellate(const std::vector<Vec<D>>& nodes, const SpecimenShape<D>& shape, double reach);

}  // namespace mc::rigid_cell
