// [[measure]], [[wall_strains]] and [[probes]]: what the scene observes.
#include "scene/scene_read_parts.hpp"

#include <sstream>

namespace mc::scene_read {

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
        t.choice("kind", {"overlap", "gap", "relative_speed", "position", "velocity", "angular_velocity"});
    using K = ProbeSpec::Kind;
    p.kind = k == "overlap"          ? K::Overlap
             : k == "gap"            ? K::Gap
             : k == "relative_speed" ? K::RelativeSpeed
             : k == "position"       ? K::Position
             : k == "velocity"       ? K::Velocity
                                     : K::AngularVelocity;
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
