// [[measure]], [[wall_strains]] and [[probes]]: what the scene observes.
#include "scene/scene_read_parts.hpp"

#include <sstream>

namespace mc::scene_read {

// An opening probe (a clip gauge, e.g. the CMOD): its sides are two particles (`particles` = [a, b]) or two
// groups (`groups` = "left right"), its reading their relative displacement along `direction` (default: the
// line from the first side to the second at the start).
void read_opening(const Table& t, const Scene& s, ProbeSpec& p) {
  if (t.has("particles") == t.has("groups"))
    t.fail("particles",
           "an opening probe takes its two sides from either 'particles' = [a, b] or 'groups' = "
           "\"first second\", one of them");
  if (t.has("particles")) {
    p.particles = ids(t, "particles", 2);
    if (p.particles[0] == p.particles[1])
      t.fail("particles", "names particle " + std::to_string(p.particles[0]) + " twice: an opening needs two sides");
  } else {
    std::stringstream ss(t.string("groups"));
    std::vector<std::string> names;
    for (std::string n; ss >> n;) names.push_back(n);
    if (names.size() != 2) t.fail("groups", "give the names of two [[groups]], separated by a space");
    if (names[0] == names[1]) t.fail("groups", "names group '" + names[0] + "' twice: an opening needs two sides");
    for (int k = 0; k < 2; ++k) {
      for (std::size_t g = 0; g < s.groups.size(); ++g)
        if (s.groups[g].name == names[k]) p.groups[k] = static_cast<int>(g);
      if (p.groups[k] < 0) t.fail("groups", "'" + names[k] + "' is not the name of a [[groups]] entry");
    }
  }
  p.direction = opt_vec(t, "direction", Unit::None, s.dimension);
  double n2 = 0;
  for (double c : p.direction) n2 += c * c;
  if (!p.direction.empty() && n2 == 0) t.fail("direction", "the direction must not be the zero vector");
}

void check_opening_walls(const Table& root, const Scene& s) {
  const auto tabs = root.tables("walls");
  for (std::size_t i = 0; i < s.walls.size(); ++i)
    if (s.walls[i].control == WallControl::Opening && s.opening_gauge(s.walls[i].probe) < 0) {
      std::string list;
      for (const auto& p : s.probes)
        if (p.kind == ProbeSpec::Kind::Opening) list += (list.empty() ? "" : ", ") + p.name;
      tabs[i].fail("probe", "'" + s.walls[i].probe +
                                "' is not the name of an opening probe ([[probes]] with kind = "
                                "\"opening\"); declared: " +
                                (list.empty() ? "none" : list));
    }
}

void read_observers(const Table& root, Scene& s) {
  const int d = s.dimension;
  for (const Table& t : root.tables("measure")) {
    RegionSpec r;
    r.name = t.string("name");
    r.centre = vec(t, "centre", Unit::Length, d);
    r.radius = t.number("radius", Unit::Length, Range::positive());
    r.stress = t.boolean("stress", true);
    r.strain = t.boolean("strain", false);
    r.porosity = t.boolean("porosity", false);
    r.coordination = t.boolean("coordination", false);
    s.regions.push_back(r);
    t.finish();
  }
  for (const Table& t : root.tables("wall_strains")) {
    WallStrainSpec g;
    g.name = t.string("name");
    // walls = "bottom top": two opposite walls.
    std::stringstream ss(t.string("walls"));
    std::vector<std::string> names;
    std::string n;
    while (ss >> n) names.push_back(n);
    if (names.size() != 2) t.fail("walls", "give the names of two opposite walls, separated by a space");
    for (int k = 0; k < 2; ++k) {
      g.walls[k] = -1;
      for (std::size_t i = 0; i < s.walls.size(); ++i)
        if (s.walls[i].name == names[k]) g.walls[k] = static_cast<int>(i);
      if (g.walls[k] < 0) t.fail("walls", "'" + names[k] + "' is not the name of a wall");
    }
    if (g.walls[0] == g.walls[1]) t.fail("walls", "names '" + names[0] + "' twice: give two different walls");
    s.wall_strains.push_back(g);
    t.finish();
  }
  for (const Table& t : root.tables("probes")) {
    ProbeSpec p;
    p.name = t.string("name");
    const std::string k =
        t.choice("kind", {"overlap", "gap", "relative_speed", "position", "velocity", "angular_velocity", "opening"});
    using K = ProbeSpec::Kind;
    p.kind = k == "overlap"          ? K::Overlap
             : k == "gap"            ? K::Gap
             : k == "relative_speed" ? K::RelativeSpeed
             : k == "position"       ? K::Position
             : k == "velocity"       ? K::Velocity
             : k == "opening"        ? K::Opening
                                     : K::AngularVelocity;
    for (const auto& o : s.probes)
      if (o.name == p.name) t.fail("name", "probe names must be unique");
    if (p.kind == K::Opening) {
      read_opening(t, s, p);
      s.probes.push_back(p);
      t.finish();
      continue;
    }
    const bool two = p.kind == K::Overlap || p.kind == K::Gap || p.kind == K::RelativeSpeed;
    p.particles = ids(t, "particles", two ? 2 : 1);
    if (two && p.particles[0] == p.particles[1])
      t.fail("particles", "names particle " + std::to_string(p.particles[0]) + " twice: a " + k +
                              " probe needs two different particles");
    if (t.has("component")) {
      const std::string c = t.choice(
          "component", d == 2 ? std::vector<std::string>{"x", "y", "z"} : std::vector<std::string>{"x", "y", "z"});
      p.component = c == "x" ? 0 : c == "y" ? 1 : 2;
      if (p.kind != K::AngularVelocity && p.component >= d) t.fail("component", "a 2D scene has only x and y");
    }
    s.probes.push_back(p);
    t.finish();
  }
}

}  // namespace mc::scene_read
