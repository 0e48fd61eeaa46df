// Aggregate disposition, Tang (2013) §4.2: take-and-place on a background grid with a status matrix.
//
// The aggregates are made first (the "aggregate database", stage 1): random convex shapes whose exact areas /
// volumes fill each size range's share of fraction × domain (fill_grading). Then, largest first, each is put at
// a random position and orientation and checked:
//  1. it lies inside the domain (else it is shifted back in by what sticks out);
//  2. initial determination: its characteristic points (vertices, centroid, midpoints between the centroid and
//     the vertices) are looked up in the status matrix; a point whose cell belongs to a settled aggregate that
//     really contains the point is an overlap;
//  3. the keep-out zones (boxes, balls) are tested exactly;
//  4. detailed determination: the grid cells whose centres it covers are rasterised; any of them taken is an
//     overlap and the update is abandoned;
//  5. an exact separating-axis test against the settled aggregates whose bounding boxes meet its own, so that
//     no overlap slips between grid nodes (aggregates may touch, never overlap).
// On an overlap it is relocated by translation: moved away from the aggregate it hit by a random distance up to
// half its size, up to 3 times, then tried at a fresh random position (a random free cell) and orientation; an
// aggregate that fails `attempts` positions is given up, and the target is then not reached. On success its id
// is written into the cells it covers (Tang 4.5: the status matrix, here with the aggregate's id, not just 1).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "engine/dim.hpp"
#include "preprocess/aggregate_shape.hpp"
#include "preprocess/grading.hpp"

namespace mc {

template <int D>
struct AlignedBox {
  Vec<D> lo, hi;
};

template <int D>
struct Ball {
  Vec<D> centre;
  double radius = 0;
};

template <int D>
struct PlacementSpec {
  Vec<D> lo = Vec<D>::Zero(), hi = Vec<D>::Zero();  // the domain, a rectangle / box
  Grading grading = tang_table_4_1();
  double fraction = 0.5;  // target aggregate area / volume fraction of the whole domain (keep-out zones included)
  ShapeParams shape;
  SizeDraw size_draw = SizeDraw::uniform;
  double fuller_n = 0.5;  // for SizeDraw::fuller
  // Zones that stay mortar (Tang §7.1: the notch, and a radius around its tip): no aggregate may overlap them.
  std::vector<AlignedBox<D>> keep_out_boxes;
  std::vector<Ball<D>> keep_out_balls;
  double cells_per_dmin =
      5;                // grid cell = D_min / cells_per_dmin (per axis, rounded to fit the domain), in [5, 10] (4.6)
  int attempts = 2000;  // fresh positions per aggregate (each with up to 3 relocations) before it is given up
  std::uint64_t seed = 1;
};

template <int D>
struct PlacedAggregate {
  ConvexShape<D> shape;  // in the domain: polygon vertices counter-clockwise / polyhedron vertices and faces
  Vec<D> centroid;
  Vec<D> lo, hi;       // bounding box
  double size = 0;     // d, the auxiliary circle / sphere diameter
  double content = 0;  // exact area / volume
  int range = 0;       // index in the grading's ranges
};

// The background grid (Tang 4.6) and status matrix (4.5): cell (i, j[, k]) has its centre at
// lo + (i + ½, j + ½[, k + ½]) ⊙ h; its status is the id of the aggregate containing that centre (1, 2, …),
// 0 for mortar, kKeepOut for mortar in a keep-out zone. Index i + n₀ (j + n₁ k).
template <int D>
struct StatusGrid {
  static constexpr std::int32_t kKeepOut = -1;
  Vec<D> lo = Vec<D>::Zero(), h = Vec<D>::Ones();
  std::array<int, D> n{};
  std::vector<std::int32_t> status;

  std::int64_t cells() const;
  std::int64_t cell_of(const Vec<D>& x) const;  // −1 outside the grid
  Vec<D> centre(std::int64_t cell) const;
  std::int32_t at(const Vec<D>& x) const;  // the status of x's cell (0 outside the grid)
};

struct RangeOutcome {
  double lo = 0, hi = 0;                             // the size range
  double target_share = 0, target_fraction = 0;      // of the aggregate content / of the domain
  double achieved_share = 0, achieved_fraction = 0;  // by the exact contents of the placed aggregates
  int placed = 0, failed = 0;                        // aggregates placed / given up
};

// The mesostructure. For phases: aggregate_at(x) (exact) or status_at(x) (Tang's grid lookup) for each particle
// centre. For pictures: aggregates[i].shape.v are the outlines (2D, counter-clockwise); in 3D, section(shape, axis,
// value) from aggregate_shape.hpp gives the outline of each aggregate in a slice.
template <int D>
struct AggregateLayout {
  Vec<D> lo, hi;                               // the domain
  std::vector<PlacedAggregate<D>> aggregates;  // aggregate id = index + 1; largest first
  StatusGrid<D> grid;
  std::vector<RangeOutcome> ranges;  // in the order of the grading's ranges
  double target_fraction = 0, achieved_fraction = 0;
  bool reached = false;       // every aggregate was placed, so every range holds its target share
  std::int64_t attempts = 0;  // placements tried (fresh positions and relocations)

  // The aggregate containing x, exactly (0: mortar). Aggregates only touch, so a point in two is on both
  // boundaries; the lower id is returned.
  int aggregate_at(const Vec<D>& x) const;
  // Tang §4.3.1: the grid's answer, the aggregate containing the centre of x's cell (0: mortar).
  int status_at(const Vec<D>& x) const;

  // Bins of bounding boxes behind aggregate_at.
  Vec<D> bin_size;
  std::array<int, D> bins_n{};
  std::vector<std::vector<int>> bins;
};

// Throws InputError for a bad spec (empty domain, fraction outside (0, 1), bad grading or shape limits,
// cells_per_dmin outside [5, 10], a grid of more than 2³¹ cells, keep-out zones with non-positive size).
// Not reaching the target is not an error: see `reached` and `ranges`.
template <int D>
AggregateLayout<D> place_aggregates(const PlacementSpec<D>& spec);

}  // namespace mc
