// [[walls]], [[groups]], [physics] and [timestep]: what holds and loads the specimen, and the effects declared.
#include "scene/scene_read_parts.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "engine/errors.hpp"

namespace mc::scene_read {

namespace {

WallControl read_motion(const Table& t, WallSpec& w, int d) {
  // The loaded area of the wall's stress history (and of a servo): a platen longer than the specimen it presses.
  w.servo_area = t.number("area", d == 2 ? Unit::Length : Unit::None, Range::positive(), kNaN);
  const std::string m = t.choice("motion", {"fixed", "velocity", "servo", "opening"}, "fixed");
  if (m == "opening") {
    // CMOD control (Tang §7.1): the wall moves along its normal so that an opening probe grows at `rate`.
    w.probe = t.string("probe");  // resolved once [[probes]] are read (check_opening_walls)
    w.opening_rate = t.number("rate", Unit::Velocity, Range::positive());
    w.ramp_time = t.number("ramp_time", Unit::Time, Range::non_negative(), 0.0);
    w.opening_gain = t.number("gain", Unit::Rate, Range::positive());
    w.max_speed = t.number("max_speed", Unit::Velocity, Range::positive());
    w.retreat_speed = t.number("retreat_speed", Unit::Velocity, Range::positive(), w.max_speed);
    return WallControl::Opening;
  }
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
      for (std::size_t j = 0; j + 1 < w.area_between.size(); j += 2)
        if (w.area_between[j] == w.area_between[j + 1])
          t.fail("area_between", "pairs '" + w.area_between[j] + "' with itself: each pair is two opposite walls");
      if (!std::isnan(w.servo_area)) t.fail("area", "give either 'area' or 'area_between', not both");
    }
    w.gain = t.number("gain", Unit::None, Range{0.0, 1.0, true, false}, 0.5);
    w.max_speed = t.number("max_speed", Unit::Velocity, Range::positive());
    return WallControl::Servo;
  }
  return WallControl::Fixed;
}

double norm(const std::vector<double>& v) {
  double n2 = 0;
  for (double c : v) n2 += c * c;
  return std::sqrt(n2);
}

// A segment has a length, and its inside point lies off its line: the side the particles are on must be
// decidable, else the wall's normal is undefined (a zero-length segment gave NaN forces).
void check_segment(const Table& t, const WallSpec& w) {
  const double ux = w.b[0] - w.a[0], uy = w.b[1] - w.a[1];
  const double length = std::hypot(ux, uy);
  if (!(length > 0)) t.fail("b", "the segment's ends a and b are the same point: a segment needs a length");
  const double off = (ux * (w.inside[1] - w.a[1]) - uy * (w.inside[0] - w.a[0])) / length;
  // Relative to the segment's length: a point within 1e-9 of it is on the line to rounding.
  if (!(std::abs(off) > 1e-9 * length))
    t.fail("inside", "the point lies on the segment's line; give a point off the line, on the side the particles are");
}

// A rectangle's axis lies in its plane, so it must not be (nearly) parallel to the normal: the edge directions
// come from the axis's part across the normal. Within 1e-6 of parallel that part is rounding noise.
void check_rectangle_axes(const Table& t, const WallSpec& w) {
  const double na = norm(w.axis), nn = norm(w.normal);
  if (na == 0) t.fail("axis", "the axis must not be the zero vector");
  if (nn == 0) t.fail("normal", "the normal must not be the zero vector");
  double dot = 0;
  for (int k = 0; k < 3; ++k) dot += w.axis[k] * w.normal[k];
  const double sine = std::sqrt(std::max(0.0, 1.0 - dot * dot / (na * na * nn * nn)));
  if (!(sine > 1e-6)) t.fail("axis", "the axis is parallel to the normal; it must lie in the rectangle's plane");
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
      m |= fix_all(d);
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
      check_segment(t, w);
    } else {
      w.kind = WallSpec::Kind::Rectangle;
      w.point = vec(t, "centre", Unit::Length, d);
      w.normal = vec(t, "normal", Unit::None, d);
      w.axis = vec(t, "axis", Unit::None, d);
      const auto size = t.numbers("size", Unit::Length, Range::positive(), 2);
      w.size0 = size[0];
      w.size1 = size[1];
      check_rectangle_axes(t, w);
    }
    if (!w.normal.empty() && norm(w.normal) == 0) t.fail("normal", "the normal must not be the zero vector");
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

// A group driven at its velocity through a ramp: the velocity is held on fixed translations only (a free one
// would be changed by the law of motion the next step), so each non-zero component needs its axis fixed.
void read_driven(const Table& t, GroupSpec& g, int d) {
  g.ramp_time = t.number("ramp_time", Unit::Time, Range::non_negative());
  if (g.velocity.empty()) t.fail("ramp_time", "a ramp needs the 'velocity' it rises to");
  check_driven_axes(t, g, d);
}

void check_driven_axes(const Table& t, const GroupSpec& g, int d) {
  const char* axis = "xyz";
  for (int k = 0; k < d && !g.velocity.empty(); ++k)
    if (g.velocity[k] != 0 && !(g.fix & (1u << k)))
      t.fail("fix", "the group is driven along " + std::string(1, axis[k]) + " (velocity " +
                        std::to_string(g.velocity[k]) + " m/s), so " + axis[k] + " must be fixed: add it to 'fix'");
}

void read_groups(const Table& root, Scene& s) {
  const int d = s.dimension, r = d == 2 ? 1 : 3;
  for (const Table& t : root.tables("groups")) {
    GroupSpec g;
    g.name = t.string("name", "group" + std::to_string(s.groups.size()));
    if (t.has("tags")) g.tags = ids(t, "tags", 0);
    if (t.has("ids")) g.ids = ids(t, "ids", 0);
    g.box_lo = opt_vec(t, "box_lo", Unit::Length, d);
    g.box_hi = opt_vec(t, "box_hi", Unit::Length, d);
    if (g.box_lo.empty() != g.box_hi.empty())
      t.fail(g.box_lo.empty() ? "box_hi" : "box_lo", "box_lo and box_hi go together");
    if (!g.box_lo.empty()) check_box(t, "box_lo", g.box_lo, "box_hi", g.box_hi);
    if (g.tags.empty() && g.ids.empty() && g.box_lo.empty())
      t.fail("tags", "a group selects particles by 'tags', 'ids' or 'box_lo'/'box_hi'");
    g.fix = parse_fix(t, d);
    g.velocity = opt_vec(t, "velocity", Unit::Velocity, d);
    g.angular_velocity = opt_vec(t, "angular_velocity", Unit::Rate, r);
    if (t.has("ramp_time")) read_driven(t, g, d);
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
    s.rebuild_interval = static_cast<int>(t->integer("rebuild_interval", Range::closed(0, 1e9), 30));
    s.domain_lo = opt_vec(*t, "domain_lo", Unit::Length, d);
    s.domain_hi = opt_vec(*t, "domain_hi", Unit::Length, d);
    if (s.domain_lo.empty() != s.domain_hi.empty())
      t->fail(s.domain_lo.empty() ? "domain_hi" : "domain_lo", "domain_lo and domain_hi go together");
    if (!s.domain_lo.empty()) check_box(*t, "domain_lo", s.domain_lo, "domain_hi", s.domain_hi);
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
