#include "scene/key_reference.hpp"

#include <cmath>
#include <sstream>

#include "engine/errors.hpp"
#include "rigid_cell/facet_law.hpp"  // the facet law's table, beside its parameters
#include "scene/analysis.hpp"
#include "scene/key_reader.hpp"
#include "scene/model_registry.hpp"
#include "scene/scene_keys.hpp"
#include "scene/units.hpp"

namespace mc {

std::vector<const KeyTable*> all_key_tables() {
  std::vector<const KeyTable*> t = {&scene_keys(), &phases_keys(), &contacts_keys()};
  for (const KeyTable* m : contact_model_keys()) t.push_back(m);
  for (const KeyTable* k :
       {&bonds_keys(), &specimen_keys(), &specimen_particles_keys(), &specimen_cuts_keys(), &specimen_regions_keys(),
        &mesostructure_keys(), &grading_ranges_keys(), &keep_out_keys(), &walls_keys(), &groups_keys(),
        &physics_keys(), &timestep_keys(), &measure_keys(), &probes_keys(), &wall_strains_keys(), &run_keys(),
        &stop_keys(), &summary_keys(), &output_keys()})
    t.push_back(k);
  for (const KeyTable* a : analysis_keys()) t.push_back(a);
  for (const KeyTable* k : {&rigid_cell_keys(), &rigid_cell::facet_law_keys(), &cell_specimen_keys(),
                            &random_field_keys(), &opening_control_keys(), &cell_dynamics_keys(), &stress_wave_keys(),
                            &sections_keys(), &strain_box_keys(), &fibres_keys()})
    t.push_back(k);
  return t;
}

namespace {

std::string text_of(std::string_view s) { return std::string(s); }

// What a key takes: "number [Pa], value > 0", "true or false", "`box`, `disc`".
std::string value_of(const Key& k) {
  const std::string unit = detail::si_unit(k.unit);
  const std::string in = unit.empty() ? "" : " [" + unit + "]";
  const bool ranged = k.range.lo > -kInf || k.range.hi < kInf;
  std::string range = ranged ? "; " + describe(k.range) : "";
  if (k.range.usual_lo != 0 || k.range.usual_hi != 0)
    range += "; usually " + detail::format_number(k.range.usual_lo) + " to " + detail::format_number(k.range.usual_hi);
  switch (k.words.empty() ? k.type : KeyType::Word) {
    case KeyType::Real:
      return (k.unit == Unit::Angle ? "angle" : "number") + in + range;
    case KeyType::Integer:
      return "whole number" + range;
    case KeyType::Flag:
      return "true or false";
    case KeyType::Word: {
      std::string w;
      for (const auto& x : k.words) w += (w.empty() ? "`" : ", `") + text_of(x) + "`";
      return w.empty() ? "a name" : w;
    }
    case KeyType::Text:
      return "text";
    case KeyType::Reals:
      return "list of numbers" + in + range;
    case KeyType::Scatter:
      return "number" + in + "; value > 0";
  }
  return "";
}

// The default as a scene would write it, "required", or "none" (absent: not given, not computed).
std::string default_of(const KeyTable& t, const Key& k) {
  if (k.need == Need::Required) return "required";
  if (!k.shown_default.empty()) return text_of(k.shown_default);
  if (k.fallback) return k.type == KeyType::Flag ? (*k.fallback != 0 ? "true" : "false") : detail::format_number(*k.fallback);
  if (k.by_hand() || !t.defaults) return "none";
  if (k.type == KeyType::Reals && member<std::vector<double>>(t.defaults, k).empty()) return "none";
  if (k.type == KeyType::Text && member<std::string>(t.defaults, k).empty()) return "\"\"";
  if (k.type == KeyType::Real && std::isnan(member<double>(t.defaults, k))) return "none";
  return key_value_text(k, t.defaults);
}

struct Row {
  std::string key, value, fallback, doc;
};

// The table's rows: a Scatter key is three (the mean or scale, its spread, its Weibull shape).
std::vector<Row> rows_of(const KeyTable& t) {
  std::vector<Row> rows;
  for (const Key& k : t.keys) {
    const std::string name = text_of(k.name), when = k.when.empty() ? "" : " (" + text_of(k.when) + ")";
    if (k.type == KeyType::Scatter) {
      const std::string unit = detail::si_unit(k.unit);
      rows.push_back({name + when, value_of(k), default_of(t, k), text_of(k.doc) + ": the mean, or the Weibull scale λ"});
      rows.push_back({name + "_std", "number [" + unit + "]; value >= 0", "0",
                      "its spread: drawn per bond from a normal distribution truncated to > 0"});
      rows.push_back({name + "_weibull_shape", "number; value > 0", "none",
                      "or from a Weibull distribution of this shape, Tang (8.4); not with " + name + "_std"});
      continue;
    }
    rows.push_back({name + when, value_of(k), default_of(t, k), text_of(k.doc)});
  }
  return rows;
}

std::string alternatives_of(const KeyTable& t) {
  std::string out;
  for (const Alternatives& a : t.alternatives) {
    std::string keys;
    for (const auto& k : a.keys) keys.append(keys.empty() ? "`" : ", `").append(text_of(k)).append("`");
    out.append(a.one_required ? "Exactly one of " : "At most one of ").append(keys).append(".");
    if (!a.why.empty()) out.append(" ").append(text_of(a.why)).append(".");
    out.append("\n");
  }
  return out;
}

// Where the table's keys are on the command line: "walls[0].", "contacts[0].", "run.", "" (the top level).
std::string set_path(const KeyTable& t) {
  if (t.title.rfind("[[contacts]]", 0) == 0) return "contacts[0].";
  if (t.title.rfind("Top level", 0) == 0) return "";
  std::string path = text_of(t.name);
  if (!t.location.empty()) path = text_of(t.location);
  return path + (t.title.rfind("[[", 0) == 0 ? "[0]." : ".");
}

// A model's example entry, when its table gives examples.
std::string example_of(const KeyTable& t) {
  const std::string lines = example_entry(t);
  if (lines.empty()) return "";
  const bool model = t.title.rfind("[[contacts]]", 0) == 0;
  std::string head = model ? "[[contacts]]\nmodel = \"" + text_of(t.name) + "\"\nphase_a = \"concrete\"\n" : "";
  return "```toml\n" + head + lines + "```\n";
}

std::string escaped(std::string s) {  // for a Markdown table cell
  std::string out;
  for (const char c : s) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

}  // namespace

std::string key_table_list() {
  std::ostringstream o;
  for (const KeyTable* t : all_key_tables()) {
    o << text_of(t->name);
    for (std::size_t n = t->name.size(); n < 28; ++n) o << ' ';
    o << text_of(t->title) << "\n";
  }
  return o.str();
}

std::string key_table_text(const std::string& name) {
  std::string names;
  for (const KeyTable* t : all_key_tables()) {
    names += (names.empty() ? "" : ", ") + text_of(t->name);
    if (t->name != name) continue;
    std::ostringstream o;
    o << text_of(t->title) << "\n\n" << text_of(t->about) << "\n\n";
    for (const Row& r : rows_of(*t))
      o << "  " << r.key << "\n      " << r.value << "; default: " << r.fallback << "\n      " << r.doc << "\n";
    const std::string alt = alternatives_of(*t);
    if (!alt.empty()) o << "\n" << alt;
    o << "\nA number with a unit (\"30 GPa\", \"5 mm/s\") is converted to SI; one without is SI, and warned "
         "about when it lies more than 100 times outside the usual values of its key or kind (docs/keys.md).\n";
    const std::string example = example_of(*t);
    if (!example.empty()) o << "\nExample:\n" << example;
    return o.str();
  }
  throw InputError("keys: '" + name + "' is not a table of a scene file; allowed: " + names);
}

std::string key_reference_markdown() {
  std::ostringstream o;
  o << "# Scene keys\n\n"
    << "Every key a scene file may hold, table by table, as the key tables in the code declare them (this page is "
       "written by `mesocrack keys --markdown`; `mesocrack keys TABLE` prints one table). Numbers are SI; a number "
       "may also be a string with a unit of the key's kind (`\"30 GPa\"`, `\"5 mm/s\"`, `\"45 deg\"`). A number "
       "written without a unit is read as SI, with a warning when it lies more than 100 times outside the usual "
       "values of its key (stated below as \"usually\") or of its kind (a length 1 µm to 1 m, a pressure 10 kPa to "
       "100 GPa, a velocity 10 nm/s to 100 m/s, a density 300 to 20 000 kg/m3, a force 1 mN to 10 MN, a time 1 ns "
       "to 1 000 s, a fracture energy 1 to 10 000 J/m2; an angle: beyond a turn). A key "
       "given on the command line (`--set table.key=value`, `--set contacts[0].friction=0.3`) is read as if it "
       "were in the file. Unknown keys are errors.\n\n";
  for (const KeyTable* t : all_key_tables()) {
    o << "## " << text_of(t->title) << "\n\n" << text_of(t->about) << "\n\n";
    const std::string first = t->keys.empty() ? "" : text_of(t->keys.front().name);
    o << "`mesocrack keys " << text_of(t->name) << "`; on the command line `--set " << set_path(*t) << first
      << "=…`.\n\n";
    o << "| key | value | default | meaning |\n|---|---|---|---|\n";
    for (const Row& r : rows_of(*t))
      o << "| `" << escaped(r.key.substr(0, r.key.find(' '))) << "`"
        << escaped(r.key.find(' ') == std::string::npos ? "" : r.key.substr(r.key.find(' '))) << " | "
        << escaped(r.value) << " | " << escaped(r.fallback) << " | " << escaped(r.doc) << " |\n";
    const std::string alt = alternatives_of(*t);
    if (!alt.empty()) o << "\n" << alt;
    const std::string example = example_of(*t);
    if (!example.empty()) o << "\n" << example;
    o << "\n";
  }
  return o.str();
}

}  // namespace mc
