// What the 2D and 3D builders of the tessellation (tessellation_2d.cpp, tessellation_3d.cpp) share around their
// CGAL parts.
#pragma once
#include <array>
#include <utility>
#include <vector>

#include "rigid_cell/tessellation.hpp"

namespace mc::rigid_cell {

// Where a builder begins: the nodes checked (check_nodes), then the points to triangulate, the nodes followed by
// their mirror images across the surface within `reach`.
template <int D>
std::vector<Vec<D>> nodes_and_images(const std::vector<Vec<D>>& nodes, const SpecimenShape<D>& shape, double reach);

// Throws InputError: the cell's node lies farther from the surface than the mirroring reach.
template <int D>
[[noreturn]] void throw_unbounded(int cell, const Vec<D>& node);

// A Delaunay simplex's circumcentre from its vertices given with their point indices: computed with the vertices in
// the order of their indices, so that its bits do not depend on the order CGAL keeps them in (which follows the
// addresses its allocations happened to get). Also returns the sorted indices, the simplex's key.
template <int D>
std::pair<Vec<D>, std::array<int, D + 1>> circumcentre(std::array<std::pair<int, Vec<D>>, D + 1> vertices);

// Where a builder ends, with the contacts (in t.facets) and the surface faces: the contacts sorted by their cells
// and the surface faces after them, so that the order does not depend on the triangulation's; then the cells at
// the nodes, each one's volume and moments from the pyramids over its faces, in that order. Throws InputError
// naming the two cells when a contact joins cells across a gap of the outline (a notch, a slit narrower than the
// cells: the nodes on either side mirror into each other's side, where images are dropped).
template <int D>
void finish(Tessellation<D>& t, const std::vector<Vec<D>>& nodes, std::vector<Facet<D>> surface,
            const SpecimenShape<D>& shape);

}  // namespace mc::rigid_cell
