// [[walls]], [[groups]], [physics] and [timestep]: what holds and loads the specimen, and the effects declared.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "engine/errors.hpp"
#include "scene/scene_read_parts.hpp"

namespace mc {

namespace {
constexpr std::string_view kServo = "motion = servo", kOpening = "motion = opening";
}  // namespace

const KeyTable& walls_keys() {
  static const KeyTable t{
      .name = "walls",
      .title = "[[walls]]",
      .about = "Rigid walls: planes, 2D segments or 3D rectangles, with springs in series with the balls'. A wall "
               "is fixed, moves at a velocity, holds a stress (PFC's servo) or opens a clip gauge at a rate (CMOD "
               "control, Tang §7.1). Histories wall.<name>.force_*, .stress, .disp_*, .moment_*.",
      .keys = {
          {.name = "name", .type = KeyType::Text, .doc = "unique name (histories are wall.<name>.*)", .shown_default = "wall<i>"},
          {.name = "shape", .type = KeyType::Word,
           .need = Need::Required,
           .doc = "2D: segment or plane (an infinite line); 3D: rectangle or plane",
           .words = {"plane", "segment", "rectangle"}},
          {.name = "point", .type = KeyType::Reals, .unit = Unit::Length, .need = Need::Required, .when = "shape = plane",
           .doc = "a point of the plane"},
          {.name = "normal", .type = KeyType::Reals, .need = Need::Required, .when = "shape = plane or rectangle",
           .doc = "points towards the material; not the zero vector"},
          {.name = "a", .type = KeyType::Reals, .unit = Unit::Length, .need = Need::Required, .when = "shape = segment",
           .doc = "one end (2D)"},
          {.name = "b", .type = KeyType::Reals, .unit = Unit::Length, .need = Need::Required, .when = "shape = segment",
           .doc = "the other end, distinct from a"},
          {.name = "inside", .type = KeyType::Reals, .unit = Unit::Length, .need = Need::Required, .when = "shape = segment",
           .doc = "a point off the segment's line, on the material side"},
          {.name = "centre", .type = KeyType::Reals, .unit = Unit::Length, .need = Need::Required, .when = "shape = rectangle",
           .doc = "the rectangle's centre (3D)"},
          {.name = "axis", .type = KeyType::Reals, .need = Need::Required, .when = "shape = rectangle",
           .doc = "an edge direction in its plane, not parallel to normal"},
          {.name = "size", .type = KeyType::Reals, .unit = Unit::Length, .range = Range::positive(), .need = Need::Required,
           .when = "shape = rectangle", .doc = "[along axis, across] its edge lengths"},
          {.name = "kn", .unit = Unit::Stiffness, .range = Range::positive(), .need = Need::Required,
           .doc = "the wall's normal spring, in series with the ball's"},
          {.name = "ks", .unit = Unit::Stiffness, .range = Range::positive(), .doc = "its shear spring",
           .shown_default = "kn"},
          {.name = "friction", .range = Range::non_negative(), .doc = "μ at the wall", .fallback = 0},
          {.name = "motion", .type = KeyType::Word,
           .doc = "fixed, velocity, servo or opening",
           .words = {"fixed", "velocity", "servo", "opening"},
           .shown_default = "fixed"},
          {.name = "velocity", .type = KeyType::Reals, .unit = Unit::Velocity, .need = Need::Required, .when = "motion = velocity",
           .doc = "the target velocity, reached as (1 − cos πt/T)/2 over ramp_time"},
          {.name = "ramp_time", .unit = Unit::Time, .range = Range::non_negative(),
           .when = "motion = velocity or opening", .doc = "T of the ramp", .fallback = 0},
          {.name = "stress", .unit = Unit::Pressure, .need = Need::Required, .when = kServo,
           .doc = "the compressive normal stress to hold"},
          {.name = "gain", .range = Range{0.0, 1.0, true, false}, .when = kServo,
           .doc = "PFC's servo gain α: G = αA/(Σk Δt), 0 < α ≤ 1", .fallback = 0.5},
          {.name = "gain", .unit = Unit::Rate, .range = Range::positive(), .need = Need::Required, .when = kOpening,
           .doc = "proportional control v = clamp(gain (rate·τ(t) − reading), −retreat_speed, max_speed), τ(t) the "
                  "time the ramped rate has acted: the wall trails its target by its speed/gain; the run stops "
                  "with exit 4 if gain·Δt ≥ 1"},
          {.name = "max_speed", .unit = Unit::Velocity, .range = Range::positive(), .need = Need::Required,
           .when = "motion = servo or opening", .doc = "the wall's speed limit"},
          {.name = "retreat_speed", .unit = Unit::Velocity, .range = Range::positive(), .when = kOpening,
           .doc = "how fast it may back off", .shown_default = "max_speed"},
          {.name = "probe", .type = KeyType::Text, .need = Need::Required, .when = kOpening,
           .doc = "the opening probe ([[probes]] kind = \"opening\") it drives"},
          {.name = "rate", .unit = Unit::Velocity, .range = Range::positive().usually(1e-9, 0.05),
           .need = Need::Required, .when = kOpening, .doc = "the rate the probe opens at, reached over ramp_time"},
          {.name = "area", .unit = Unit::Length, .range = Range::positive(), .when = "2D",
           .doc = "the loaded area of the wall's stress history and servo [m, per unit thickness]: e.g. the "
                  "specimen's width under a longer platen",
           .shown_default = "the wall's own"},
          {.name = "area", .range = Range::positive(), .when = "3D",
           .doc = "the loaded area [m²] of the wall's stress history and servo", .shown_default = "the wall's own"},
          {.name = "area_between", .type = KeyType::Text, .when = kServo,
           .doc = "instead of area: the names of opposite walls whose current distances span it (\"left right\"; "
                  "3D: two pairs)"},
      }};
  return t;
}

const KeyTable& groups_keys() {
  static const KeyTable t{
      .name = "groups",
      .title = "[[groups]]: boundary conditions on particles",
      .about = "Particles chosen by tags, ids or a box, held, set moving, driven or loaded. A driven group (with "
               "ramp_time) reaches its velocity as (1 − cos πt/T)/2 over T and holds it on its fixed translations, "
               "which must include every axis the velocity moves along (Tang §8.1's FRP end, pulled \"in a "
               "controlled fashion\"); its reaction is the group.<name>.reaction_* history.",
      .keys = {
          {.name = "name", .type = KeyType::Text, .doc = "unique name (histories are group.<name>.*)", .shown_default = "group<i>"},
          {.name = "tags", .type = KeyType::Reals, .range = scene_read::kIds, .doc = "the particles of these sphere-list tags"},
          {.name = "ids", .type = KeyType::Reals, .range = scene_read::kIds, .doc = "the particles of these ids"},
          {.name = "box_lo", .type = KeyType::Reals, .unit = Unit::Length, .doc = "the particles whose centres lie in the box (with box_hi)"},
          {.name = "box_hi", .type = KeyType::Reals, .unit = Unit::Length, .doc = "its high corner"},
          {.name = "fix", .type = KeyType::Text,
           .doc = "held degrees of freedom, separated by spaces: any of x y z rx ry rz, all, translation, rotation; "
                  "a held one keeps its velocity",
           .shown_default = "none"},
          {.name = "velocity", .type = KeyType::Reals, .unit = Unit::Velocity, .doc = "set at the start (held on fixed axes)"},
          {.name = "angular_velocity", .type = KeyType::Reals, .unit = Unit::Rate, .doc = "set at the start [rad/s]; one component in 2D"},
          {.name = "ramp_time", .unit = Unit::Time, .range = Range::non_negative(),
           .doc = "driven: the velocity reached over this time"},
          {.name = "force", .type = KeyType::Reals, .unit = Unit::Force, .doc = "applied on each particle, constant"},
          {.name = "moment", .type = KeyType::Reals, .unit = Unit::Moment, .doc = "applied on each particle, constant"},
      }};
  return t;
}

const KeyTable& physics_keys() {
  static const KeyTable t{
      .name = "physics",
      .title = "[physics]: effects, only when declared",
      .about = "What the scene does not declare is not computed: the effects are template parameters of the "
               "engine's loop.",
      .keys = {
          {.name = "gravity", .type = KeyType::Reals, .unit = Unit::Acceleration, .doc = "acceleration vector", .shown_default = "off"},
          {.name = "local_damping", .range = Range::open_fraction(),
           .doc = "PFC local damping α (0.7 for quasi-static runs); 0: off", .fallback = 0},
          {.name = "density_scaling", .range = Range::at_least(1.0),
           .doc = "PFC density scaling: every mass and moment of inertia times F ≥ 1, so the critical step grows by "
                  "√F and the dynamics are those of the strain rate times √F; refused with gravity; 1: off",
           .fallback = 1},
          {.name = "energy", .type = KeyType::Flag,
           .doc = "trace the energy terms (Tang 3.74-3.80): histories energy.boundary_work, body_work, strain, "
                  "kinetic, dissipated_bonds, dissipated_contacts, dissipated_local and residual",
           .fallback = 0},
          {.name = "skin", .unit = Unit::Length, .range = Range::positive(),
           .doc = "Verlet skin: lists rebuilt when something moved more than skin/2; with an adaptive skin its least "
                  "value",
           .shown_default = "0.1 R_min"},
          {.name = "rebuild_interval", .type = KeyType::Integer, .range = Range::closed(0, 1e9),
           .doc = "adaptive skin: at each rebuild the skin becomes 2 × (largest displacement per step since the "
                  "last rebuild) × this, between skin and R_min; 0 keeps the skin fixed",
           .fallback = 30},
          {.name = "domain_lo", .type = KeyType::Reals, .unit = Unit::Length,
           .doc = "a particle leaving the box [domain_lo, domain_hi] stops the run; it holds the whole specimen at "
                  "the start",
           .shown_default = "the specimen's box ± its size"},
          {.name = "domain_hi", .type = KeyType::Reals, .unit = Unit::Length, .doc = "its high corner",
           .shown_default = "the specimen's box ± its size"},
      }};
  return t;
}

const KeyTable& timestep_keys() {
  using P = TimestepControl;
  static const KeyTable t = key_table<P>(
      "timestep", "[timestep]",
      "The critical step √(m/Σk), √(I/Σk_rot) (Tang 3.21-3.24), lowered by the dashpots' damping, is estimated "
      "from the current stiffnesses every `every` steps and at every list rebuild. It bounds stability, not "
      "accuracy: long undamped impact sequences want a safety of 0.1 or less.",
      {
          bound(&P::safety, {.name = "safety",
                            .range = Range{0.0, 1.0, true, false},
                            .doc = "the step as a fraction of the critical one, Tang (3.24)"}),
          bound(&P::fixed, {.name = "fixed",
                           .unit = Unit::Time,
                           .range = Range::positive(),
                           .doc = "a fixed step, refused if above the estimate (at the start: exit 2; once the "
                                  "contacts stiffen mid-run: exit 4); 0: safety × the estimate"}),
          bound(&P::every, {.name = "every",
                           .range = Range::closed(1, 1e9),
                           .doc = "steps between estimates"}),
      });
  return t;
}

namespace scene_read {

namespace {

WallControl read_motion(const KeyReader& k, WallSpec& w, int d) {
  // The loaded area of the wall's stress history (and of a servo): a platen longer than the specimen it presses.
  w.servo_area = k.number(k.key("area", d == 2 ? "2D" : "3D"), kNaN);
  const std::string m = k.choice("motion");
  if (m == "opening") {
    // CMOD control (Tang §7.1): the wall moves along its normal so that an opening probe grows at `rate`.
    w.probe = k.string("probe");  // resolved once [[probes]] are read (check_opening_walls)
    w.opening_rate = k.number("rate");
    w.ramp_time = k.number("ramp_time");
    w.opening_gain = k.number(k.key("gain", kOpening));
    w.max_speed = k.number("max_speed");
    w.retreat_speed = k.number("retreat_speed", w.max_speed);
    return WallControl::Opening;
  }
  if (m == "velocity") {
    w.velocity = vec(k, "velocity", d);
    w.ramp_time = k.number("ramp_time");
    return WallControl::Velocity;
  }
  if (m == "servo") {
    w.stress = k.number("stress");
    if (k.has("area_between")) {
      // area_between = "left right" (2D) or "x_lo x_hi y_lo y_hi" (3D): walls whose distances span the area.
      std::stringstream ss(k.string("area_between"));
      std::string name;
      while (ss >> name) w.area_between.push_back(name);
      if (static_cast<int>(w.area_between.size()) != 2 * (d - 1))
        k.fail("area_between", "give " + std::to_string(2 * (d - 1)) + " wall names (" + std::to_string(d - 1) +
                                   " pair(s) of opposite walls), separated by spaces");
      for (std::size_t j = 0; j + 1 < w.area_between.size(); j += 2)
        if (w.area_between[j] == w.area_between[j + 1])
          k.fail("area_between", "pairs '" + w.area_between[j] + "' with itself: each pair is two opposite walls");
      if (!std::isnan(w.servo_area)) k.fail("area", "give either 'area' or 'area_between', not both");
    }
    w.gain = k.number(k.key("gain", kServo));
    w.max_speed = k.number("max_speed");
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
void check_segment(const KeyReader& k, const WallSpec& w) {
  const double ux = w.b[0] - w.a[0], uy = w.b[1] - w.a[1];
  const double length = std::hypot(ux, uy);
  if (!(length > 0)) k.fail("b", "the segment's ends a and b are the same point: a segment needs a length");
  const double off = (ux * (w.inside[1] - w.a[1]) - uy * (w.inside[0] - w.a[0])) / length;
  // Relative to the segment's length: a point within 1e-9 of it is on the line to rounding.
  if (!(std::abs(off) > 1e-9 * length))
    k.fail("inside", "the point lies on the segment's line; give a point off the line, on the side the particles are");
}

// A rectangle's axis lies in its plane, so it must not be (nearly) parallel to the normal: the edge directions
// come from the axis's part across the normal. Within 1e-6 of parallel that part is rounding noise.
void check_rectangle_axes(const KeyReader& k, const WallSpec& w) {
  const double na = norm(w.axis), nn = norm(w.normal);
  if (na == 0) k.fail("axis", "the axis must not be the zero vector");
  if (nn == 0) k.fail("normal", "the normal must not be the zero vector");
  double dot = 0;
  for (int i = 0; i < 3; ++i) dot += w.axis[i] * w.normal[i];
  const double sine = std::sqrt(std::max(0.0, 1.0 - dot * dot / (na * na * nn * nn)));
  if (!(sine > 1e-6)) k.fail("axis", "the axis is parallel to the normal; it must lie in the rectangle's plane");
}

FixMask parse_fix(const KeyReader& k, int d) {
  // fix = "x y rz" (any of x, y, z, rx, ry, rz), or "all", or "translation", or "rotation".
  const std::string text = k.string("fix", "");
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
        k.fail("fix", "'" + w + "' is not a degree of freedom; allowed (space separated): " + allowed);
      }
      m |= static_cast<FixMask>(1u << (it - dofs.begin()));
    }
  }
  return m;
}

}  // namespace

void read_walls(const Table& root, Scene& s) {
  const int d = s.dimension;
  const auto tables = tables_of(root, walls_keys());
  for (const Table& t : tables) {
    const KeyReader k(t, walls_keys());
    WallSpec w;
    w.name = k.string("name", "wall" + std::to_string(s.walls.size()));
    const std::string shape = k.choice("shape", d == 2 ? std::vector<std::string>{"plane", "segment"}
                                                       : std::vector<std::string>{"plane", "rectangle"});
    if (shape == "plane") {
      w.kind = WallSpec::Kind::Plane;
      w.point = vec(k, "point", d);
      w.normal = vec(k, "normal", d);
    } else if (shape == "segment") {
      w.kind = WallSpec::Kind::Segment;
      w.a = vec(k, "a", d);
      w.b = vec(k, "b", d);
      w.inside = vec(k, "inside", d);
      check_segment(k, w);
    } else {
      w.kind = WallSpec::Kind::Rectangle;
      w.point = vec(k, "centre", d);
      w.normal = vec(k, "normal", d);
      w.axis = vec(k, "axis", d);
      const auto size = k.numbers("size", 2);
      w.size0 = size[0];
      w.size1 = size[1];
      check_rectangle_axes(k, w);
    }
    if (!w.normal.empty() && norm(w.normal) == 0) k.fail("normal", "the normal must not be the zero vector");
    w.material.kn = k.number("kn");
    w.material.ks = k.number("ks", w.material.kn);
    w.material.friction = k.number("friction");
    w.control = read_motion(k, w, d);
    for (const auto& o : s.walls)
      if (o.name == w.name) k.fail("name", "wall names must be unique");
    s.walls.push_back(w);
    t.finish();
  }
  for (std::size_t i = 0; i < s.walls.size(); ++i)
    for (const auto& n : s.walls[i].area_between) {
      bool found = false;
      for (const auto& o : s.walls) found |= o.name == n;
      if (!found) KeyReader(tables[i], walls_keys()).fail("area_between", "'" + n + "' is not the name of a wall");
    }
}

// A group driven at its velocity through a ramp: the velocity is held on fixed translations only (a free one
// would be changed by the law of motion the next step), so each non-zero component needs its axis fixed.
void read_driven(const KeyReader& k, GroupSpec& g, int d) {
  g.ramp_time = k.number("ramp_time");
  if (g.velocity.empty()) k.fail("ramp_time", "a ramp needs the 'velocity' it rises to");
  check_driven_axes(k, g, d);
}

void check_driven_axes(const KeyReader& k, const GroupSpec& g, int d) {
  const char* axis = "xyz";
  for (int i = 0; i < d && !g.velocity.empty(); ++i)
    if (g.velocity[i] != 0 && !(g.fix & (1u << i)))
      k.fail("fix", "the group is driven along " + std::string(1, axis[i]) + " (velocity " +
                        std::to_string(g.velocity[i]) + " m/s), so " + axis[i] + " must be fixed: add it to 'fix'");
}

void read_groups(const Table& root, Scene& s) {
  const int d = s.dimension, r = d == 2 ? 1 : 3;
  for (const Table& t : tables_of(root, groups_keys())) {
    const KeyReader k(t, groups_keys());
    GroupSpec g;
    g.name = k.string("name", "group" + std::to_string(s.groups.size()));
    if (k.has("tags")) g.tags = ids(k, "tags", 0);
    if (k.has("ids")) g.ids = ids(k, "ids", 0);
    g.box_lo = opt_vec(k, "box_lo", d);
    g.box_hi = opt_vec(k, "box_hi", d);
    if (g.box_lo.empty() != g.box_hi.empty())
      k.fail(g.box_lo.empty() ? "box_hi" : "box_lo", "box_lo and box_hi go together");
    if (!g.box_lo.empty()) check_box(k, "box_lo", g.box_lo, "box_hi", g.box_hi);
    if (g.tags.empty() && g.ids.empty() && g.box_lo.empty())
      k.fail("tags", "a group selects particles by 'tags', 'ids' or 'box_lo'/'box_hi'");
    g.fix = parse_fix(k, d);
    g.velocity = opt_vec(k, "velocity", d);
    g.angular_velocity = opt_vec(k, "angular_velocity", r);
    if (k.has("ramp_time")) read_driven(k, g, d);
    g.force = opt_vec(k, "force", d);
    g.moment = opt_vec(k, "moment", r);
    s.groups.push_back(g);
    t.finish();
  }
}

void read_physics(const Table& root, Scene& s) {
  const int d = s.dimension;
  if (auto t = optional_table_of(root, physics_keys())) {
    const KeyReader k(*t, physics_keys());
    if (k.has("gravity")) s.gravity = vec(k, "gravity", d);
    s.local_damping = k.number("local_damping");
    s.density_scaling = k.number("density_scaling");
    if (s.density_scaling != 1.0 && s.gravity)
      k.fail("density_scaling",
             "scales the inertial mass, which gravity would then pull with too: density scaling is "
             "for quasi-static runs without gravity (leave it at 1 or drop gravity)");
    s.energy = k.boolean("energy");
    s.skin = k.number("skin", 0.0);
    s.rebuild_interval = static_cast<int>(k.integer("rebuild_interval"));
    s.domain_lo = opt_vec(k, "domain_lo", d);
    s.domain_hi = opt_vec(k, "domain_hi", d);
    if (s.domain_lo.empty() != s.domain_hi.empty())
      k.fail(s.domain_lo.empty() ? "domain_hi" : "domain_lo", "domain_lo and domain_hi go together");
    if (!s.domain_lo.empty()) check_box(k, "domain_lo", s.domain_lo, "domain_hi", s.domain_hi);
    t->finish();
  }
  if (auto t = optional_table_of(root, timestep_keys())) {
    read_bound_keys(*t, timestep_keys(), &s.timestep);
    t->finish();
  }
}

}  // namespace scene_read

}  // namespace mc
