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
#include "scene/scene_read_parts.hpp"

namespace mc {

namespace scene_read {

std::vector<double> vec(const Table& t, const std::string& key, Unit u, int dim) {
  return t.numbers(key, u, Range::any(), dim);
}
std::vector<double> opt_vec(const Table& t, const std::string& key, Unit u, int dim) {
  return t.has(key) ? vec(t, key, u, dim) : std::vector<double>{};
}

std::vector<std::int64_t> ids(const Table& t, const std::string& key, std::size_t n) {
  std::vector<std::int64_t> out;
  for (double x : t.numbers(key, Unit::None, Range::closed(0, 9007199254740992.0), n)) {
    if (x != std::floor(x)) {
      std::ostringstream m;
      m << "holds " << x << ": ids and tags are whole numbers";
      t.fail(key, m.str());
    }
    out.push_back(static_cast<std::int64_t>(x));
  }
  return out;
}

void check_box(const Table& t, const std::string& lo_key, const std::vector<double>& lo, const std::string& hi_key,
               const std::vector<double>& hi) {
  const char* axis[] = {"x", "y", "z"};
  for (std::size_t k = 0; k < lo.size(); ++k)
    if (!(lo[k] < hi[k])) {
      std::ostringstream m;
      m << "its " << axis[k] << " (" << hi[k] << " m) must be above " << lo_key << "'s (" << lo[k] << " m)";
      t.fail(hi_key, m.str());
    }
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

}  // namespace scene_read

namespace {

using namespace scene_read;

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

void read_bonds(const Table& root, Scene& s) {
  if (auto t = root.optional_table("bonds")) {
    // Bonds are installed once, on the specimen as built (a packing loaded from an earlier run is settled).
    s.bond_tolerance = t->number("gap_tolerance", Unit::None, Range::non_negative(), 0.0);
    s.crack_log = t->boolean("crack_log", true);
    t->finish();
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
  if (root.has("rigid_cell")) {
    read_rigid_cell(root, s);
  } else {
    read_contacts(root, s);
    read_specimen(root, s);
    read_mesostructure(root, s);
    read_walls(root, s);
    read_groups(root, s);
    read_physics(root, s);
    read_bonds(root, s);
    read_observers(root, s);
    check_opening_walls(root, s);
  }
  read_run(root, s);
  read_output(root, s);
  if (!s.rigid_cell) read_analyses(root, s);
  const std::vector<std::string> histories = history_names(s);
  check_names(root, s, histories);
  check_analyses(root, s, histories);
  doc.finish_all();
  return s;
}

}  // namespace mc
