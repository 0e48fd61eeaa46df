// The keys of a rigid-cell scene (a scene with a [rigid_cell] table): the solver's options, the facet laws of
// [[contacts]], the cell specimen, the random field of its strength ([rigid_cell.random_field]), the plates
// ([[groups]] by box) and the load step (timestep.fixed); its fibre families are read by scene/fibres_read.cpp.
#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "rigid_cell/facet_law.hpp"  // facet_law_keys: the facet law's table, beside its parameters
#include "scene/cell_specimen_checks.hpp"
#include "scene/scene_read_parts.hpp"

namespace mc {

const KeyTable& rigid_cell_keys() {
  using P = RigidCellSpec;
  static const KeyTable t = key_table<P>(
      "rigid_cell", "[rigid_cell]: the rigid-cell model (Květoň 2019)",
      "A scene with this table runs on the rigid-cell family: Voronoi cells of nodes l_min apart ([specimen] kind = "
      "\"voronoi_cells\"), joined by the facet law of [[contacts]] (model = \"facet_damage\"), held and loaded by "
      "plates ([[groups]] by box), in static load steps of timestep.fixed, or in time with [rigid_cell.dynamics]. "
      "It has no walls, bonds, physics or measurement regions.",
      {
          bound(&P::damage_tolerance, {.name = "damage_tolerance",
                                      .range = Range{0.0, 1.0, true, false},
                                      .doc = "a step's iterations stop when no facet's damage moved more than this"}),
          bound(&P::force_tolerance,
               {.name = "force_tolerance",
                .range = Range{0.0, 1.0, true, false},
                .doc = "and when the out-of-balance force is at most this fraction of the reactions"}),
          bound(&P::max_iterations, {.name = "max_iterations",
                                    .range = Range::closed(1, 1e6),
                                    .doc = "of a load step; beyond it the run stops, naming the step"}),
          bound(&P::crack_log,
               {.name = "crack_log", .doc = "each facet's first damage and its crack (D ≥ 0.99) written to /cracks"}),
          bound(&P::energy,
               {.name = "energy", .doc = "boundary work, stored and dissipated energy as histories energy.*"}),
          bound(&P::facet_integration,
               {.name = "facet_integration",
                .doc = "where the facet law is evaluated (Květoň §3.3): simple, at the facet's centroid (no "
                       "rotational stiffness), or discretized, at the centroids of the triangles its vertices make "
                       "with it (2D: its halves); discretized, counts, frames and logs of facets are of these parts",
                .words = {"simple", "discretized"},
                .shown_default = "simple"}),
      });
  return t;
}

const KeyTable& cell_specimen_keys() {
  static const KeyTable t{
      .name = "cell_specimen",
      .title = "[specimen] kind = \"voronoi_cells\" (rigid-cell scenes)",
      .about = "A shape filled with random nodes at least l_min apart (placed until saturation), each the centre "
               "of a Voronoi cell (Květoň §3.1).",
      .keys = {
          {.name = "kind", .type = KeyType::Word, .need = Need::Required, .doc = "voronoi_cells", .words = {"voronoi_cells"}},
          {.name = "shape", .type = KeyType::Word,
           .need = Need::Required,
           .doc = "box (from the origin), disc (3D: a cylinder along z) or polygon (3D: a prism along z)",
           .words = {"box", "disc", "polygon"}},
          {.name = "size", .type = KeyType::Reals, .unit = Unit::Length, .range = Range::positive(), .need = Need::Required,
           .when = "shape = box", .doc = "its edges, from the origin"},
          {.name = "centre", .type = KeyType::Reals, .unit = Unit::Length, .need = Need::Required, .when = "shape = disc",
           .doc = "the axis in the x-y plane"},
          {.name = "radius", .unit = Unit::Length, .range = Range::positive(), .need = Need::Required,
           .when = "shape = disc", .doc = "the disc's"},
          {.name = "vertices_x", .type = KeyType::Reals, .unit = Unit::Length, .need = Need::Required, .when = "shape = polygon",
           .doc = "x of the vertices, at least 3, counter-clockwise"},
          {.name = "vertices_y", .type = KeyType::Reals, .unit = Unit::Length, .need = Need::Required, .when = "shape = polygon",
           .doc = "y of the vertices"},
          {.name = "thickness", .unit = Unit::Length, .range = Range::positive(), .need = Need::Required,
           .when = "3D disc or polygon", .doc = "along z, from 0"},
          {.name = "l_min", .unit = Unit::Length, .range = Range::positive(), .need = Need::Required,
           .doc = "the least distance between nodes"},
          {.name = "l_max", .unit = Unit::Length, .range = Range::positive(), .when = "with fine_lo, fine_hi",
           .doc = "cells that coarsen away from where the crack runs: nodes l(x) = min(l_max, l_min + grading · "
                  "distance from the box fine_lo..fine_hi) apart (two nodes the mean of their l), the box filled "
                  "first; fewer cells for the same crack where it stays in the box",
           .shown_default = "l_min everywhere"},
          {.name = "fine_lo", .type = KeyType::Reals, .unit = Unit::Length, .when = "with l_max",
           .doc = "the low corner of the box where nodes are l_min apart"},
          {.name = "fine_hi", .type = KeyType::Reals, .unit = Unit::Length, .when = "with l_max",
           .doc = "its high corner"},
          {.name = "grading", .range = Range{0.0, 1.0, true, false}, .when = "with l_max",
           .doc = "how fast the distance grows: metres per metre from the box (gentle grading keeps the cells' "
                  "shapes regular)",
           .fallback = 0.25},
          {.name = "max_rejections", .type = KeyType::Integer, .range = Range::closed(10, 1e8),
           .doc = "placement saturation: consecutive rejected trials that end it", .fallback = 2000},
          {.name = "nodes", .type = KeyType::Reals, .unit = Unit::Length,
           .doc = "the cells' nodes instead of random ones (x, y[, z] each; inside the shape): a few cells placed by "
                  "hand, as Květoň's single-contact tests (§6.1-6.2)"},
      },
      .location = "specimen"};
  return t;
}

const KeyTable& random_field_keys() {
  using P = RandomFieldSpec;
  static const KeyTable t = key_table<P>(
      "rigid_cell.random_field", "[rigid_cell.random_field]",
      "Květoň §3.4 (3.21): one random field h(x) of mean 1 scales each facet's tensile strength by h and its "
      "fracture energy by h², at the facet's centroid: a Karhunen-Loève expansion per axis on a grid over the "
      "specimen's box, carried to the centroids by EOLE, a Gaussian with a grafted Weibull left tail (Bažant & "
      "Pang 2007).",
      {
          bound(&P::correlation_length, {.name = "correlation_length",
                                        .unit = Unit::Length,
                                        .range = Range::positive(),
                                        .need = Need::Required,
                                        .doc = "l_c of the autocorrelation exp(−|Δx|²/l_c²)"}),
          bound(&P::std, {.name = "std",
                         .range = Range{0.0, 0.5, true, false},
                         .need = Need::Required,
                         .doc = "the standard deviation of h"}),
          {.name = "grid_spacing", .unit = Unit::Length, .range = Range::positive(),
           .doc = "of the Karhunen-Loève grid, at most correlation_length/2 and at most 1000 nodes per axis",
           .shown_default = "correlation_length/3"},
          bound(&P::variance_kept, {.name = "variance_kept",
                                   .range = Range{0.0, 0.9999, true, false},
                                   .doc = "the fraction of the grid's variance the modes kept carry"}),
          bound(&P::weibull_modulus, {.name = "weibull_modulus",
                                     .range = Range::closed(1, 100),
                                     .doc = "of the grafted left tail"}),
          bound(&P::grafting_probability, {.name = "grafting_probability",
                                          .range = Range{0.0, 0.1, true, false},
                                          .doc = "the probability where the tail is grafted on"}),
          {.name = "seed_offset", .type = KeyType::Integer, .range = Range::closed(0, 9.0e18),
           .doc = "the field's seed is the scene's plus this: several fields on the same cells", .fallback = 0},
      });
  return t;
}

const KeyTable& opening_control_keys() {
  static const KeyTable t{
      .name = "rigid_cell.opening_control",
      .title = "[rigid_cell.opening_control]",
      .about = "Indirect displacement control: a plate travels along `direction` so that an opening probe (between "
               "two plates) opens at `rate` through the smooth rise (9.1).",
      .keys = {
          {.name = "probe", .type = KeyType::Text, .need = Need::Required, .doc = "the opening probe"},
          {.name = "plate", .type = KeyType::Text, .need = Need::Required,
           .doc = "the plate ([[groups]]) that travels; its direction's axes held, without a velocity along them"},
          {.name = "direction", .type = KeyType::Reals, .need = Need::Required, .doc = "the direction it travels"},
          {.name = "rate", .unit = Unit::Velocity, .range = Range::positive().usually(1e-9, 0.05),
           .need = Need::Required,
           .doc = "the opening rate"},
          {.name = "ramp_time", .unit = Unit::Time, .range = Range::non_negative(),
           .doc = "the rate reached over this time", .fallback = 0},
      }};
  return t;
}

const KeyTable& cell_dynamics_keys() {
  using P = CellDynamicsSpec;
  static const KeyTable t = key_table<P>(
      "rigid_cell.dynamics", "[rigid_cell.dynamics] (Květoň ch. 8)",
      "Dynamics of the cells: implicit by Newmark's β, γ (8.1)-(8.5) with the full mass matrix (8.6)-(8.12), or "
      "explicit by central differences; Rayleigh damping C = a_M M + a_K K₀.",
      {
          {.name = "scheme", .type = KeyType::Word,
           .doc = "newmark or central_difference",
           .words = {"newmark", "central_difference"},
           .shown_default = "newmark"},
          bound(&P::beta, {.name = "beta",
                          .range = Range::positive(),
                          .doc = "Newmark's β; unconditionally stable for 2β ≥ γ ≥ 0.5 (8.5), Květoň §9.1's 0.3"}),
          bound(&P::gamma,
               {.name = "gamma", .range = Range::at_least(0.5), .doc = "Newmark's γ, Květoň §9.1's 0.55"}),
          bound(&P::mass_damping,
               {.name = "mass_damping", .unit = Unit::Rate, .range = Range::non_negative(), .doc = "a_M"}),
          bound(&P::stiffness_damping,
               {.name = "stiffness_damping", .unit = Unit::Time, .range = Range::non_negative(), .doc = "a_K"}),
      });
  return t;
}

const KeyTable& stress_wave_keys() {
  static const KeyTable t{
      .name = "rigid_cell.stress_wave",
      .title = "[rigid_cell.stress_wave]",
      .about = "A pressure wave on the surface facets in a box, in dynamics only: Květoň's cosine pulse (9.5), or a "
               "piecewise-linear one through given points (the measured waves of his §9.5.3).",
      .keys = {
          {.name = "box_lo", .type = KeyType::Reals, .unit = Unit::Length, .need = Need::Required, .doc = "the loaded facets' box"},
          {.name = "box_hi", .type = KeyType::Reals, .unit = Unit::Length, .need = Need::Required, .doc = "its high corner"},
          {.name = "pressure", .unit = Unit::Pressure, .need = Need::Required, .when = "a cosine pulse",
           .doc = "σ_max, positive pushing in, not 0"},
          {.name = "duration", .unit = Unit::Time, .range = Range::positive(), .need = Need::Required,
           .when = "a cosine pulse", .doc = "t_P"},
          {.name = "times", .type = KeyType::Reals, .unit = Unit::Time, .range = Range::non_negative(), .when = "a piecewise-linear wave",
           .doc = "from 0, increasing"},
          {.name = "pressures", .type = KeyType::Reals, .unit = Unit::Pressure, .when = "a piecewise-linear wave",
           .doc = "one per time, from 0 back to 0"},
      }};
  return t;
}

const KeyTable& sections_keys() {
  static const KeyTable t{
      .name = "rigid_cell.sections",
      .title = "[rigid_cell.sections]",
      .about = "Section planes normal to one axis: the mean normal stress across each is a history.",
      .keys = {
          {.name = "axis", .type = KeyType::Word, .need = Need::Required, .doc = "x, y or z (2D: x or y)", .words = {"x", "y", "z"}},
          {.name = "at", .type = KeyType::Reals, .unit = Unit::Length, .need = Need::Required, .doc = "the planes' positions along it"},
      }};
  return t;
}

const KeyTable& strain_box_keys() {
  static const KeyTable t{
      .name = "rigid_cell.strain",
      .title = "[rigid_cell.strain]",
      .about = "The mean strain of the cells whose nodes lie in a box, by the least-squares displacement gradient of "
               "those nodes: histories strain.xx, strain.yy, strain.xy (3D: and strain.zz, strain.yz, strain.zx), "
               "tensile positive, engineering-free (ε_xy is half the shear angle). An extensometer over the box: "
               "E and ν of a tension prism read away from its plates.",
      .keys = {
          {.name = "box_lo", .type = KeyType::Reals, .unit = Unit::Length, .need = Need::Required, .doc = "the box's low corner"},
          {.name = "box_hi", .type = KeyType::Reals, .unit = Unit::Length, .need = Need::Required, .doc = "its high corner"},
      }};
  return t;
}

namespace scene_read {

namespace {

void read_facet_laws(const Table& root, Scene& s) {
  const auto tables = tables_of(root, contacts_keys());
  for (std::size_t i = 0; i < tables.size(); ++i) {
    const KeyReader c(tables[i], contacts_keys()), k(tables[i], rigid_cell::facet_law_keys());
    c.choice("model", std::vector<std::string>{"facet_damage"});
    FacetLawSpec f;
    f.where = s.file + ": contacts[" + std::to_string(i) + "]";
    f.phase_a = phase_index(c, "phase_a", s.phases);
    f.phase_b = c.has("phase_b") ? phase_index(c, "phase_b", s.phases) : f.phase_a;
    // Květoň (3.6)-(3.8): the facet's E₀ and α, or the macroscopic E and ν they follow from.
    if (k.has("E0") == k.has("modulus"))
      k.fail(k.has("E0") ? "modulus" : "E0",
             "give the facets' normal modulus E0 with alpha, or the macroscopic modulus with poisson_ratio "
             "(Květoň (3.8)), one pair");
    if (k.has("E0")) {
      f.E0 = k.number("E0");
      f.alpha = k.number("alpha");
    } else {
      f.modulus = k.number("modulus");
      f.poisson_ratio = k.number("poisson_ratio");
    }
    f.tensile_strength = k.number("tensile_strength");
    if (f.tensile_strength > 0) f.fracture_energy = k.number("fracture_energy");
    // Květoň (8.16)-(8.17): F = 1 + c₁ asinh(ė/c₀) on the elastic limit, c₀ a strain rate (Tab. 8.1).
    if (k.has("rate_c1") || k.has("rate_c0")) {
      if (!(f.tensile_strength > 0))
        k.fail(k.has("rate_c1") ? "rate_c1" : "rate_c0",
               "a rate dependence scales the elastic limit of a facet that "
               "damages: give tensile_strength and fracture_energy");
      f.rate_c1 = k.number("rate_c1");
      f.rate_c0 = k.number("rate_c0");
    }
    for (const auto& o : s.rigid_cell->facets)
      if ((o.phase_a == f.phase_a && o.phase_b == f.phase_b) || (o.phase_a == f.phase_b && o.phase_b == f.phase_a))
        c.fail("phase_b", "a facet law for this pair of phases is already given");
    s.rigid_cell->facets.push_back(f);
    tables[i].finish();
  }
  if (tables.empty())
    throw InputError(s.file +
                     ": missing [[contacts]]: the facet law between phases (model = \"facet_damage\", "
                     "phase_a, phase_b, E0 and alpha or modulus and poisson_ratio, tensile_strength, "
                     "fracture_energy)");
}

// The shape's outline: a box from the origin, a disc (3D: a cylinder along z) or a counter-clockwise polygon
// (3D: a prism along z).
void read_cell_specimen(const Table& root, Scene& s) {
  const Table t = table_of(root, cell_specimen_keys());
  const KeyReader k(t, cell_specimen_keys());
  k.choice("kind");
  CellSpecimenSpec& c = s.rigid_cell->specimen;
  const int d = s.dimension;
  const std::string shape = k.choice("shape");
  if (shape == "box") {
    c.shape = CellSpecimenSpec::Shape::Box;
    c.size = k.numbers("size", d);
  } else if (shape == "disc") {
    c.shape = CellSpecimenSpec::Shape::Disc;
    c.centre = vec(k, "centre", 2);
    c.radius = k.number("radius");
  } else {
    c.shape = CellSpecimenSpec::Shape::Polygon;
    const auto x = k.numbers("vertices_x", 0);
    const auto y = k.numbers("vertices_y", x.size());
    if (x.size() < 3) k.fail("vertices_x", "a polygon needs at least 3 vertices");
    refuse_repeated_or_crossing(k, x, y);
    double twice_area = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      const std::size_t j = (i + 1) % x.size();
      twice_area += x[i] * y[j] - x[j] * y[i];
      c.vertices.push_back({x[i], y[i]});
    }
    if (!(twice_area > 0)) k.fail("vertices_y", "the vertices must go round the polygon counter-clockwise");
  }
  if (d == 3 && shape != "box") c.thickness = k.number("thickness");
  c.l_min = k.number("l_min");
  c.max_rejections = static_cast<int>(k.integer("max_rejections"));
  read_coarsening(k, c, d);
  if (k.has("nodes")) {
    c.nodes = k.numbers("nodes", 0);
    if (c.nodes.size() < 2 * static_cast<std::size_t>(d) || c.nodes.size() % d != 0)
      k.fail("nodes", "gives " + std::to_string(c.nodes.size()) + " numbers: " + std::to_string(d) +
                          " per node, at least two nodes");
  } else {
    check_cells_affordable(k, c, d);
  }
  t.finish();
}

// Květoň §3.4 (3.21): the random field of [rigid_cell.random_field], on a grid over the specimen's box (so read
// after the specimen). Each axis's correlation matrix is decomposed densely, in O(n³): at most this many nodes.
constexpr double kMaxFieldNodesPerAxis = 1000;

void read_random_field(const Table& t, Scene& s) {
  const KeyReader k(t, random_field_keys());
  RandomFieldSpec f;
  f.correlation_length = k.number("correlation_length");
  f.std = k.number("std");
  const double lc = f.correlation_length;
  f.grid_spacing = k.number("grid_spacing", lc / 3);
  if (f.grid_spacing > lc / 2) {
    std::ostringstream m;
    m << "at most correlation_length/2 = " << lc / 2
      << " m: a coarser grid misses the field's variance between its nodes (EOLE)";
    k.fail("grid_spacing", m.str());
  }
  const std::vector<double> extent = specimen_extent(s.rigid_cell->specimen, s.dimension);
  for (std::size_t i = 0; i < extent.size(); ++i) {
    const double nodes = std::ceil(extent[i] / f.grid_spacing) + 1;
    if (nodes <= kMaxFieldNodesPerAxis) continue;
    std::ostringstream m;
    m << "gives " << nodes << " nodes along "
      << "xyz"[i] << " over the specimen's " << extent[i] << " m; at most " << kMaxFieldNodesPerAxis
      << " are allowed (each axis's correlation matrix is decomposed densely): a larger grid_spacing (default "
         "correlation_length/3) or a longer correlation_length";
    k.fail("grid_spacing", m.str());
  }
  f.variance_kept = k.number("variance_kept");
  f.weibull_modulus = k.number("weibull_modulus");
  f.grafting_probability = k.number("grafting_probability");
  f.seed_offset = static_cast<std::uint64_t>(k.integer("seed_offset"));
  t.finish();
  s.rigid_cell->random_field = f;
}

// Plates are [[groups]] by box; their held degrees of freedom follow velocity / angular_velocity through (9.1).
void check_plates(const Table& root, const Scene& s) {
  const auto tables = tables_of(root, groups_keys());
  for (std::size_t g = 0; g < s.groups.size(); ++g) {
    const GroupSpec& p = s.groups[g];
    const KeyReader k(tables[g], groups_keys());
    for (const char* key : {"tags", "ids"})
      if (k.has(key))
        k.fail(key,
               "a rigid-cell plate takes the cells whose nodes lie in its box (box_lo, box_hi) and holds or "
               "drives them (fix, velocity, angular_velocity, ramp_time) or loads them (force, moment); it has no '" +
                   std::string(key) + "'");
    // A load acts on the plate's free degrees of freedom: on a held one the support would take it.
    const int r = s.dimension == 2 ? 1 : 3;
    const std::vector<std::string> dofs = s.dimension == 2 ? std::vector<std::string>{"x", "y", "rz"}
                                                           : std::vector<std::string>{"x", "y", "z", "rx", "ry", "rz"};
    for (int i = 0; i < s.dimension + r; ++i) {
      const bool rotation = i >= s.dimension;
      const auto& load = rotation ? p.moment : p.force;
      if (!load.empty() && load[rotation ? i - s.dimension : i] != 0 && (p.fix & (1u << i)))
        k.fail(rotation ? "moment" : "force",
               "loads the plate along " + dofs[i] + ", which it holds (fix): a load acts on a free degree of freedom");
    }
    if (p.box_lo.empty()) k.fail("box_lo", "a rigid-cell plate takes the cells whose nodes lie in its box");
    check_driven_axes(k, p, s.dimension);  // a plate moves along its velocity on held axes only
    for (int i = 0; i < r && !p.angular_velocity.empty(); ++i)
      if (p.angular_velocity[i] != 0 && !(p.fix & (1u << (s.dimension + i))))
        k.fail("fix", "the plate turns at its angular velocity about a held axis only: add its rotation to 'fix'");
    for (std::size_t o = 0; o < g; ++o)
      if (s.groups[o].name == p.name) k.fail("name", "plate names must be unique");
  }
}

// [[probes]]: opening gauges between two plates (the CMOD of a notched specimen); the other kinds read particles.
void read_cell_probes(const Table& root, Scene& s) {
  for (const Table& t : tables_of(root, probes_keys())) {
    const KeyReader k(t, probes_keys());
    ProbeSpec p;
    p.name = k.string("name");
    k.choice("kind", std::vector<std::string>{"opening"});
    p.kind = ProbeSpec::Kind::Opening;
    if (k.has("particles"))
      k.fail("particles", "a rigid-cell opening probe is read between two plates: 'groups' = \"first second\"");
    for (const auto& o : s.probes)
      if (o.name == p.name) k.fail("name", "probe names must be unique");
    read_opening(k, s, p);
    s.probes.push_back(p);
    t.finish();
  }
}

// [rigid_cell.opening_control]: which plate travels, along which direction, to open which probe at what rate.
void read_opening_control(const Table& t, Scene& s) {
  const KeyReader k(t, opening_control_keys());
  OpeningControlSpec c;
  const std::string probe = k.string("probe");
  c.probe = -1;
  std::string declared;
  for (std::size_t i = 0; i < s.probes.size(); ++i) {
    if (s.probes[i].name == probe) c.probe = static_cast<int>(i);
    declared += (declared.empty() ? "" : ", ") + s.probes[i].name;
  }
  if (c.probe < 0)
    k.fail("probe", "'" + probe +
                        "' is not the name of an opening probe ([[probes]] with kind = \"opening\"); "
                        "declared: " +
                        (declared.empty() ? "none" : declared));
  const std::string plate = k.string("plate");
  c.plate = -1;
  for (std::size_t g = 0; g < s.groups.size(); ++g)
    if (s.groups[g].name == plate) c.plate = static_cast<int>(g);
  if (c.plate < 0) k.fail("plate", "'" + plate + "' is not the name of a plate ([[groups]])");
  c.direction = vec(k, "direction", s.dimension);
  double n2 = 0;
  for (double x : c.direction) n2 += x * x;
  if (n2 == 0) k.fail("direction", "the direction the plate travels must not be the zero vector");
  const GroupSpec& g = s.groups[c.plate];
  for (int i = 0; i < s.dimension; ++i) {
    if (c.direction[i] == 0) continue;
    const std::string axis(1, "xyz"[i]);
    if (!(g.fix & (1u << i)))
      k.fail("direction", "plate '" + plate + "' travels along " + axis + ": add " + axis + " to its 'fix'");
    if (!g.velocity.empty() && g.velocity[i] != 0)
      k.fail("plate", "plate '" + plate + "' has a velocity along " + axis +
                          ", which the opening control sets: leave it out of the plate's 'velocity'");
  }
  c.rate = k.number("rate");
  c.ramp_time = k.number("ramp_time");
  t.finish();
  s.rigid_cell->opening_control = c;
}

// [rigid_cell.dynamics]: the scheme, Newmark's parameters within (8.5), and Rayleigh damping.
void read_dynamics(const Table& t, Scene& s) {
  const KeyReader k(t, cell_dynamics_keys());
  CellDynamicsSpec d;
  d.central_difference = k.choice("scheme") == "central_difference";
  if (d.central_difference)
    for (const char* key : {"beta", "gamma"})
      if (k.has(key)) k.fail(key, "is a parameter of Newmark's scheme; the central-difference scheme has none");
  d.beta = k.number("beta");
  d.gamma = k.number("gamma");
  if (!(2 * d.beta >= d.gamma)) {
    std::ostringstream m;
    m << "Newmark's scheme is unconditionally stable for 2 beta >= gamma >= 0.5 (Kveton (8.5)); gamma is " << d.gamma
      << ", so beta must be at least " << d.gamma / 2;
    k.fail("beta", m.str());
  }
  d.mass_damping = k.number("mass_damping");
  d.stiffness_damping = k.number("stiffness_damping");
  t.finish();
  s.rigid_cell->dynamics = d;
}

// [rigid_cell.stress_wave]: Květoň (9.5), a cosine pulse of pressure on a face of the specimen, in dynamics only.
void read_stress_wave(const Table& t, Scene& s) {
  const KeyReader k(t, stress_wave_keys());
  StressWaveSpec w;
  if (!s.rigid_cell->dynamics)
    k.fail("pressure", "a stress wave loads the specimen in time: it needs [rigid_cell.dynamics]");
  w.box_lo = vec(k, "box_lo", s.dimension);
  w.box_hi = vec(k, "box_hi", s.dimension);
  check_box(k, "box_lo", w.box_lo, "box_hi", w.box_hi);
  if (k.has("times") || k.has("pressures")) {
    if (k.has("pressure") || k.has("duration"))
      k.fail("times", "give the cosine pulse (pressure, duration) or the piecewise-linear wave (times, pressures)");
    w.times = k.numbers("times", 0);
    w.pressures = k.numbers("pressures", 0);
    if (w.times.size() < 2 || w.times.size() != w.pressures.size())
      k.fail("pressures", "needs one pressure per time, and at least two points");
    if (w.times.front() != 0) k.fail("times", "the wave starts at time 0");
    for (std::size_t i = 1; i < w.times.size(); ++i)
      if (!(w.times[i] > w.times[i - 1])) k.fail("times", "must increase");
    if (w.pressures.front() != 0 || w.pressures.back() != 0)
      k.fail("pressures", "the wave rises from 0 and returns to 0 (a jump would be a shock the steps cannot resolve)");
    if (std::all_of(w.pressures.begin(), w.pressures.end(), [](double p) { return p == 0; }))
      k.fail("pressures", "a stress wave of no pressure loads nothing");
  } else {
    w.pressure = k.number("pressure");
    if (w.pressure == 0) k.fail("pressure", "a stress wave of no pressure loads nothing");
    w.duration = k.number("duration");
  }
  t.finish();
  s.rigid_cell->stress_wave = w;
}

// [rigid_cell.sections]: planes normal to one axis at the given positions, each with a history of the mean normal
// stress across it.
void read_sections(const Table& t, Scene& s) {
  const KeyReader k(t, sections_keys());
  const std::vector<std::string> axes =
      s.dimension == 2 ? std::vector<std::string>{"x", "y"} : std::vector<std::string>{"x", "y", "z"};
  const std::string axis = k.choice("axis", axes);
  const int a = static_cast<int>(std::find(axes.begin(), axes.end(), axis) - axes.begin());
  const std::vector<double> at = k.numbers("at", 0);
  if (at.empty()) k.fail("at", "give at least one position of a section plane");
  for (double x : at) s.rigid_cell->sections.push_back({a, x});
  t.finish();
}

// [rigid_cell.strain]: the box of the strain histories (the cells in it are counted when the cells exist).
void read_strain_box(const Table& t, Scene& s) {
  const KeyReader k(t, strain_box_keys());
  StrainBoxSpec b;
  b.box_lo = vec(k, "box_lo", s.dimension);
  b.box_hi = vec(k, "box_hi", s.dimension);
  check_box(k, "box_lo", b.box_lo, "box_hi", b.box_hi);
  s.rigid_cell->strain = b;
  t.finish();
}

// The load step, or the time step of dynamics: given ('fixed'); under central differences it may instead be the
// fraction 'safety' of the critical step (0.8 unless given), as in the explicit engine.
void read_load_step(const Table& root, Scene& s) {
  const Table t = table_of(root, timestep_keys());
  const KeyReader k(t, timestep_keys());
  const bool explicit_scheme = s.rigid_cell->dynamics && s.rigid_cell->dynamics->central_difference;
  if (!explicit_scheme && k.has("safety"))
    k.fail("safety", "a fraction of the critical step belongs to explicit dynamics (scheme = \"central_difference\")");
  if (explicit_scheme && k.has("fixed") && k.has("safety")) k.fail("safety", "give either 'fixed' or 'safety', not both");
  if (explicit_scheme && !k.has("fixed")) {
    s.timestep.fixed = 0;
    s.timestep.safety = k.number("safety");
  } else {
    s.timestep.fixed = k.required_number("fixed");
  }
  t.finish();
}

}  // namespace

void read_rigid_cell(const Table& root, Scene& s) {
  // Fibres bridge the cracks between rigid cells: a scene of particles that declares them is told so first.
  if (table_of(root, rigid_cell_keys()).has(std::string(fibres_keys().key())) && root.has("specimen")) {
    const std::string kind = KeyReader(table_of(root, cell_specimen_keys()), cell_specimen_keys()).string("kind");
    if (kind != "voronoi_cells")
      KeyReader(table_of(root, rigid_cell_keys()), rigid_cell_keys())
          .fail(fibres_keys(), "fibres bridge cracks between rigid cells: a fibre family needs a rigid-cell specimen "
                               "([specimen] kind = \"voronoi_cells\"), not kind = \"" + kind + "\"");
  }
  for (const KeyTable* sub : {&walls_keys(), &bonds_keys(), &physics_keys(), &measure_keys(), &wall_strains_keys()})
    if (root.has(std::string(sub->key())))
      KeyReader(root, scene_keys())
          .fail(*sub,
                "a rigid-cell scene ([rigid_cell]) is held and loaded by plates ([[groups]] by box); it has "
                "no walls, bonds, physics or measurement regions");
  const Table t = table_of(root, rigid_cell_keys());
  RigidCellSpec& r = s.rigid_cell.emplace();
  read_bound_keys(t, rigid_cell_keys(), &r);
  const std::optional<Table> field = optional_table_of(t, random_field_keys());
  const std::optional<Table> control = optional_table_of(t, opening_control_keys());
  const std::optional<Table> dynamics = optional_table_of(t, cell_dynamics_keys());
  const std::optional<Table> wave = optional_table_of(t, stress_wave_keys());
  const std::optional<Table> sections = optional_table_of(t, sections_keys());
  const std::optional<Table> strain = optional_table_of(t, strain_box_keys());
  const std::vector<Table> fibres = tables_of(t, fibres_keys());
  t.finish();
  read_facet_laws(root, s);
  read_cell_specimen(root, s);
  {
    const std::vector<double> extent = specimen_extent(s.rigid_cell->specimen, s.dimension);
    read_fibres(fibres, *std::max_element(extent.begin(), extent.end()), s);
  }
  if (field) read_random_field(*field, s);
  if (dynamics) read_dynamics(*dynamics, s);
  if (wave) read_stress_wave(*wave, s);
  if (sections) read_sections(*sections, s);
  if (strain) read_strain_box(*strain, s);
  read_mesostructure(root, s);
  read_groups(root, s);
  check_plates(root, s);
  read_cell_probes(root, s);
  if (control) read_opening_control(*control, s);
  read_load_step(root, s);
}

}  // namespace scene_read

}  // namespace mc
