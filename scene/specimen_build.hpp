// The particles of a scene's specimen, read, loaded or generated, and the coarse aggregate laid over them
// (scene/specimen_build.cpp). Used by build_world.
#pragma once
#include <vector>

#include "engine/particles.hpp"
#include "preprocess/aggregate_placement.hpp"
#include "scene/build_world.hpp"

namespace mc {

template <int D>
Vec<D> vec_of(const std::vector<double>& v) {
  Vec<D> out;
  for (int k = 0; k < D; ++k) out[k] = v[k];
  return out;
}

// Whether x lies in the box [lo, hi], faces included.
template <int D>
bool in_box(const Vec<D>& x, const std::vector<double>& lo, const std::vector<double>& hi) {
  for (int k = 0; k < D; ++k)
    if (!(x[k] >= lo[k] && x[k] <= hi[k])) return false;
  return true;
}
template <int D>
Rot<D> rot_of(const std::vector<double>& v) {
  Rot<D> out;
  for (int k = 0; k < Dim<D>::rot; ++k) out[k] = v[k];
  return out;
}

// The specimen's particles, with each one's tag (sphere lists; 0 otherwise); ids and generation facts go to
// `info`. Sphere lists and generated packings are renumbered along a Morton curve (cache locality).
template <int D>
void add_specimen(const Scene& s, Particles<D>& p, std::vector<int>& tags, SpecimenInfo& info);

// Tang §4.2–4.3.1: the coarse aggregate laid over the box [lo, hi] (or the scene's [mesostructure] lo, hi);
// throws InputError naming the table when the grading cannot be placed.
template <int D>
AggregateLayout<D> lay_aggregates(const Scene& s, const Vec<D>& lo, const Vec<D>& hi);
// The layout's fractions, targets and aggregate count, as generation facts.
template <int D>
void add_aggregate_facts(const AggregateLayout<D>& layout, std::vector<std::pair<std::string, double>>& facts);
// Outlines for pictures: 2D polygons; 3D sections at y = y_section, as (x, z).
template <int D>
std::vector<std::vector<std::array<double, 2>>> aggregate_outlines(const AggregateLayout<D>& layout, double y_section);

// Tang §4.2–4.3.1: aggregates laid over the specimen; mortar particles whose centres fall in one become
// aggregate. The fractions achieved go to info.facts, the outlines to info.outlines.
template <int D>
void apply_mesostructure(const Scene& s, Particles<D>& p, SpecimenInfo& info);

}  // namespace mc
