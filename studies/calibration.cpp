#include "studies/calibration.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "engine/errors.hpp"
#include "scene/model_registry.hpp"
#include "scene/toml_reader.hpp"
#include "scene/scene.hpp"
#include "studies/calibration_run.hpp"
#include "studies/model_code.hpp"
#include "studies/ranks.hpp"

namespace mc {

using namespace calibration;

CalibrationTarget parse_targets(const std::string& text) {
  // Each "name=value" becomes a TOML line, so units and ranges are checked by the scene reader's own rules.
  std::string toml;
  std::istringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    const auto eq = item.find('=');
    if (eq == std::string::npos)
      throw InputError("--target '" + item + "': give name=value, e.g. E=30GPa,nu=0.2,ucs=40MPa");
    auto trim = [](std::string s) {
      s.erase(0, s.find_first_not_of(" \t"));
      s.erase(s.find_last_not_of(" \t") + 1);
      return s;
    };
    const std::string key = trim(item.substr(0, eq)), value = trim(item.substr(eq + 1));
    const bool number = !value.empty() && value.find_first_not_of("0123456789.eE+-") == std::string::npos;
    toml += key + " = " + (number ? value : "\"" + value + "\"") + "\n";
  }
  try {
    const TomlDoc doc = TomlDoc::parse_text(toml, "--target");
    const Table t = doc.root();
    CalibrationTarget c;
    c.modulus = t.number("E", Unit::Pressure, Range::positive(), kNaN);
    c.poisson = t.number("nu", Unit::None, Range{0.0, 0.5, true, true}, kNaN);
    c.ucs = t.number("ucs", Unit::Pressure, Range::positive(), kNaN);
    c.tensile = t.number("ft", Unit::Pressure, Range::positive(), kNaN);
    c.compressive = t.number("fc", Unit::Pressure, Range::positive(), kNaN);
    c.fracture_energy = t.number("Gf", Unit::EnergyPerArea, Range::positive(), kNaN);
    c.concrete_class = t.string("class", "");
    c.aggregate = t.string("aggregate", c.aggregate);
    t.finish();
    if (!c.concrete_class.empty() || t.has("aggregate")) model_code_concrete(c.concrete_class, c.aggregate);
    if (std::isnan(c.modulus) && std::isnan(c.poisson) && std::isnan(c.ucs) && std::isnan(c.tensile) &&
        std::isnan(c.compressive) && std::isnan(c.fracture_energy) && c.concrete_class.empty())
      throw InputError("--target '" + text + "': name at least one of E, nu, ucs, ft, fc, Gf, or a class");
    return c;
  } catch (const InputError& e) {
    throw InputError(std::string(e.what()) +
                     " (allowed: E [Pa], nu in (0, 0.5), ucs, ft, fc [Pa], Gf [N/m], class=C30/37 (fib Model Code "
                     "2010), aggregate; which fit: mesocrack calibrate --help)");
  }
}

namespace {

// The targets of `t` not given by value that a model can fit, from its concrete class; said on `log`.
CalibrationTarget with_class_values(CalibrationTarget t, bool cpm, bool softening, bool tension, bool compression_run,
                                    std::FILE* log) {
  if (t.concrete_class.empty()) return t;
  const ModelCodeConcrete m = model_code_concrete(t.concrete_class, t.aggregate);
  std::string took;
  auto take = [&](double& target, double value, bool fits, const char* name) {
    if (!fits || !std::isnan(target)) return;
    target = value;
    took += std::string(took.empty() ? "" : ", ") + name;
  };
  take(t.modulus, m.e_ci, true, "E = E_ci");
  take(t.poisson, m.poisson, true, "nu");
  take(t.tensile, m.f_ctm, cpm || tension, "ft = f_ctm");
  take(t.ucs, m.f_cm, !cpm && !tension, "ucs = f_cm");
  take(t.compressive, m.f_cm, cpm && compression_run, "fc = f_cm");
  take(t.fracture_energy, m.fracture_energy, softening, "Gf = G_F");
  std::fprintf(log,
               "%s (fib Model Code 2010, %s aggregate): E_ci %.4g GPa, nu %.2g, f_ctm %.3g MPa, f_cm %.4g MPa, "
               "G_F %.4g N/m; this scene's model fits %s\n",
               m.name.c_str(), m.aggregate.c_str(), m.e_ci * 1e-9, m.poisson, m.f_ctm * 1e-6, m.f_cm * 1e-6,
               m.fracture_energy, took.empty() ? "none of them beside the targets given" : took.c_str());
  return t;
}

}  // namespace

// Which procedure: the scene's calibrated [[contacts]] entry decides; the procedure refuses targets it cannot reach.
CalibrationResult calibrate(const std::string& scene_file, const std::vector<std::string>& overrides,
                            const CalibrationTarget& target, const CalibrationOptions& options, std::FILE* log) {
  if (options.output.empty()) throw InputError("calibrate: give the calibrated scene's file with -o CALIBRATED.toml");
  const TomlDoc doc = TomlDoc::load(scene_file, overrides);
  const int parallel = contacts_entry(doc, ParallelBond::name), softening = contacts_entry(doc, SofteningBond::name),
            cpm = contacts_entry(doc, Cpm::name);
  const Scene scene = read_scene(doc, scene_file);
  if (scene.rigid_cell) {
    const CalibrationTarget t = with_class_values(target, false, true, true, false, log);
    CalibrationOptions o = options;
    if (std::isnan(o.tolerance)) o.tolerance = 0.05;
    return calibrate_rigid_cell(scene_file, overrides, contacts_entry(doc, "facet_damage"), t, o, log);
  }
  const int found = (parallel >= 0) + (softening >= 0) + (cpm >= 0);
  if (found != 1)
    throw InputError(scene_file +
                     ": calibrate needs one [[contacts]] entry with model = \"parallel_bond\" (Tang §6.3 in "
                     "compression, ch. 7 in tension), model = \"softening_bond\" (Tang ch. 7, in tension) or "
                     "model = \"cpm\" (Šmilauer, \"Parameter calibration\")" +
                     (found > 1 ? "; this scene has several: calibrate each material in its own scene" : ""));
  const auto* u = scene.analysis<UniaxialAnalysis>();
  const CalibrationTarget t = with_class_values(target, cpm >= 0, softening >= 0, u && u->tension,
                                                !options.compression_scene.empty(), log);
  CalibrationOptions o = options;
  if (cpm >= 0) {
    auto refuse = [](double value, const std::string& name, const std::string& why) {
      if (!std::isnan(value))
        throw InputError("--target " + name + ": not a target for a cpm scene (its targets: E, nu, ft, fc)" + why);
    };
    refuse(t.ucs, "ucs", "; its compressive strength is fc");
    refuse(t.fracture_energy, "Gf", "; its G_f follows from relative_ductility, which calibrate holds");
    if (std::isnan(o.tolerance)) o.tolerance = 0.03;
    return calibrate_cpm(scene_file, overrides, cpm, t, o, log);
  }
  if (std::isnan(o.tolerance)) o.tolerance = 0.05;
  return calibrate_bonded(scene_file, overrides, std::max(parallel, softening), t, o, log);
}

namespace calibration {

void RunCost::ran(double seconds, double k, double strain) {
  if (first_ == 0) first_ = seconds;
  last_ = seconds, k_ = k, strain_ = strain;
}

bool RunCost::beyond_bound(double k, double strain, const char* kind, std::FILE* log) const {
  if (first_ == 0) return false;
  const double predicted = last_ * std::sqrt(k / k_) * strain / strain_;
  const double bound = std::max(kMostGrowth * first_, kLeastBoundSeconds);
  if (predicted <= bound) return false;
  std::fprintf(log,
               "stopped: the next %s run would take about %.3g s (stiffness %.3g times, strain reach %.3g times the "
               "last's), beyond %.3g s, %g times the first: the targets are likely beyond what this specimen and "
               "model can give; check them, or start nearer to them\n",
               kind, predicted, k / k_, strain / strain_, bound, kMostGrowth);
  return true;
}

std::string run_file(const std::string& output, int iteration, const std::string& suffix) {
  const std::filesystem::path out(output);
  return (out.parent_path() / (out.stem().string() + "_it" + std::to_string(iteration) + suffix + ".h5")).string();
}

void write_scene(const std::string& scene_file, const std::vector<std::string>& overrides, const std::string& output,
                 const std::string& note) {
  if (!Ranks::world().root()) return;  // every rank of an MPI launch holds the same scene: rank 0 writes it
  const std::string text = TomlDoc::load(scene_file, overrides).text();
  const std::string tmp = output + ".tmp";
  {
    std::ofstream f(tmp);
    if (!note.empty()) f << "# " << note << "\n";
    f << text;
    if (!f) throw IoError(tmp + ": cannot write the calibrated scene");
  }
  std::filesystem::rename(tmp, output);
}

}  // namespace calibration

}  // namespace mc
