// Scene file → Scene. Every key is read through the validated Table accessors (scene/toml_reader.hpp), so
// each error names the file, the key, the value and what is allowed; unknown keys are errors.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "engine/errors.hpp"
#include "rigid_cell/facet_law.hpp"  // the facet law's name, a word of [[contacts]] model
#include "scene/analysis.hpp"
#include "scene/histories.hpp"
#include "scene/model_registry.hpp"
#include "scene/scene_keys.hpp"
#include "scene/scene_read_parts.hpp"

namespace mc {

namespace scene_read {

std::vector<double> vec(const KeyReader& k, std::string_view key, int dim) { return k.numbers(key, dim); }
std::vector<double> opt_vec(const KeyReader& k, std::string_view key, int dim) {
  return k.has(key) ? vec(k, key, dim) : std::vector<double>{};
}

std::vector<std::int64_t> ids(const KeyReader& k, std::string_view key, std::size_t n) {
  std::vector<std::int64_t> out;
  for (double x : k.numbers(key, n)) {
    if (x != std::floor(x)) {
      std::ostringstream m;
      m << "holds " << x << ": ids and tags are whole numbers";
      k.fail(key, m.str());
    }
    out.push_back(static_cast<std::int64_t>(x));
  }
  return out;
}

void check_box(const KeyReader& k, std::string_view lo_key, const std::vector<double>& lo, std::string_view hi_key,
               const std::vector<double>& hi) {
  const char* axis[] = {"x", "y", "z"};
  for (std::size_t i = 0; i < lo.size(); ++i)
    if (!(lo[i] < hi[i])) {
      std::ostringstream m;
      m << "its " << axis[i] << " (" << hi[i] << " m) must be above " << lo_key << "'s (" << lo[i] << " m)";
      k.fail(hi_key, m.str());
    }
}

int phase_index(const KeyReader& k, std::string_view key, const std::vector<PhaseSpec>& phases) {
  std::vector<std::string> names;
  for (const auto& p : phases) names.push_back(p.name);
  const std::string n = k.choice(key, names);
  return static_cast<int>(std::find(names.begin(), names.end(), n) - names.begin());
}

// A file named in a scene is relative to the scene file's folder.
std::string relative_to(const std::string& scene_file, const std::string& path) {
  const std::filesystem::path p(path);
  if (p.is_absolute()) return path;
  return (std::filesystem::path(scene_file).parent_path() / p).lexically_normal().string();
}

}  // namespace scene_read

const KeyTable& scene_keys() {
  static const KeyTable t{
      .name = "scene",
      .title = "Top level",
      .about = "A scene file is TOML, in SI units; a number may also be a string with a unit (\"30 GPa\", "
               "\"5 mm/s\", \"45 deg\") of the key's kind. Unknown keys are errors.",
      .keys = {
          {.name = "dimension", .type = KeyType::Integer,
           .range = Range::closed(2, 3),
           .need = Need::Required,
           .doc = "2 (discs of unit thickness) or 3 (spheres); vectors have this many components"},
          {.name = "seed", .type = KeyType::Integer,
           .range = Range::closed(0, 9.0e18),
           .doc = "random seed: generated specimens, bond strengths, heterogeneity, random fields",
           .fallback = 1},
          {.name = "title", .type = KeyType::Text, .doc = "free text, shown by summary"},
      }};
  return t;
}

const KeyTable& phases_keys() {
  using P = PhaseSpec;
  static const KeyTable t = key_table<P>(
      "phases", "[[phases]] (at least one)",
      "The materials of the particles: each particle belongs to one phase, and [[contacts]] gives each pair of "
      "phases its contact model.",
      {
          bound(&P::name, {.name = "name", .need = Need::Required, .doc = "unique name"}),
          bound(&P::density, {.name = "density",
                             .unit = Unit::Density,
                             .range = Range::positive(),
                             .need = Need::Required,
                             .doc = "ρ; in 2D per unit thickness, mass = ρπR² · 1 m"}),
          bound(&P::stiffness_std,
               {.name = "stiffness_std",
                .range = Range::non_negative(),
                .doc = "heterogeneity (Tang §8.1.2): each particle's springs (the ball stiffness of the linear "
                       "family, G of Hertz-Mindlin, k_N of the CPM) scaled by a factor drawn per particle from a "
                       "normal distribution of mean 1 and this spread, truncated to > 0; 0: factor 1"}),
          bound(&P::stiffness_weibull_shape,
               {.name = "stiffness_weibull_shape",
                .range = Range::positive(),
                .doc = "or from a Weibull distribution of scale 1 and this shape, Tang (8.4); not with "
                       "stiffness_std"}),
      },
      {}, [](const P& p) -> std::optional<KeyProblem> {
        if (p.stiffness_std > 0 && p.stiffness_weibull_shape > 0)
          return KeyProblem{"stiffness_weibull_shape",
                            "given together with stiffness_std: the particles' stiffness factor is drawn "
                            "either from a normal distribution (mean 1, stiffness_std) or from a Weibull "
                            "distribution (scale 1, stiffness_weibull_shape), not both"};
        return std::nullopt;
      });
  return t;
}

const KeyTable& contacts_keys() {
  static const KeyTable t = [] {
    KeyTable t{
      .name = "contacts",
      .title = "[[contacts]]: the contact-model table",
      .about = "One entry per pair of phases that meet: its model and the model's keys (the tables below). A ball "
               "touching a wall uses the model of its own phase, with the wall's springs in series.",
      .keys = {
          {.name = "model", .type = KeyType::Word,
           .need = Need::Required,
           .doc = "the contact model (its keys: the tables below); cpm is for 3D scenes only, facet_damage for "
                  "rigid-cell scenes only"},
          {.name = "phase_a", .type = KeyType::Text, .need = Need::Required, .doc = "a phase name"},
          {.name = "phase_b", .type = KeyType::Text, .doc = "the other phase (either order)", .shown_default = "phase_a"},
      }};
    // The words of `model`: the registered models' names (their tables' names, static like the models'), and the
    // rigid-cell facet law's.
    for (const KeyTable* m : contact_model_keys()) t.keys[0].words.push_back(m->name);
    t.keys[0].words.push_back(rigid_cell::facet_law_keys().name);
    return t;
  }();
  return t;
}

const KeyTable& bonds_keys() {
  static const KeyTable t{
      .name = "bonds",
      .title = "[bonds]",
      .about = "Bonds are installed once, at the start, on the specimen as built, each with the model of its phase "
               "pair (models without bonds ignore it). The bonded coordination number 2 N_bonds / N is written "
               "as the /specimen attribute bonded_coordination.",
      .keys = {
          {.name = "gap_tolerance",
           .range = Range::non_negative(),
           .doc = "every pair whose gap is at most gap_tolerance · min(R_A, R_B) is bonded; 0 bonds touching pairs "
                  "only (Potyondy & Cundall). A cpm model bonds by its own interaction_radius instead",
           .fallback = 0},
          {.name = "crack_log", .type = KeyType::Flag,
           .doc = "every bond break, and every first yield of a softening bond (first damage of a cpm contact), "
                  "written to /cracks",
           .fallback = 1},
      }};
  return t;
}

const KeyTable& run_keys() {
  static const KeyTable t{
      .name = "run",
      .title = "[run]",
      .about = "When the run ends: after `steps`, at `duration`, or at the first [[run.stop]] condition met; at "
               "least one of them.",
      .keys = {
          {.name = "steps", .type = KeyType::Integer, .range = Range::closed(0, 1e15), .doc = "stop after this many steps; 0: no limit",
           .fallback = 0},
          {.name = "duration",
           .unit = Unit::Time,
           .range = Range::non_negative(),
           .doc = "stop at this simulated time; 0: no limit",
           .fallback = 0},
      }};
  return t;
}

const KeyTable& stop_keys() {
  static const KeyTable t{
      .name = "run.stop",
      .title = "[[run.stop]]",
      .about = "A condition that ends the run: a history crossing a value, or falling after its peak.",
      .keys = {
          {.name = "quantity", .type = KeyType::Text, .need = Need::Required, .doc = "a history name"},
          {.name = "below", .doc = "stop when the history falls below this (SI)"},
          {.name = "above", .doc = "stop when it rises above this (SI)"},
          {.name = "post_peak_fraction",
           .range = Range{0.0, 1.0, true, true},
           .doc = "stop when its magnitude falls to this fraction of the largest reached (a load may be a "
                  "negative reaction)"},
          {.name = "after_time",
           .unit = Unit::Time,
           .range = Range::non_negative(),
           .doc = "not before this time",
           .fallback = 0},
      },
      .alternatives = {{.keys = {"below", "above", "post_peak_fraction"}, .one_required = true}}};
  return t;
}

const KeyTable& summary_keys() {
  using P = SummarySpec;
  static const KeyTable t = key_table<P>(
      "summary", "[[summary]]", "A number of `summary`: a reduction of one history.",
      {
          bound(&P::name, {.name = "name", .need = Need::Required, .doc = "its name in summary's JSON"}),
          bound(&P::of, {.name = "of", .need = Need::Required, .doc = "a history name"}),
          bound(&P::reduce, {.name = "reduce",
                            .need = Need::Required,
                            .doc = "max, min, final, initial, time_of_max, duration_positive (time the series is "
                                   "> 0, crossings interpolated), final_over_initial (|final|/|initial|), "
                                   "mean_final_10 (mean over the last 10 % of rows)",
                            .words = {"max", "min", "final", "initial", "time_of_max", "duration_positive",
                                      "final_over_initial", "mean_final_10"}}),
      });
  return t;
}

const KeyTable& output_keys() {
  using P = Scene;
  static const KeyTable t = key_table<P>(
      "output", "[output]", "What the output file holds, and how often.",
      {
          bound(&P::history_every, {.name = "history_every",
                                   .range = Range::closed(1, 1e12),
                                   .doc = "steps between history rows"}),
          bound(&P::frame_every, {.name = "frame_every",
                                 .range = Range::closed(0, 1e12),
                                 .doc = "steps between frames; 0: `frames` frames spread over the run"}),
          bound(&P::frames, {.name = "frames",
                            .range = Range::closed(2, 1e6),
                            .doc = "with frame_every = 0: frames spread evenly over the run's steps or duration "
                                   "(in steps of the timestep at its start), and at least one every 20 history rows "
                                   "where a stop condition may end it sooner; never more than 1 GiB of frames over "
                                   "its steps or duration; 2: only the first and the last"}),
          bound(&P::frame_contacts,
               {.name = "contacts",
                .doc = "each frame's contacts between particles (/contacts: the pair, its normal and shear force, "
                       "bond and branch vector; what ParaView and report draw as force chains); the force pass "
                       "then keeps each pair's force, 24 bytes per pair (2D: 16). No effect on rigid cells"}),
          bound(&P::checkpoint_every, {.name = "checkpoint_every",
                                      .range = Range::closed(0, 1e12),
                                      .doc = "steps between checkpoints; 0: every 60 s of wall time"}),
          bound(&P::guard_every,
               {.name = "guard_every", .range = Range::closed(1, 1e9), .doc = "steps between stability checks"}),
          bound(&P::xy_plots, {.name = "xy_plots", .doc = "\"x:y;x2:y2\": history pairs drawn by report"}),
      });
  return t;
}

namespace {

using namespace scene_read;

void read_phases(const Table& root, Scene& s) {
  for (const Table& t : tables_of(root, phases_keys())) {
    const PhaseSpec p = read_keys<PhaseSpec>(t, phases_keys());
    const KeyReader k(t, phases_keys());
    for (const auto& q : s.phases)
      if (q.name == p.name) k.fail("name", "phase names must be unique");
    s.phases.push_back(p);
    t.finish();
  }
  if (s.phases.empty())
    throw InputError(s.file + ": missing [[phases]]: at least one phase with a name and a density (kg/m3)");
}

void read_contacts(const Table& root, Scene& s) {
  for (const Table& t : tables_of(root, contacts_keys())) {
    const KeyReader k(t, contacts_keys());
    std::vector<std::string> names;
    for (const auto& p : s.phases) names.push_back(p.name);
    ContactSpec c;
    const std::string pa = k.choice("phase_a", names), pb = k.choice("phase_b", names, pa);
    c.phase_a = static_cast<int>(std::find(names.begin(), names.end(), pa) - names.begin());
    c.phase_b = static_cast<int>(std::find(names.begin(), names.end(), pb) - names.begin());
    c.model = read_contact_model(k, k.choice("model", contact_model_names()), s.dimension);
    for (const auto& o : s.contacts)
      if ((o.phase_a == c.phase_a && o.phase_b == c.phase_b) || (o.phase_a == c.phase_b && o.phase_b == c.phase_a))
        k.fail("phase_b", "a contact model for this pair of phases is already given");
    s.contacts.push_back(std::move(c));
    t.finish();
  }
  if (s.contacts.empty())
    throw InputError(s.file + ": missing [[contacts]]: the contact model between phases (model = " +
                     "\"linear\" or \"hertz_mindlin\", phase_a, phase_b and the model's parameters)");
}

void read_bonds(const Table& root, Scene& s) {
  if (auto t = optional_table_of(root, bonds_keys())) {
    const KeyReader k(*t, bonds_keys());
    s.bond_tolerance = k.number("gap_tolerance");
    s.crack_log = k.boolean("crack_log");
    t->finish();
  }
}

void read_run(const Table& root, Scene& s) {
  const Table t = table_of(root, run_keys());
  const KeyReader k(t, run_keys());
  s.steps = k.integer("steps");
  s.duration = k.number("duration");
  for (const Table& st : tables_of(t, stop_keys())) {
    const KeyReader ks(st, stop_keys());
    StopSpec x;
    x.quantity = ks.string("quantity");
    const int given = ks.has("below") + ks.has("above") + ks.has("post_peak_fraction");
    if (given != 1) ks.fail("quantity", "give exactly one of 'below', 'above', 'post_peak_fraction'");
    if (ks.has("below")) x.kind = StopSpec::Kind::Below, x.value = ks.number("below");
    if (ks.has("above")) x.kind = StopSpec::Kind::Above, x.value = ks.number("above");
    if (ks.has("post_peak_fraction"))
      x.kind = StopSpec::Kind::PostPeak, x.value = ks.number("post_peak_fraction");
    x.after_time = ks.number("after_time");
    s.stops.push_back(x);
    st.finish();
  }
  if (s.steps == 0 && s.duration == 0 && s.stops.empty())
    k.fail("steps", "the run needs an end: 'steps', 'duration' or a [[run.stop]] condition");
  t.finish();
  for (const Table& st : tables_of(root, summary_keys())) {
    s.summaries.push_back(read_keys<SummarySpec>(st, summary_keys()));
    st.finish();
  }
}

void read_output(const Table& root, Scene& s) {
  if (auto t = optional_table_of(root, output_keys())) {
    read_bound_keys(*t, output_keys(), &s);
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
  auto tabs = tables_of(table_of(root, run_keys()), stop_keys());
  for (std::size_t i = 0; i < s.stops.size(); ++i)
    if (!known(s.stops[i].quantity))
      KeyReader(tabs[i], stop_keys()).fail("quantity", "not a history of this scene; recorded: " + list);
  auto sums = tables_of(root, summary_keys());
  for (std::size_t i = 0; i < s.summaries.size(); ++i)
    if (!known(s.summaries[i].of))
      KeyReader(sums[i], summary_keys()).fail("of", "not a history of this scene; recorded: " + list);
}

}  // namespace

namespace {

// A misspelt table ([[wall]] for [[walls]]) would be found only once the whole scene is read, after the tables that
// name its entries have failed for want of them ("'load' is not the name of a wall"): it is named first.
void refuse_misspelt_tables(const Table& root) {
  std::vector<std::string> names;  // the keys and tables a scene's top level may hold
  for (const Key& key : scene_keys().keys) names.emplace_back(key.name);
  // The tables of the top level: those named without a dot, but for the models' own (their keys sit in
  // [[contacts]] entries) and the rigid cells' facet law and specimen (in [[contacts]] and [specimen]).
  std::vector<std::string_view> nested{rigid_cell::facet_law_keys().name, cell_specimen_keys().name};
  for (const KeyTable* m : contact_model_keys()) nested.push_back(m->name);
  for (const KeyTable* t : all_key_tables())
    if (t != &scene_keys() && t->name.find('.') == std::string_view::npos &&
        std::find(nested.begin(), nested.end(), t->name) == nested.end())
      names.emplace_back(t->name);
  root.refuse_misspellings(names);
}

}  // namespace

Scene read_scene(const TomlDoc& doc, const std::string& file) {
  Scene s;
  s.file = file;
  s.text = doc.text();
  const Table root = doc.root();
  refuse_misspelt_tables(root);
  const KeyReader k(root, scene_keys());
  s.dimension = static_cast<int>(k.integer("dimension"));
  s.seed = static_cast<std::uint64_t>(k.integer("seed"));
  s.title = k.string("title");
  read_phases(root, s);
  if (root.has(std::string(rigid_cell_keys().key()))) {
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
  s.warnings = doc.warnings();
  return s;
}

}  // namespace mc
