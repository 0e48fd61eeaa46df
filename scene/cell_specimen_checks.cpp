#include "scene/cell_specimen_checks.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "engine/machine_memory.hpp"
#include "rigid_cell/factor_size.hpp"

namespace mc::scene_read {

// A specimen polygon must be simple: no vertex twice (a zero-length edge, whose cells the tessellation cannot
// bound), no edge crossing another (its cells would cover an area the outline does not have).
void refuse_repeated_or_crossing(const KeyReader& k, const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = x.size();
  double extent = 0;
  for (std::size_t i = 0; i < n; ++i) extent = std::max({extent, std::abs(x[i] - x[0]), std::abs(y[i] - y[0])});
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      if (std::hypot(x[i] - x[j], y[i] - y[j]) <= 1e-12 * extent)
        k.fail("vertices_x", "vertices " + std::to_string(i) + " and " + std::to_string(j) +
                                 " are the same point: give each corner once");
  auto cross = [&](std::size_t o, std::size_t a, std::size_t b) {
    return (x[a] - x[o]) * (y[b] - y[o]) - (y[a] - y[o]) * (x[b] - x[o]);
  };
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const std::size_t i1 = (i + 1) % n, j1 = (j + 1) % n;
      if (j == i1 || i == j1) continue;  // neighbouring edges share a vertex
      // Proper crossings and touchings: each edge's ends on opposite sides of (or on) the other's line.
      const double a = cross(i, i1, j), b = cross(i, i1, j1), c = cross(j, j1, i), d = cross(j, j1, i1);
      if (a * b <= 0 && c * d <= 0 && !(a == 0 && b == 0))
        k.fail("vertices_x", "edge " + std::to_string(i) + "-" + std::to_string(i1) + " meets edge " +
                                 std::to_string(j) + "-" + std::to_string(j1) +
                                 ": the outline crosses itself; give the corners of a simple polygon in order");
    }
}

std::vector<AxisRange> specimen_bounds(const CellSpecimenSpec& c, int d) {
  std::vector<AxisRange> b(d);
  for (int i = 0; i < d; ++i) {
    auto& [lo, hi] = b[i];
    if (c.shape == CellSpecimenSpec::Shape::Box) {
      lo = 0, hi = c.size[i];
    } else if (i == 2) {
      lo = 0, hi = c.thickness;
    } else if (c.shape == CellSpecimenSpec::Shape::Disc) {
      lo = c.centre[i] - c.radius, hi = c.centre[i] + c.radius;
    } else {
      lo = hi = c.vertices[0][i];
      for (const auto& v : c.vertices) lo = std::min(lo, v[i]), hi = std::max(hi, v[i]);
    }
  }
  return b;
}

std::vector<double> specimen_extent(const CellSpecimenSpec& c, int d) {
  std::vector<double> e;
  for (const auto& [lo, hi] : specimen_bounds(c, d)) e.push_back(hi - lo);
  return e;
}

namespace {

// Random sequential addition keeps a node at least l_min/2 inside the surface and l_min from every other; it
// saturates (max_rejections 2000) at 0.60-0.77 nodes per l_min³ of that inner volume in 3D and 0.62 per l_min² in
// 2D (measured: prisms of 370-18 543 cells, discs of 2 308-9 329), 0.6 taken as the least.
constexpr double kNodesPerLminVolume = 0.6;
// A run's memory per cell, at least (measured: the peak resident size of one static step, incremental between
// sizes): 2D 7.1 kB (discs of 2 308 and 9 329 cells); 3D 48-61 kB (prisms of 1 871-18 543 cells, most of it the
// factor, whose fill per cell grows with the size). The refusal must never turn away what fits.
constexpr double kBytesPerCell2D = 6e3, kBytesPerCell3D = 40e3;

// The specimen shrunk by l_min/2 on every side, where the nodes lie: its volume (2D: area), or 0 if none is left.
double inner_volume(const CellSpecimenSpec& c, int d) {
  const double h = c.l_min;  // l_min/2 off each side
  using S = CellSpecimenSpec::Shape;
  double v = 1;
  if (c.shape == S::Box) {
    for (const double side : c.size) v *= std::max(0.0, side - h);
    return v;
  }
  if (c.shape == S::Disc) {
    v = std::numbers::pi * std::pow(std::max(0.0, c.radius - h / 2), 2);
  } else {  // the area less a band l_min/2 wide along the perimeter: a lower bound of the inner area
    double twice_area = 0, perimeter = 0;
    for (std::size_t i = 0; i < c.vertices.size(); ++i) {
      const auto& a = c.vertices[i];
      const auto& b = c.vertices[(i + 1) % c.vertices.size()];
      twice_area += a[0] * b[1] - b[0] * a[1];
      perimeter += std::hypot(b[0] - a[0], b[1] - a[1]);
    }
    v = std::max(0.0, twice_area / 2 - perimeter * h / 2);
  }
  return d == 3 ? v * std::max(0.0, c.thickness - h) : v;
}

// The volume (2D: area) of the fine box within the specimen's inner volume, at least: its overlap with the bounding
// box less what of the bounding box is not inner.
double fine_inner_volume(const CellSpecimenSpec& c, int d, double inner) {
  double box = 1, overlap = 1;
  const std::vector<AxisRange> bounds = specimen_bounds(c, d);
  for (int i = 0; i < d; ++i) {
    const auto [lo, hi] = bounds[i];
    box *= hi - lo;
    overlap *= std::max(0.0, std::min(hi, c.fine_hi[i]) - std::max(lo, c.fine_lo[i]));
  }
  return std::max(0.0, overlap - (box - inner));
}

}  // namespace

void read_coarsening(const KeyReader& k, CellSpecimenSpec& c, int d) {
  if (!k.has("l_max")) {
    for (const char* key : {"fine_lo", "fine_hi", "grading"})
      if (k.has(key)) k.fail(key, "coarsens the cells away from a box, which needs l_max (the coarsest distance)");
    return;
  }
  if (k.has("nodes")) k.fail("l_max", "the nodes are given (nodes): there is no placement to coarsen");
  c.l_max = k.number("l_max");
  if (!(c.l_max >= c.l_min)) k.fail("l_max", "at least l_min, the distance in the fine box (equal: l_min everywhere)");
  c.fine_lo = k.numbers("fine_lo", d);
  c.fine_hi = k.numbers("fine_hi", d);
  for (int i = 0; i < d; ++i)
    if (!(c.fine_hi[i] > c.fine_lo[i]))
      k.fail("fine_hi", "each component must exceed fine_lo's (component " + std::to_string(i) + ")");
  c.grading = k.number("grading");
}

// Before any node is placed: a specimen with no room for a node, or whose cells this machine cannot hold, is refused
// with the estimate (placing 10⁹ nodes takes hours before it fails).
void check_cells_affordable(const KeyReader& k, const CellSpecimenSpec& c, int d) {
  const double inner = inner_volume(c, d);
  std::ostringstream m;
  m.precision(3);
  if (!(inner > 0)) {
    m << "every node keeps l_min/2 from the surface, so the specimen has no room for one; l_min must be below the "
         "specimen's smallest extent";
    k.fail("l_min", m.str());
  }
  // Coarsening cells: the fine box's inner part at l_min, the rest at l_max at least.
  const double fine = c.l_max > 0 ? fine_inner_volume(c, d, inner) : inner;
  const double cells = kNodesPerLminVolume * (fine / std::pow(c.l_min, d) +
                                              (inner - fine) / std::pow(std::max(c.l_max, c.l_min), d));
  const double per_cell = d == 2 ? kBytesPerCell2D : kBytesPerCell3D;
  const double need = cells * per_cell;
  const double have = physical_memory();
  const double values = d == 3 ? rigid_cell::least_factor_values_3d(cells) : 0;
  if (need <= have && values <= rigid_cell::kMostFactorValues) return;
  m << "the specimen would hold about " << cells << " cells, which need at least " << need / (1 << 30) << " GiB ("
    << per_cell / 1e3 << " kB each)";
  if (d == 3) m << " and a stiffness factor of at least " << values << " values";
  m << "; this machine has " << have / (1 << 30) << " GiB and its CHOLMOD takes at most "
    << rigid_cell::kMostFactorValues << " values: use a larger l_min or a smaller specimen";
  k.fail("l_min", m.str());
}

}  // namespace mc::scene_read
