// The keys of a rigid-cell scene (a scene with a [rigid_cell] table): the solver's options, the facet laws of
// [[contacts]], the cell specimen, the random field of its strength ([rigid_cell.random_field]), the plates
// ([[groups]] by box) and the load step (timestep.fixed).
#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "scene/scene_read_parts.hpp"

namespace mc::scene_read {

namespace {

void read_facet_laws(const Table& root, Scene& s) {
  const auto tables = root.tables("contacts");
  for (std::size_t i = 0; i < tables.size(); ++i) {
    const Table& t = tables[i];
    t.choice("model", {"facet_damage"});
    FacetLawSpec f;
    f.where = s.file + ": contacts[" + std::to_string(i) + "]";
    f.phase_a = phase_index(t, "phase_a", s.phases);
    f.phase_b = t.has("phase_b") ? phase_index(t, "phase_b", s.phases) : f.phase_a;
    // Květoň (3.6)-(3.8): the facet's E₀ and α, or the macroscopic E and ν they follow from.
    if (t.has("E0") == t.has("modulus"))
      t.fail(t.has("E0") ? "modulus" : "E0",
             "give the facets' normal modulus E0 with alpha, or the macroscopic modulus with poisson_ratio "
             "(Květoň (3.8)), one pair");
    if (t.has("E0")) {
      f.E0 = t.number("E0", Unit::Pressure, Range::positive());
      f.alpha = t.number("alpha", Unit::None, Range::positive());
    } else {
      f.E = t.number("modulus", Unit::Pressure, Range::positive());
      f.nu = t.number("poisson_ratio", Unit::None, Range{-1.0, 0.5, true, true});
    }
    f.tensile_strength = t.number("tensile_strength", Unit::Pressure, Range::non_negative(), 0.0);
    if (f.tensile_strength > 0) f.fracture_energy = t.number("fracture_energy", Unit::EnergyPerArea, Range::positive());
    // Květoň (8.16)-(8.17): F = 1 + c₁ asinh(ė/c₀) on the elastic limit, c₀ a strain rate (Tab. 8.1).
    if (t.has("rate_c1") || t.has("rate_c0")) {
      if (!(f.tensile_strength > 0))
        t.fail(t.has("rate_c1") ? "rate_c1" : "rate_c0",
               "a rate dependence scales the elastic limit of a facet that "
               "damages: give tensile_strength and fracture_energy");
      f.rate_c1 = t.number("rate_c1", Unit::None, Range::positive());
      f.rate_c0 = t.number("rate_c0", Unit::Rate, Range::positive());
    }
    for (const auto& o : s.rigid_cell->facets)
      if ((o.phase_a == f.phase_a && o.phase_b == f.phase_b) || (o.phase_a == f.phase_b && o.phase_b == f.phase_a))
        t.fail("phase_b", "a facet law for this pair of phases is already given");
    s.rigid_cell->facets.push_back(f);
    t.finish();
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
  const Table t = root.table("specimen");
  t.choice("kind", {"voronoi_cells"});
  CellSpecimenSpec& c = s.rigid_cell->specimen;
  const int d = s.dimension;
  const std::string shape = t.choice("shape", {"box", "disc", "polygon"});
  if (shape == "box") {
    c.shape = CellSpecimenSpec::Shape::Box;
    c.size = t.numbers("size", Unit::Length, Range::positive(), d);
  } else if (shape == "disc") {
    c.shape = CellSpecimenSpec::Shape::Disc;
    c.centre = vec(t, "centre", Unit::Length, 2);
    c.radius = t.number("radius", Unit::Length, Range::positive());
  } else {
    c.shape = CellSpecimenSpec::Shape::Polygon;
    const auto x = t.numbers("vertices_x", Unit::Length, Range::any(), 0);
    const auto y = t.numbers("vertices_y", Unit::Length, Range::any(), x.size());
    if (x.size() < 3) t.fail("vertices_x", "a polygon needs at least 3 vertices");
    double twice_area = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      const std::size_t j = (i + 1) % x.size();
      twice_area += x[i] * y[j] - x[j] * y[i];
      c.vertices.push_back({x[i], y[i]});
    }
    if (!(twice_area > 0)) t.fail("vertices_y", "the vertices must go round the polygon counter-clockwise");
  }
  if (d == 3 && shape != "box") c.thickness = t.number("thickness", Unit::Length, Range::positive());
  c.l_min = t.number("l_min", Unit::Length, Range::positive());
  c.max_rejections = static_cast<int>(t.integer("max_rejections", Range::closed(10, 1e8), 2000));
  t.finish();
}

// The specimen's bounding box, its extent along each axis: what the random field's grid spans.
std::vector<double> specimen_extent(const CellSpecimenSpec& c, int d) {
  using S = CellSpecimenSpec::Shape;
  if (c.shape == S::Box) return c.size;
  std::vector<double> e{2 * c.radius, 2 * c.radius};
  if (c.shape == S::Polygon)
    for (int k = 0; k < 2; ++k) {
      const auto [lo, hi] = std::minmax_element(c.vertices.begin(), c.vertices.end(),
                                                [k](const auto& a, const auto& b) { return a[k] < b[k]; });
      e[k] = (*hi)[k] - (*lo)[k];
    }
  if (d == 3) e.push_back(c.thickness);
  return e;
}

// Květoň §3.4 (3.21): the random field of [rigid_cell.random_field], on a grid over the specimen's box (so read
// after the specimen). Each axis's correlation matrix is decomposed densely, in O(n³): at most this many nodes.
constexpr double kMaxFieldNodesPerAxis = 1000;

void read_random_field(const Table& t, Scene& s) {
  RandomFieldSpec f;
  f.correlation_length = t.number("correlation_length", Unit::Length, Range::positive());
  f.std = t.number("std", Unit::None, Range{0.0, 0.5, true, false});
  const double lc = f.correlation_length;
  f.grid_spacing = t.number("grid_spacing", Unit::Length, Range::positive(), lc / 3);
  if (f.grid_spacing > lc / 2) {
    std::ostringstream m;
    m << "at most correlation_length/2 = " << lc / 2
      << " m: a coarser grid misses the field's variance between its nodes (EOLE)";
    t.fail("grid_spacing", m.str());
  }
  const std::vector<double> extent = specimen_extent(s.rigid_cell->specimen, s.dimension);
  for (std::size_t k = 0; k < extent.size(); ++k) {
    const double nodes = std::ceil(extent[k] / f.grid_spacing) + 1;
    if (nodes <= kMaxFieldNodesPerAxis) continue;
    std::ostringstream m;
    m << "gives " << nodes << " nodes along "
      << "xyz"[k] << " over the specimen's " << extent[k] << " m; at most " << kMaxFieldNodesPerAxis
      << " are allowed (each axis's correlation matrix is decomposed densely): a larger grid_spacing (default "
         "correlation_length/3) or a longer correlation_length";
    t.fail("grid_spacing", m.str());
  }
  f.variance_kept = t.number("variance_kept", Unit::None, Range{0.0, 0.9999, true, false}, f.variance_kept);
  f.weibull_modulus = t.number("weibull_modulus", Unit::None, Range::closed(1, 100), f.weibull_modulus);
  f.grafting_probability =
      t.number("grafting_probability", Unit::None, Range{0.0, 0.1, true, false}, f.grafting_probability);
  f.seed_offset = static_cast<std::uint64_t>(t.integer("seed_offset", Range::closed(0, 9.0e18), 0));
  t.finish();
  s.rigid_cell->random_field = f;
}

// Plates are [[groups]] by box; their held degrees of freedom follow velocity / angular_velocity through (9.1).
void check_plates(const Table& root, const Scene& s) {
  const auto tables = root.tables("groups");
  for (std::size_t g = 0; g < s.groups.size(); ++g) {
    const GroupSpec& p = s.groups[g];
    const Table& t = tables[g];
    for (const char* key : {"tags", "ids"})
      if (t.has(key))
        t.fail(key,
               "a rigid-cell plate takes the cells whose nodes lie in its box (box_lo, box_hi) and holds or "
               "drives them (fix, velocity, angular_velocity, ramp_time) or loads them (force, moment); it has no '" +
                   std::string(key) + "'");
    // A load acts on the plate's free degrees of freedom: on a held one the support would take it.
    const int r = s.dimension == 2 ? 1 : 3;
    const std::vector<std::string> dofs = s.dimension == 2 ? std::vector<std::string>{"x", "y", "rz"}
                                                           : std::vector<std::string>{"x", "y", "z", "rx", "ry", "rz"};
    for (int k = 0; k < s.dimension + r; ++k) {
      const bool rotation = k >= s.dimension;
      const auto& load = rotation ? p.moment : p.force;
      if (!load.empty() && load[rotation ? k - s.dimension : k] != 0 && (p.fix & (1u << k)))
        t.fail(rotation ? "moment" : "force",
               "loads the plate along " + dofs[k] + ", which it holds (fix): a load acts on a free degree of freedom");
    }
    if (p.box_lo.empty()) t.fail("box_lo", "a rigid-cell plate takes the cells whose nodes lie in its box");
    check_driven_axes(t, p, s.dimension);  // a plate moves along its velocity on held axes only
    for (int k = 0; k < r && !p.angular_velocity.empty(); ++k)
      if (p.angular_velocity[k] != 0 && !(p.fix & (1u << (s.dimension + k))))
        t.fail("fix", "the plate turns at its angular velocity about a held axis only: add its rotation to 'fix'");
    for (std::size_t o = 0; o < g; ++o)
      if (s.groups[o].name == p.name) t.fail("name", "plate names must be unique");
  }
}

// [[probes]]: opening gauges between two plates (the CMOD of a notched specimen); the other kinds read particles.
void read_cell_probes(const Table& root, Scene& s) {
  for (const Table& t : root.tables("probes")) {
    ProbeSpec p;
    p.name = t.string("name");
    t.choice("kind", {"opening"});
    p.kind = ProbeSpec::Kind::Opening;
    if (t.has("particles"))
      t.fail("particles", "a rigid-cell opening probe is read between two plates: 'groups' = \"first second\"");
    for (const auto& o : s.probes)
      if (o.name == p.name) t.fail("name", "probe names must be unique");
    read_opening(t, s, p);
    s.probes.push_back(p);
    t.finish();
  }
}

// [rigid_cell.opening_control]: which plate travels, along which direction, to open which probe at what rate.
void read_opening_control(const Table& t, Scene& s) {
  OpeningControlSpec c;
  const std::string probe = t.string("probe");
  c.probe = -1;
  std::string declared;
  for (std::size_t i = 0; i < s.probes.size(); ++i) {
    if (s.probes[i].name == probe) c.probe = static_cast<int>(i);
    declared += (declared.empty() ? "" : ", ") + s.probes[i].name;
  }
  if (c.probe < 0)
    t.fail("probe", "'" + probe +
                        "' is not the name of an opening probe ([[probes]] with kind = \"opening\"); "
                        "declared: " +
                        (declared.empty() ? "none" : declared));
  const std::string plate = t.string("plate");
  c.plate = -1;
  for (std::size_t g = 0; g < s.groups.size(); ++g)
    if (s.groups[g].name == plate) c.plate = static_cast<int>(g);
  if (c.plate < 0) t.fail("plate", "'" + plate + "' is not the name of a plate ([[groups]])");
  c.direction = vec(t, "direction", Unit::None, s.dimension);
  double n2 = 0;
  for (double x : c.direction) n2 += x * x;
  if (n2 == 0) t.fail("direction", "the direction the plate travels must not be the zero vector");
  const GroupSpec& g = s.groups[c.plate];
  for (int k = 0; k < s.dimension; ++k) {
    if (c.direction[k] == 0) continue;
    const std::string axis(1, "xyz"[k]);
    if (!(g.fix & (1u << k)))
      t.fail("direction", "plate '" + plate + "' travels along " + axis + ": add " + axis + " to its 'fix'");
    if (!g.velocity.empty() && g.velocity[k] != 0)
      t.fail("plate", "plate '" + plate + "' has a velocity along " + axis +
                          ", which the opening control sets: leave it out of the plate's 'velocity'");
  }
  c.rate = t.number("rate", Unit::Velocity, Range::positive());
  c.ramp_time = t.number("ramp_time", Unit::Time, Range::non_negative(), 0.0);
  t.finish();
  s.rigid_cell->opening_control = c;
}

// [rigid_cell.dynamics]: the scheme, Newmark's parameters within (8.5), and Rayleigh damping.
void read_dynamics(const Table& t, Scene& s) {
  CellDynamicsSpec d;
  d.central_difference = t.choice("scheme", {"newmark", "central_difference"}, "newmark") == "central_difference";
  if (d.central_difference)
    for (const char* key : {"beta", "gamma"})
      if (t.has(key)) t.fail(key, "is a parameter of Newmark's scheme; the central-difference scheme has none");
  d.beta = t.number("beta", Unit::None, Range::positive(), d.beta);
  d.gamma = t.number("gamma", Unit::None, Range::at_least(0.5), d.gamma);
  if (!(2 * d.beta >= d.gamma)) {
    std::ostringstream m;
    m << "Newmark's scheme is unconditionally stable for 2 beta >= gamma >= 0.5 (Kveton (8.5)); gamma is " << d.gamma
      << ", so beta must be at least " << d.gamma / 2;
    t.fail("beta", m.str());
  }
  d.mass_damping = t.number("mass_damping", Unit::Rate, Range::non_negative(), 0.0);
  d.stiffness_damping = t.number("stiffness_damping", Unit::Time, Range::non_negative(), 0.0);
  t.finish();
  s.rigid_cell->dynamics = d;
}

// [rigid_cell.stress_wave]: Květoň (9.5), a cosine pulse of pressure on a face of the specimen, in dynamics only.
void read_stress_wave(const Table& t, Scene& s) {
  StressWaveSpec w;
  if (!s.rigid_cell->dynamics)
    t.fail("pressure", "a stress wave loads the specimen in time: it needs [rigid_cell.dynamics]");
  w.box_lo = vec(t, "box_lo", Unit::Length, s.dimension);
  w.box_hi = vec(t, "box_hi", Unit::Length, s.dimension);
  check_box(t, "box_lo", w.box_lo, "box_hi", w.box_hi);
  if (t.has("times") || t.has("pressures")) {
    if (t.has("pressure") || t.has("duration"))
      t.fail("times", "give the cosine pulse (pressure, duration) or the piecewise-linear wave (times, pressures)");
    w.times = t.numbers("times", Unit::Time, Range::non_negative(), 0);
    w.pressures = t.numbers("pressures", Unit::Pressure, Range::any(), 0);
    if (w.times.size() < 2 || w.times.size() != w.pressures.size())
      t.fail("pressures", "needs one pressure per time, and at least two points");
    if (w.times.front() != 0) t.fail("times", "the wave starts at time 0");
    for (std::size_t i = 1; i < w.times.size(); ++i)
      if (!(w.times[i] > w.times[i - 1])) t.fail("times", "must increase");
    if (w.pressures.front() != 0 || w.pressures.back() != 0)
      t.fail("pressures", "the wave rises from 0 and returns to 0 (a jump would be a shock the steps cannot resolve)");
    if (std::all_of(w.pressures.begin(), w.pressures.end(), [](double p) { return p == 0; }))
      t.fail("pressures", "a stress wave of no pressure loads nothing");
  } else {
    w.pressure = t.number("pressure", Unit::Pressure, Range::any());
    if (w.pressure == 0) t.fail("pressure", "a stress wave of no pressure loads nothing");
    w.duration = t.number("duration", Unit::Time, Range::positive());
  }
  t.finish();
  s.rigid_cell->stress_wave = w;
}

// The load step, or the time step of dynamics: given ('fixed'); under central differences it may instead be the
// fraction 'safety' of the critical step (0.8 unless given), as in the explicit engine.
// [rigid_cell.sections]: planes normal to one axis at the given positions, each with a history of the mean normal
// stress across it.
void read_sections(const Table& t, Scene& s) {
  const std::vector<std::string> axes =
      s.dimension == 2 ? std::vector<std::string>{"x", "y"} : std::vector<std::string>{"x", "y", "z"};
  const std::string axis = t.choice("axis", axes);
  const int k = static_cast<int>(std::find(axes.begin(), axes.end(), axis) - axes.begin());
  const std::vector<double> at = t.numbers("at", Unit::Length, Range::any(), 0);
  if (at.empty()) t.fail("at", "give at least one position of a section plane");
  for (double x : at) s.rigid_cell->sections.push_back({k, x});
  t.finish();
}

void read_load_step(const Table& root, Scene& s) {
  const Table t = root.table("timestep");
  const bool explicit_scheme = s.rigid_cell->dynamics && s.rigid_cell->dynamics->central_difference;
  if (!explicit_scheme && t.has("safety"))
    t.fail("safety", "a fraction of the critical step belongs to explicit dynamics (scheme = \"central_difference\")");
  if (explicit_scheme && t.has("fixed") && t.has("safety"))
    t.fail("safety", "give either 'fixed' or 'safety', not both");
  if (explicit_scheme && !t.has("fixed")) {
    s.timestep.fixed = 0;
    s.timestep.safety = t.number("safety", Unit::None, Range{0.0, 1.0, true, false}, 0.8);
  } else {
    s.timestep.fixed = t.number("fixed", Unit::Time, Range::positive());
  }
  t.finish();
}

}  // namespace

void read_rigid_cell(const Table& root, Scene& s) {
  for (const char* key : {"walls", "bonds", "physics", "measure", "wall_strains"})
    if (root.has(key))
      root.fail(key,
                "a rigid-cell scene ([rigid_cell]) is held and loaded by plates ([[groups]] by box); it has "
                "no walls, bonds, physics or measurement regions");
  const Table t = root.table("rigid_cell");
  RigidCellSpec& r = s.rigid_cell.emplace();
  r.damage_tolerance = t.number("damage_tolerance", Unit::None, Range{0.0, 1.0, true, false}, r.damage_tolerance);
  r.force_tolerance = t.number("force_tolerance", Unit::None, Range{0.0, 1.0, true, false}, r.force_tolerance);
  r.max_iterations = static_cast<int>(t.integer("max_iterations", Range::closed(1, 1e6), r.max_iterations));
  r.crack_log = t.boolean("crack_log", false);
  r.energy = t.boolean("energy", false);
  const std::optional<Table> field = t.optional_table("random_field");
  const std::optional<Table> control = t.optional_table("opening_control");
  const std::optional<Table> dynamics = t.optional_table("dynamics");
  const std::optional<Table> wave = t.optional_table("stress_wave");
  const std::optional<Table> sections = t.optional_table("sections");
  t.finish();
  read_facet_laws(root, s);
  read_cell_specimen(root, s);
  if (field) read_random_field(*field, s);
  if (dynamics) read_dynamics(*dynamics, s);
  if (wave) read_stress_wave(*wave, s);
  if (sections) read_sections(*sections, s);
  read_mesostructure(root, s);
  read_groups(root, s);
  check_plates(root, s);
  read_cell_probes(root, s);
  if (control) read_opening_control(*control, s);
  read_load_step(root, s);
}

}  // namespace mc::scene_read
