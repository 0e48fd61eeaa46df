#include "studies/stored_run.hpp"

#include <algorithm>

#include "engine/errors.hpp"
#include "io/h5_file.hpp"
#include "io/run_output.hpp"
#include "scene/toml_reader.hpp"

namespace mc {

namespace {

// The names in /history's `order` attribute (the scene's order), each a series present in the file with as many
// rows as `time`; IoError naming the file and the entry otherwise. A file lacking them is damaged, or was not
// written by `mesocrack run`. A run killed while it flushed a row (status still "running") may have written the row
// to some series only, or left a chunk unreadable: its histories are read as far as they can be and cut to the
// rows every series holds.
Histories read_histories(const H5File& f, bool killed) {
  const std::string& file = f.path();
  if (!f.exists("/history")) throw IoError(file + ": no /history group: not a complete mesocrack output file");
  const std::string order = f.attr_string("/history", "order");
  Histories h;
  for (std::size_t from = 0; from <= order.size();) {
    const std::size_t to = std::min(order.find(';', from), order.size());
    const std::string name = order.substr(from, to - from);
    const std::string ds = "/history/" + name;  // IoError naming it when it is missing
    if (!name.empty()) h[name] = killed ? f.read_leading_doubles(ds) : f.read_doubles(ds);
    from = to + 1;
  }
  for (const char* needed : {"time", "step"})
    if (!h.count(needed))
      throw IoError(file + ": /history/" + needed +
                    " is not among the recorded histories ('order' attribute of /history)");
  std::size_t rows = h.at("time").size();
  if (killed)
    for (auto& [name, y] : h) rows = std::min(rows, y.size());
  for (auto& [name, y] : h) {
    if (killed) y.resize(rows);
    if (y.size() != rows)
      throw IoError(file + ": /history/" + name + " has " + std::to_string(y.size()) + " rows, /history/time " +
                    std::to_string(rows) + ": the histories are damaged");
  }
  return h;
}

// The crack log (/cracks; none: empty), its tables cut to the shortest (a run killed mid-append, whose tables are read
// as far as they can be).
std::vector<LoggedCrack> read_cracks(const H5File& f, int dimension, bool killed) {
  std::vector<LoggedCrack> out;
  if (!f.exists("/cracks/position")) return out;
  const auto reals = [&](const char* ds) { return killed ? f.read_leading_doubles(ds) : f.read_doubles(ds); };
  const auto ints = [&](const char* ds) { return killed ? f.read_leading_ints(ds) : f.read_ints(ds); };
  const std::vector<double> time = reals("/cracks/time"), pos = reals("/cracks/position");
  const std::vector<std::int64_t> mode = ints("/cracks/mode"), kind = ints("/cracks/kind");
  const std::vector<std::int64_t> pa = ints("/cracks/phase_a"), pb = ints("/cracks/phase_b");
  const std::size_t d = static_cast<std::size_t>(dimension);
  const std::size_t n = std::min({time.size(), pos.size() / d, mode.size(), kind.size(), pa.size(), pb.size()});
  out.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    LoggedCrack& c = out[k];
    c.time = time[k];
    for (std::size_t a = 0; a < d; ++a) c.position[a] = pos[k * d + a];
    c.mode = static_cast<CrackMode>(mode[k]);
    c.kind = static_cast<CrackKind>(kind[k]);
    c.phase_a = static_cast<int>(pa[k]);
    c.phase_b = static_cast<int>(pb[k]);
  }
  return out;
}

// The stored scene, re-read and validated: one this version refuses makes the file unreadable here (a file error).
Scene read_stored_scene(const H5File& f) {
  const std::string& file = f.path();
  try {
    return read_scene(TomlDoc::parse_text(f.read_string("/scene"), file + ":/scene"), file);
  } catch (const InputError& e) {
    throw IoError(file + ": the scene stored in it (/scene) is not valid: " + e.what());
  }
}

}  // namespace

StoredRun read_stored_run(const std::string& output_file) {
  const H5File f(output_file, H5File::Mode::ReadOnly);
  if (!f.has_attr("/", "format") || f.attr_string("/", "format") != "mesocrack-1")
    throw IoError(output_file + ": not a mesocrack output file (no format attribute 'mesocrack-1')");
  StoredRun r;
  const bool killed = killed_run(f);
  r.histories = read_histories(f, killed);
  for (const auto& [name, y] : r.histories)
    r.units[name] = f.has_attr("/history/" + name, "unit") ? f.attr_string("/history/" + name, "unit") : "";
  r.scene = read_stored_scene(f);
  r.cracks = read_cracks(f, r.scene.dimension, killed);
  for (const auto& s : r.scene.summaries)
    if (!r.histories.count(s.of))
      throw IoError(output_file + ": /history/" + s.of + ", which the scene's [[summary]] '" + s.name +
                    "' reduces, is not among the recorded histories");
  r.status = f.attr_string("/", "status");
  r.status_message = f.attr_string("/", "status_message");
  r.particles = static_cast<std::int64_t>(f.rows("/specimen/radius"));
  r.specimen_facts = f.number_attrs("/specimen");
  return r;
}

UniaxialResult uniaxial_result(const std::string& output_file) {
  const StoredRun run = read_stored_run(output_file);
  const auto* u = run.scene.analysis<UniaxialAnalysis>();
  if (!u) throw InputError(output_file + ": the scene declares no [uniaxial] analysis");
  return u->result(run.histories);
}

}  // namespace mc
