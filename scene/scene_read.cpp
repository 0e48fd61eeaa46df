// Scene file → Scene. Every key is read through the validated Table accessors (scene/toml_reader.hpp), so
// each error names the file, the key, the value and what is allowed; unknown keys are errors.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "engine/errors.hpp"
#include "scene/analysis.hpp"
#include "scene/histories.hpp"
#include "scene/model_registry.hpp"
#include "scene/scene.hpp"
#include "scene/toml_reader.hpp"

namespace mc {

namespace {

std::vector<double> vec(const Table& t, const std::string& key, Unit u, int dim) {
  return t.numbers(key, u, Range::any(), dim);
}
std::vector<double> opt_vec(const Table& t, const std::string& key, Unit u, int dim) {
  return t.has(key) ? vec(t, key, u, dim) : std::vector<double>{};
}

int phase_index(const Table& t, const std::string& key, const std::vector<PhaseSpec>& phases) {
  std::vector<std::string> names;
  for (const auto& p : phases) names.push_back(p.name);
  const std::string n = t.choice(key, names);
  return static_cast<int>(std::find(names.begin(), names.end(), n) - names.begin());
}

// A file named in a scene is relative to the scene file's folder.
std::string relative_to(const std::string& scene_file, const std::string& path) {
  const std::filesystem::path p(path);
  if (p.is_absolute()) return path;
  return (std::filesystem::path(scene_file).parent_path() / p).lexically_normal().string();
}

void read_phases(const Table& root, Scene& s) {
  for (const Table& t : root.tables("phases")) {
    PhaseSpec p;
    p.name = t.string("name");
    p.density = t.number("density", Unit::Density, Range::positive());
    p.stiffness_std = t.number("stiffness_std", Unit::None, Range::non_negative(), 0.0);
    p.stiffness_weibull = t.number("stiffness_weibull_shape", Unit::None, Range::positive(), 0.0);
    if (p.stiffness_std > 0 && p.stiffness_weibull > 0)
      t.fail("stiffness_weibull_shape",
             "given together with stiffness_std: the particles' stiffness factor is drawn "
             "either from a normal distribution (mean 1, stiffness_std) or from a Weibull "
             "distribution (scale 1, stiffness_weibull_shape), not both");
    for (const auto& q : s.phases)
      if (q.name == p.name) t.fail("name", "phase names must be unique");
    s.phases.push_back(p);
    t.finish();
  }
  if (s.phases.empty())
    throw InputError(s.file + ": missing [[phases]]: at least one phase with a name and a density (kg/m3)");
}

void read_contacts(const Table& root, Scene& s) {
  for (const Table& t : root.tables("contacts")) {
    std::vector<std::string> names;
    for (const auto& p : s.phases) names.push_back(p.name);
    ContactSpec c;
    // phases = ["a", "b"]: two phase names; the model acts between them (in either order).
    const std::string pa = t.choice("phase_a", names), pb = t.choice("phase_b", names, pa);
    c.phase_a = static_cast<int>(std::find(names.begin(), names.end(), pa) - names.begin());
    c.phase_b = static_cast<int>(std::find(names.begin(), names.end(), pb) - names.begin());
    c.model = read_contact_model(t, t.choice("model", contact_model_names()), s.dimension);
    for (const auto& o : s.contacts)
      if ((o.phase_a == c.phase_a && o.phase_b == c.phase_b) || (o.phase_a == c.phase_b && o.phase_b == c.phase_a))
        t.fail("phase_b", "a contact model for this pair of phases is already given");
    s.contacts.push_back(std::move(c));
    t.finish();
  }
  if (s.contacts.empty())
    throw InputError(s.file + ": missing [[contacts]]: the contact model between phases (model = " +
                     "\"linear\" or \"hertz_mindlin\", phase_a, phase_b and the model's parameters)");
}

void read_specimen(const Table& root, Scene& s) {
  const Table t = root.table("specimen");
  SpecimenSpec& sp = s.specimen;
  const int d = s.dimension;
  const std::string kind = t.choice("kind", {"particles", "sphere_list", "output", "random_box", "lattice", "packing"});
  if (kind == "particles") {
    sp.kind = SpecimenSpec::Kind::Particles;
    for (const Table& p : t.tables("particles")) {
      InlineParticle ip;
      ip.x = vec(p, "x", Unit::Length, d);
      ip.radius = p.number("radius", Unit::Length, Range::positive());
      ip.v = p.has("velocity") ? vec(p, "velocity", Unit::Velocity, d) : std::vector<double>(d, 0.0);
      ip.w = p.has("angular_velocity") ? vec(p, "angular_velocity", Unit::Rate, d == 2 ? 1 : 3)
                                       : std::vector<double>(d == 2 ? 1 : 3, 0.0);
      ip.phase = s.phases.size() == 1 && !p.has("phase") ? 0 : phase_index(p, "phase", s.phases);
      sp.particles.push_back(ip);
      p.finish();
    }
    if (sp.particles.empty()) t.fail("particles", "kind = \"particles\" needs at least one [[specimen.particles]]");
  } else if (kind == "sphere_list" || kind == "output") {
    sp.kind = kind == "output" ? SpecimenSpec::Kind::Output : SpecimenSpec::Kind::SphereList;
    sp.file = relative_to(s.file, t.string("file"));
    if (kind == "sphere_list") {
      std::vector<std::string> names;
      for (const auto& p : s.phases) names.push_back(p.name);
      if (t.has("tag_phases")) {
        // tag_phases = "concrete,concrete,concrete": the phase of each tag, in tag order.
        std::stringstream ss(t.string("tag_phases"));
        std::string item;
        while (std::getline(ss, item, ',')) {
          item.erase(0, item.find_first_not_of(' '));
          item.erase(item.find_last_not_of(' ') + 1);
          const auto it = std::find(names.begin(), names.end(), item);
          if (it == names.end()) t.fail("tag_phases", "'" + item + "' is not a phase name");
          sp.tag_phase.push_back(static_cast<int>(it - names.begin()));
        }
      }
    }
  } else {
    sp.kind = kind == "lattice"   ? SpecimenSpec::Kind::Lattice
              : kind == "packing" ? SpecimenSpec::Kind::Packing
                                  : SpecimenSpec::Kind::RandomBox;
    sp.box_lo = vec(t, "lo", Unit::Length, d);
    sp.box_hi = vec(t, "hi", Unit::Length, d);
    for (int k = 0; k < d; ++k)
      if (sp.box_hi[k] <= sp.box_lo[k]) t.fail("hi", "each component must exceed the one of 'lo'");
    if (kind == "lattice") {  // equal particles: hexagonal (2D) or face-centred cubic (3D), Tang §8.1.1
      sp.radius_min = sp.radius_max = t.number("radius", Unit::Length, Range::positive());
      for (int k = 0; k < d; ++k)
        if (sp.box_hi[k] - sp.box_lo[k] < 2 * sp.radius_min)
          t.fail("radius", "the box [lo, hi] must be at least one diameter wide in every direction");
    } else if (kind == "packing") {  // PFC material genesis, Tang §5.2
      sp.radius_min = t.number("radius_min", Unit::Length, Range::positive());
      sp.radius_ratio = t.number("radius_ratio", Unit::None, Range::at_least(1.0), 1.66);
      sp.porosity = t.number("porosity", Unit::None, Range{0.05, 0.9, true, true}, d == 2 ? 0.16 : 0.36);
      sp.stress = t.number("stress", Unit::Pressure, Range::positive(), 1e5);
      sp.modulus = t.number("modulus", Unit::Pressure, Range::positive());
      sp.cylinder = t.choice("shape", {"box", "cylinder"}, "box") == "cylinder";
      if (sp.cylinder && d == 2) t.fail("shape", "a cylinder is a 3D shape; 2D packings fill the rectangle [lo, hi]");
      for (int k = 0; k < d; ++k)
        if (sp.box_hi[k] - sp.box_lo[k] < 6 * sp.radius_min * sp.radius_ratio)
          t.fail("radius_min", "the box [lo, hi] must be at least three largest diameters wide in every direction");
    } else {
      sp.count = t.integer("count", Range::closed(1, 5e7));
      sp.radius_min = t.number("radius_min", Unit::Length, Range::positive());
      sp.radius_max = t.number("radius_max", Unit::Length, Range::at_least(sp.radius_min), sp.radius_min);
    }
    sp.phase = s.phases.size() == 1 && !t.has("phase") ? 0 : phase_index(t, "phase", s.phases);
  }
  t.finish();
}

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
    s.timestep.safety = t->number("safety", Unit::None, Range{0.0, 1.0, true, false}, 0.8);
    s.timestep.fixed = t->number("fixed", Unit::Time, Range::positive(), 0.0);
    s.timestep.every = static_cast<int>(t->integer("every", Range::closed(1, 1e9), 10));
    t->finish();
  }
}

void read_mesostructure(const Table& root, Scene& s) {
  auto t = root.optional_table("mesostructure");
  if (!t) return;
  const int d = s.dimension;
  MesostructureSpec& m = s.mesostructure;
  m.present = true;
  m.fraction = t->number("fraction", Unit::None, Range{0.0, 1.0, true, true});
  // Tang Table 4.1 (4–8, 8–16, 16–32, 32–64 mm at 2:2:3:3), scaled by size_scale; or explicit ranges.
  const std::string grading = t->choice("grading", {"table_4_1", "ranges"}, "table_4_1");
  const double scale = t->number("size_scale", Unit::None, Range::positive(), 1.0);
  if (grading == "table_4_1") {
    for (auto [lo, hi, share] : {std::array<double, 3>{4, 8, 2}, {8, 16, 2}, {16, 32, 3}, {32, 64, 3}})
      m.ranges.push_back({lo * 1e-3 * scale, hi * 1e-3 * scale, share / 10});
  } else {
    double total = 0;
    for (const Table& r : t->tables("ranges")) {
      const double lo = r.number("lo", Unit::Length, Range::positive());
      const double hi = r.number("hi", Unit::Length, Range{lo, kInf, true, false});
      const double share = r.number("share", Unit::None, Range::positive());
      m.ranges.push_back({lo * scale, hi * scale, share});
      total += share;
      r.finish();
    }
    if (m.ranges.empty())
      t->fail("ranges", "grading = \"ranges\" needs at least one [[mesostructure.ranges]] with lo, hi, share");
    for (auto& r : m.ranges) r[2] /= total;
  }
  m.lo = opt_vec(*t, "lo", Unit::Length, d);
  m.hi = opt_vec(*t, "hi", Unit::Length, d);
  if (m.lo.empty() != m.hi.empty()) t->fail(m.lo.empty() ? "hi" : "lo", "lo and hi go together");
  for (const Table& k : t->tables("keep_out")) {
    if (k.has("radius")) {
      m.keep_out_centre.push_back(vec(k, "centre", Unit::Length, d));
      m.keep_out_radius.push_back(k.number("radius", Unit::Length, Range::positive()));
    } else {
      m.keep_out_lo.push_back(vec(k, "box_lo", Unit::Length, d));
      m.keep_out_hi.push_back(vec(k, "box_hi", Unit::Length, d));
    }
    k.finish();
  }
  m.cells_per_dmin = t->number("cells_per_dmin", Unit::None, Range::closed(5, 10), 5);
  m.mortar_phase = phase_index(*t, "mortar_phase", s.phases);
  m.aggregate_phase = phase_index(*t, "aggregate_phase", s.phases);
  if (m.mortar_phase == m.aggregate_phase) t->fail("aggregate_phase", "must differ from mortar_phase");
  t->finish();
}

void read_bonds(const Table& root, Scene& s) {
  if (auto t = root.optional_table("bonds")) {
    // Bonds are installed once, on the specimen as built (a packing loaded from an earlier run is settled).
    s.bond_tolerance = t->number("gap_tolerance", Unit::None, Range::non_negative(), 0.0);
    s.crack_log = t->boolean("crack_log", true);
    t->finish();
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
    for (double x : t.numbers("particles", Unit::None, Range::closed(0, 1e12), two ? 2 : 1))
      p.particles.push_back(static_cast<std::int64_t>(x));
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

void read_run(const Table& root, Scene& s) {
  const Table t = root.table("run");
  s.steps = t.integer("steps", Range::closed(0, 1e15), 0);
  s.duration = t.number("duration", Unit::Time, Range::non_negative(), 0.0);
  for (const Table& st : t.tables("stop")) {
    StopSpec x;
    x.quantity = st.string("quantity");
    const int given = st.has("below") + st.has("above") + st.has("post_peak_fraction");
    if (given != 1) st.fail("quantity", "give exactly one of 'below', 'above', 'post_peak_fraction'");
    if (st.has("below")) x.kind = StopSpec::Kind::Below, x.value = st.number("below", Unit::None, Range::any());
    if (st.has("above")) x.kind = StopSpec::Kind::Above, x.value = st.number("above", Unit::None, Range::any());
    if (st.has("post_peak_fraction"))
      x.kind = StopSpec::Kind::PostPeak,
      x.value = st.number("post_peak_fraction", Unit::None, Range{0.0, 1.0, true, true});
    x.after_time = st.number("after_time", Unit::Time, Range::non_negative(), 0.0);
    s.stops.push_back(x);
    st.finish();
  }
  if (s.steps == 0 && s.duration == 0 && s.stops.empty())
    t.fail("steps", "the run needs an end: 'steps', 'duration' or a [[run.stop]] condition");
  t.finish();
  for (const Table& st : root.tables("summary")) {
    SummarySpec x;
    x.name = st.string("name");
    x.of = st.string("of");
    const std::vector<std::string> kinds = {
        "max", "min", "final", "initial", "time_of_max", "duration_positive", "final_over_initial", "mean_final_10"};
    const std::string k = st.choice("reduce", kinds);
    x.reduce = static_cast<SummarySpec::Reduce>(std::find(kinds.begin(), kinds.end(), k) - kinds.begin());
    s.summaries.push_back(x);
    st.finish();
  }
}

void read_output(const Table& root, Scene& s) {
  if (auto t = root.optional_table("output")) {
    s.history_every = t->integer("history_every", Range::closed(1, 1e12), 100);
    s.frame_every = t->integer("frame_every", Range::closed(0, 1e12), 0);
    s.checkpoint_every = t->integer("checkpoint_every", Range::closed(0, 1e12), 0);
    s.guard_every = t->integer("guard_every", Range::closed(1, 1e9), 100);
    s.xy_plots = t->string("xy_plots", "");
    t->finish();
  }
}

// Names used by stop conditions and summaries must be histories the scene records.
void check_names(const Table& root, const Scene& s, const std::vector<std::string>& histories) {
  auto known = [&](const std::string& n) {
    return std::find(histories.begin(), histories.end(), n) != histories.end();
  };
  std::string list;
  for (const auto& h : histories) list += (list.empty() ? "" : ", ") + h;
  auto tabs = root.table("run").tables("stop");
  for (std::size_t i = 0; i < s.stops.size(); ++i)
    if (!known(s.stops[i].quantity)) tabs[i].fail("quantity", "not a history of this scene; recorded: " + list);
  auto sums = root.tables("summary");
  for (std::size_t i = 0; i < s.summaries.size(); ++i)
    if (!known(s.summaries[i].of)) sums[i].fail("of", "not a history of this scene; recorded: " + list);
}

}  // namespace

Scene read_scene(const TomlDoc& doc, const std::string& file) {
  Scene s;
  s.file = file;
  s.text = doc.text();
  const Table root = doc.root();
  s.dimension = static_cast<int>(root.integer("dimension", Range::closed(2, 3)));
  s.seed = static_cast<std::uint64_t>(root.integer("seed", Range::closed(0, 9.0e18), 1));
  s.title = root.string("title", "");
  read_phases(root, s);
  read_contacts(root, s);
  read_specimen(root, s);
  read_mesostructure(root, s);
  read_walls(root, s);
  read_groups(root, s);
  read_physics(root, s);
  read_bonds(root, s);
  read_observers(root, s);
  read_run(root, s);
  read_output(root, s);
  read_analyses(root, s);
  const std::vector<std::string> histories = history_names(s);
  check_names(root, s, histories);
  check_analyses(root, s, histories);
  doc.finish_all();
  return s;
}

}  // namespace mc
