// [[measure]], [[wall_strains]] and [[probes]]: what the scene observes.
#include <sstream>

#include "scene/scene_read_parts.hpp"

namespace mc {

const KeyTable& measure_keys() {
  static const KeyTable t{
      .name = "measure",
      .title = "[[measure]]",
      .about = "A measurement circle (2D) or sphere (3D): histories measure.<name>.stress_xx … of what it measures.",
      .keys = {
          {.name = "name", .type = KeyType::Text, .need = Need::Required, .doc = "unique name"},
          {.name = "centre", .type = KeyType::Reals, .unit = Unit::Length, .need = Need::Required, .doc = "its centre"},
          {.name = "radius", .unit = Unit::Length, .range = Range::positive(), .need = Need::Required,
           .doc = "its radius"},
          {.name = "stress", .type = KeyType::Flag,
           .doc = "the average stress, Tang (3.63), with the porosity correction; tension positive",
           .fallback = 1},
          {.name = "strain", .type = KeyType::Flag, .doc = "the best-fit strain rate (3.64-3.73), integrated every step", .fallback = 0},
          {.name = "porosity", .type = KeyType::Flag, .doc = "the porosity", .fallback = 0},
          {.name = "coordination", .type = KeyType::Flag, .doc = "the coordination number", .fallback = 0},
      }};
  return t;
}

const KeyTable& wall_strains_keys() {
  static const KeyTable t{
      .name = "wall_strains",
      .title = "[[wall_strains]]",
      .about = "The strain (L − L0)/L0 between two opposite walls, L their distance along the first wall's normal "
               "(tension positive; the second wall stands in front of the first). History strain.<name>.",
      .keys = {
          {.name = "name", .type = KeyType::Text, .need = Need::Required, .doc = "unique name"},
          {.name = "walls", .type = KeyType::Text, .need = Need::Required, .doc = "\"bottom top\": the names of two opposite walls"},
      }};
  return t;
}

const KeyTable& probes_keys() {
  static const KeyTable t{
      .name = "probes",
      .title = "[[probes]]",
      .about = "A history read off one or two particles, or an opening between two sides (a clip gauge, e.g. the "
               "CMOD) whose start is kept in checkpoints. Histories by the probe's name.",
      .keys = {
          {.name = "name", .type = KeyType::Text, .need = Need::Required, .doc = "unique name"},
          {.name = "kind", .type = KeyType::Word,
           .need = Need::Required,
           .doc = "overlap, gap, relative_speed (two particles; along the line of centres, positive when "
                  "separating); position, velocity, angular_velocity (one particle); opening (the mean displacement "
                  "of the second side minus the first's along direction, positive when they part)",
           .words = {"overlap", "gap", "relative_speed", "position", "velocity", "angular_velocity", "opening"}},
          {.name = "particles", .type = KeyType::Reals, .range = scene_read::kIds, .doc = "[ids]: the particle, or the two particles (distinct)"},
          {.name = "component", .type = KeyType::Word,
           .doc = "x, y or z of a vector (relative_speed: instead of the normal component); absent: the magnitude",
           .words = {"x", "y", "z"}},
          {.name = "groups", .type = KeyType::Text, .when = "kind = opening",
           .doc = "\"first second\": the two [[groups]] that are the sides, instead of particles"},
          {.name = "direction", .type = KeyType::Reals, .when = "kind = opening", .doc = "the direction the opening is measured along",
           .shown_default = "from the first side to the second at the start"},
      }};
  return t;
}

namespace scene_read {

// An opening probe (a clip gauge, e.g. the CMOD): its sides are two particles (`particles` = [a, b]) or two
// groups (`groups` = "left right"), its reading their relative displacement along `direction` (default: the
// line from the first side to the second at the start).
void read_opening(const KeyReader& k, const Scene& s, ProbeSpec& p) {
  if (k.has("particles") == k.has("groups"))
    k.fail("particles",
           "an opening probe takes its two sides from either 'particles' = [a, b] or 'groups' = "
           "\"first second\", one of them");
  if (k.has("particles")) {
    p.particles = ids(k, "particles", 2);
    if (p.particles[0] == p.particles[1])
      k.fail("particles", "names particle " + std::to_string(p.particles[0]) + " twice: an opening needs two sides");
  } else {
    std::stringstream ss(k.string("groups"));
    std::vector<std::string> names;
    for (std::string n; ss >> n;) names.push_back(n);
    if (names.size() != 2) k.fail("groups", "give the names of two [[groups]], separated by a space");
    if (names[0] == names[1]) k.fail("groups", "names group '" + names[0] + "' twice: an opening needs two sides");
    for (int i = 0; i < 2; ++i) {
      for (std::size_t g = 0; g < s.groups.size(); ++g)
        if (s.groups[g].name == names[i]) p.groups[i] = static_cast<int>(g);
      if (p.groups[i] < 0) k.fail("groups", "'" + names[i] + "' is not the name of a [[groups]] entry");
    }
  }
  p.direction = opt_vec(k, "direction", s.dimension);
  double n2 = 0;
  for (double c : p.direction) n2 += c * c;
  if (!p.direction.empty() && n2 == 0) k.fail("direction", "the direction must not be the zero vector");
}

void check_opening_walls(const Table& root, const Scene& s) {
  const auto tabs = tables_of(root, walls_keys());
  for (std::size_t i = 0; i < s.walls.size(); ++i)
    if (s.walls[i].control == WallControl::Opening && s.opening_gauge(s.walls[i].probe) < 0) {
      std::string list;
      for (const auto& p : s.probes)
        if (p.kind == ProbeSpec::Kind::Opening) list += (list.empty() ? "" : ", ") + p.name;
      KeyReader(tabs[i], walls_keys())
          .fail("probe", "'" + s.walls[i].probe +
                             "' is not the name of an opening probe ([[probes]] with kind = "
                             "\"opening\"); declared: " +
                             (list.empty() ? "none" : list));
    }
}

void read_observers(const Table& root, Scene& s) {
  const int d = s.dimension;
  for (const Table& t : tables_of(root, measure_keys())) {
    const KeyReader k(t, measure_keys());
    RegionSpec r;
    r.name = k.string("name");
    r.centre = vec(k, "centre", d);
    r.radius = k.number("radius");
    r.stress = k.boolean("stress");
    r.strain = k.boolean("strain");
    r.porosity = k.boolean("porosity");
    r.coordination = k.boolean("coordination");
    s.regions.push_back(r);
    t.finish();
  }
  for (const Table& t : tables_of(root, wall_strains_keys())) {
    const KeyReader k(t, wall_strains_keys());
    WallStrainSpec g;
    g.name = k.string("name");
    // walls = "bottom top": two opposite walls.
    std::stringstream ss(k.string("walls"));
    std::vector<std::string> names;
    std::string n;
    while (ss >> n) names.push_back(n);
    if (names.size() != 2) k.fail("walls", "give the names of two opposite walls, separated by a space");
    for (int i = 0; i < 2; ++i) {
      g.walls[i] = -1;
      for (std::size_t w = 0; w < s.walls.size(); ++w)
        if (s.walls[w].name == names[i]) g.walls[i] = static_cast<int>(w);
      if (g.walls[i] < 0) k.fail("walls", "'" + names[i] + "' is not the name of a wall");
    }
    if (g.walls[0] == g.walls[1]) k.fail("walls", "names '" + names[0] + "' twice: give two different walls");
    s.wall_strains.push_back(g);
    t.finish();
  }
  for (const Table& t : tables_of(root, probes_keys())) {
    const KeyReader k(t, probes_keys());
    ProbeSpec p;
    p.name = k.string("name");
    const std::string kind = k.choice("kind");
    using K = ProbeSpec::Kind;
    p.kind = kind == "overlap"          ? K::Overlap
             : kind == "gap"            ? K::Gap
             : kind == "relative_speed" ? K::RelativeSpeed
             : kind == "position"       ? K::Position
             : kind == "velocity"       ? K::Velocity
             : kind == "opening"        ? K::Opening
                                        : K::AngularVelocity;
    for (const auto& o : s.probes)
      if (o.name == p.name) k.fail("name", "probe names must be unique");
    if (p.kind == K::Opening) {
      read_opening(k, s, p);
      s.probes.push_back(p);
      t.finish();
      continue;
    }
    const bool two = p.kind == K::Overlap || p.kind == K::Gap || p.kind == K::RelativeSpeed;
    p.particles = ids(k, "particles", two ? 2 : 1);
    if (two && p.particles[0] == p.particles[1])
      k.fail("particles", "names particle " + std::to_string(p.particles[0]) + " twice: a " + kind +
                              " probe needs two different particles");
    if (k.has("component")) {
      const std::string c = k.choice("component");
      p.component = c == "x" ? 0 : c == "y" ? 1 : 2;
      if (p.kind != K::AngularVelocity && p.component >= d) k.fail("component", "a 2D scene has only x and y");
    }
    s.probes.push_back(p);
    t.finish();
  }
}

}  // namespace scene_read

}  // namespace mc
