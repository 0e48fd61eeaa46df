#include "studies/stored_run.hpp"

#include "engine/errors.hpp"
#include "io/h5_file.hpp"
#include "scene/toml_reader.hpp"

namespace mc {

StoredRun read_stored_run(const std::string& output_file) {
  const H5File f(output_file, H5File::Mode::ReadOnly);
  if (!f.has_attr("/", "format") || f.attr_string("/", "format") != "mesocrack-1")
    throw IoError(output_file + ": not a mesocrack output file (no format attribute 'mesocrack-1')");
  StoredRun r;
  if (f.exists("/history"))
    for (const auto& n : f.list("/history")) r.histories[n] = f.read_doubles("/history/" + n);
  r.scene = read_scene(TomlDoc::parse_text(f.read_string("/scene"), output_file + ":/scene"), output_file);
  r.status = f.attr_string("/", "status");
  r.status_message = f.attr_string("/", "status_message");
  r.particles = static_cast<std::int64_t>(f.rows("/specimen/radius"));
  return r;
}

UniaxialResult uniaxial_result(const std::string& output_file) {
  const StoredRun run = read_stored_run(output_file);
  const auto* u = run.scene.analysis<UniaxialAnalysis>();
  if (!u) throw InputError(output_file + ": the scene declares no [uniaxial] analysis");
  return u->result(run.histories);
}

}  // namespace mc
