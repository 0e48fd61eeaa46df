// [[walls]], [[groups]], [physics] and [timestep]: what holds and loads the specimen, and the effects declared.
#include "scene/scene_read_parts.hpp"

#include <cmath>
#include <sstream>

#include "engine/errors.hpp"

namespace mc::scene_read {

namespace {

WallControl read_motion(const Table& t, WallSpec& w, int d) {
  // The loaded area of the wall's stress history (and of a servo): a platen longer than the specimen it presses.
  w.servo_area = t.number("area", d == 2 ? Unit::Length : Unit::None, Range::positive(), kNaN);
  const std::string m = t.choice("motion", {"fixed", "velocity", "servo"}, "fixed");
  if (m == "velocity") {
    w.velocity = vec(t, "velocity", Unit::Velocity, d);
    w.ramp_time = t.number("ramp_time", Unit::Time, Range::non_negative(), 0.0);
    return WallControl::Velocity;
  }
  if (m == "servo") {
    w.stress = t.number("stress", Unit::Pressure, Range::any());
    if (t.has("area_between")) {
      // area_between = "left right" (2D) or "x_lo x_hi y_lo y_hi" (3D): walls whose distances span the area.
      std::stringstream ss(t.string("area_between"));
      std::string name;
      while (ss >> name) w.area_between.push_back(name);
      if (static_cast<int>(w.area_between.size()) != 2 * (d - 1))
        t.fail("area_between", "give " + std::to_string(2 * (d - 1)) + " wall names (" + std::to_string(d - 1) +
                                   " pair(s) of opposite walls), separated by spaces");
      if (!std::isnan(w.servo_area)) t.fail("area", "give either 'area' or 'area_between', not both");
    }
    w.gain = t.number("gain", Unit::None, Range{0.0, 1.0, true, false}, 0.5);
    w.max_speed = t.number("max_speed", Unit::Velocity, Range::positive());
    return WallControl::Servo;
  }
  return WallControl::Fixed;
}

FixMask parse_fix(const Table& t, int d) {
  // fix = "x y rz" (any of x, y, z, rx, ry, rz), or "all", or "translation", or "rotation".
  const std::string text = t.string("fix", "");
  std::vector<std::string> dofs =
      d == 2 ? std::vector<std::string>{"x", "y", "rz"} : std::vector<std::string>{"x", "y", "z", "rx", "ry", "rz"};
  FixMask m = 0;
  std::stringstream ss(text);
  std::string w;
  while (ss >> w) {
    if (w == "all")
      m |= static_cast<FixMask>((1u << (d + (d == 2 ? 1 : 3))) - 1);
    else if (w == "translation")
      m |= static_cast<FixMask>((1u << d) - 1);
    else if (w == "rotation")
      m |= static_cast<FixMask>(((1u << (d == 2 ? 1 : 3)) - 1) << d);
    else {
      const auto it = std::find(dofs.begin(), dofs.end(), w);
      if (it == dofs.end()) {
        std::string allowed = "all, translation, rotation";
        for (const auto& x : dofs) allowed += ", " + x;
        t.fail("fix", "'" + w + "' is not a degree of freedom; allowed (space separated): " + allowed);
      }
      m |= static_cast<FixMask>(1u << (it - dofs.begin()));
    }
  }
  return m;
}

}  // namespace

void read_walls(const Table& root, Scene& s) {
  const int d = s.dimension;
  for (const Table& t : root.tables("walls")) {
    WallSpec w;
    w.name = t.string("name", "wall" + std::to_string(s.walls.size()));
    const std::string shape = t.choice("shape", d == 2 ? std::vector<std::string>{"plane", "segment"}
                                                       : std::vector<std::string>{"plane", "rectangle"});
    if (shape == "plane") {
      w.kind = WallSpec::Kind::Plane;
      w.point = vec(t, "point", Unit::Length, d);
      w.normal = vec(t, "normal", Unit::None, d);
    } else if (shape == "segment") {
      w.kind = WallSpec::Kind::Segment;
      w.a = vec(t, "a", Unit::Length, d);
      w.b = vec(t, "b", Unit::Length, d);
      w.inside = vec(t, "inside", Unit::Length, d);
    } else {
      w.kind = WallSpec::Kind::Rectangle;
      w.point = vec(t, "centre", Unit::Length, d);
      w.normal = vec(t, "normal", Unit::None, d);
      w.axis = vec(t, "axis", Unit::None, d);
      const auto size = t.numbers("size", Unit::Length, Range::positive(), 2);
      w.size0 = size[0];
      w.size1 = size[1];
    }
    if (!w.normal.empty()) {
      double n2 = 0;
      for (double c : w.normal) n2 += c * c;
      if (n2 == 0) t.fail("normal", "the normal must not be the zero vector");
    }
    w.material.kn = t.number("kn", Unit::Stiffness, Range::positive());
    w.material.ks = t.number("ks", Unit::Stiffness, Range::positive(), w.material.kn);
    w.material.friction = t.number("friction", Unit::None, Range::non_negative(), 0.0);
    w.control = read_motion(t, w, d);
    for (const auto& o : s.walls)
      if (o.name == w.name) t.fail("name", "wall names must be unique");
    s.walls.push_back(w);
    t.finish();
  }
  const auto tabs = root.tables("walls");
  for (std::size_t i = 0; i < s.walls.size(); ++i)
    for (const auto& n : s.walls[i].area_between) {
      bool found = false;
      for (const auto& o : s.walls) found |= o.name == n;
      if (!found) tabs[i].fail("area_between", "'" + n + "' is not the name of a wall");
    }
}

void read_groups(const Table& root, Scene& s) {
  const int d = s.dimension, r = d == 2 ? 1 : 3;
  for (const Table& t : root.tables("groups")) {
    GroupSpec g;
    g.name = t.string("name", "group" + std::to_string(s.groups.size()));
    if (t.has("tags"))
      for (double x : t.numbers("tags", Unit::None, Range::closed(0, 1e9), 0))
        g.tags.push_back(static_cast<std::int64_t>(x));
    if (t.has("ids"))
      for (double x : t.numbers("ids", Unit::None, Range::closed(0, 1e12), 0))
        g.ids.push_back(static_cast<std::int64_t>(x));
    g.box_lo = opt_vec(t, "box_lo", Unit::Length, d);
    g.box_hi = opt_vec(t, "box_hi", Unit::Length, d);
    if (g.box_lo.empty() != g.box_hi.empty())
      t.fail(g.box_lo.empty() ? "box_hi" : "box_lo", "box_lo and box_hi go together");
    if (g.tags.empty() && g.ids.empty() && g.box_lo.empty())
      t.fail("tags", "a group selects particles by 'tags', 'ids' or 'box_lo'/'box_hi'");
    g.fix = parse_fix(t, d);
    g.velocity = opt_vec(t, "velocity", Unit::Velocity, d);
    g.angular_velocity = opt_vec(t, "angular_velocity", Unit::Rate, r);
    g.force = opt_vec(t, "force", Unit::Force, d);
    g.moment = opt_vec(t, "moment", Unit::Moment, r);
    s.groups.push_back(g);
    t.finish();
  }
}

void read_physics(const Table& root, Scene& s) {
  const int d = s.dimension;
  if (auto t = root.optional_table("physics")) {
    if (t->has("gravity")) s.gravity = vec(*t, "gravity", Unit::Acceleration, d);
    s.local_damping = t->number("local_damping", Unit::None, Range::open_fraction(), 0.0);
    s.density_scaling = t->number("density_scaling", Unit::None, Range::at_least(1.0), 1.0);
    if (s.density_scaling != 1.0 && s.gravity)
      t->fail("density_scaling",
              "scales the inertial mass, which gravity would then pull with too: density scaling is "
              "for quasi-static runs without gravity (leave it at 1 or drop gravity)");
    s.energy = t->boolean("energy", false);
    s.skin = t->number("skin", Unit::Length, Range::positive(), 0.0);
    s.domain_lo = opt_vec(*t, "domain_lo", Unit::Length, d);
    s.domain_hi = opt_vec(*t, "domain_hi", Unit::Length, d);
    t->finish();
  }
  if (auto t = root.optional_table("timestep")) {
    const TimestepControl defaults;
    s.timestep.safety = t->number("safety", Unit::None, Range{0.0, 1.0, true, false}, defaults.safety);
    s.timestep.fixed = t->number("fixed", Unit::Time, Range::positive(), defaults.fixed);
    s.timestep.every = static_cast<int>(t->integer("every", Range::closed(1, 1e9), defaults.every));
    t->finish();
  }
}

}  // namespace mc::scene_read
