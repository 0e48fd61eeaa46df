// Květoň §3.3: a facet's law evaluated at more points than its centroid. A *simple* facet lumps its area into its
// centroid, so two cells rotating against each other about it strain it nowhere: it has no rotational stiffness. A
// *discretized* facet is the triangles its vertices make with its centroid (2D: its two halves), the law applied at
// each triangle's centroid over the triangle's area (Fig. 3.1(d)). The parts' areas sum to the facet's and their
// first moment about its centroid is zero, so a uniform strain loads them as it loads the simple facet; their second
// moment is the rotational stiffness kept: 3/4 of a segment's, 2/3 of a square's.
#pragma once
#include <cstddef>
#include <vector>

#include "rigid_cell/tessellation.hpp"

namespace mc::rigid_cell {

// A tessellation whose contact facets are replaced by their parts, contact facet f's being parts.facets[first[f],
// first[f + 1]), in order. Each part keeps its facet's cells, normal and length L (the crack band (3.20) is the
// cells'), and has its own area, centroid (its integration point) and vertices (its triangle). The surface facets
// follow the parts unchanged.
template <int D>
struct FacetParts {
  Tessellation<D> parts;
  std::vector<std::size_t> first;  // contacts + 1 entries
};

template <int D>
FacetParts<D> discretize_facets(const Tessellation<D>& t);

// The part of contact facet f (parts [first[f], first[f + 1]) of `parts`) that holds the point x of its plane (the
// nearest one when x lies just outside all: round-off on an edge).
// The contact facet whose parts include `part`.
std::size_t facet_of_part(const std::vector<std::size_t>& first, std::size_t part);

template <int D>
std::size_t part_holding(const Tessellation<D>& parts, const std::vector<std::size_t>& first, std::size_t f,
                         const Vec<D>& x);

}  // namespace mc::rigid_cell
