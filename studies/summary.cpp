#include "studies/summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "engine/errors.hpp"
#include "io/h5_file.hpp"
#include "scene/scene.hpp"
#include "scene/toml_reader.hpp"

namespace mc {

namespace {


std::string quote(const std::string& s) {
  std::string o = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\', o += c;
    else if (c == '\n') o += "\\n";
    else if (static_cast<unsigned char>(c) < 0x20) o += ' ';
    else o += c;
  }
  return o + "\"";
}

// Total time the series is positive, with the sign changes located by linear interpolation between samples.
double duration_positive(const std::vector<double>& t, const std::vector<double>& y) {
  double total = 0;
  for (std::size_t k = 1; k < y.size(); ++k) {
    const double a = y[k - 1], b = y[k], dt = t[k] - t[k - 1];
    if (a > 0 && b > 0) total += dt;
    else if (a > 0 || b > 0) total += dt * std::max(a, b) / std::abs(b - a);
  }
  return total;
}

double reduce(SummarySpec::Reduce r, const std::vector<double>& t, const std::vector<double>& y) {
  using R = SummarySpec::Reduce;
  if (y.empty()) return kNaN;
  std::size_t imax = 0, imin = 0;
  for (std::size_t k = 1; k < y.size(); ++k) {
    if (y[k] > y[imax]) imax = k;
    if (y[k] < y[imin]) imin = k;
  }
  switch (r) {
    case R::Max: return y[imax];
    case R::Min: return y[imin];
    case R::Final: return y.back();
    case R::Initial: return y.front();
    case R::TimeOfMax: return t[imax];
    case R::DurationPositive: return duration_positive(t, y);
    case R::FinalOverInitial: return std::abs(y.back()) / std::abs(y.front());
    case R::MeanFinal10: {
      const std::size_t from = y.size() - std::max<std::size_t>(1, y.size() / 10);
      double s = 0;
      for (std::size_t k = from; k < y.size(); ++k) s += y[k];
      return s / static_cast<double>(y.size() - from);
    }
  }
  return kNaN;
}

}  // namespace

std::string json_number(double x) {
  if (!std::isfinite(x)) return "null";
  char b[32];
  std::snprintf(b, sizeof b, "%.10g", x);
  return b;
}

// Tang §5.2: the pre-peak curve σ(ε_axial) gives E as the secant between 25 % and 50 % of the peak and ν as
// −Δε_lateral/Δε_axial over the same stretch; UCS (f_c, or in tension f_t) is the peak; the crack-initiation stress is the stress when the
// cracks reach 1 % of their count at the peak. Compression is positive for the stress and the axial strain
// (whatever signs the histories carry), the lateral strain keeps its sign (expansion positive).
UniaxialResult uniaxial_result(const UniaxialSpec& u, std::map<std::string, std::vector<double>>& h) {
  UniaxialResult r;
  std::vector<double> s = h[u.stress], ea = h[u.axial_strain], el(s.size(), 0.0);
  for (const auto& name : u.lateral_strain) {
    const std::vector<double>& y = h[name];
    el.resize(std::min(el.size(), y.size()));
    for (std::size_t k = 0; k < el.size(); ++k) el[k] += y[k] / static_cast<double>(u.lateral_strain.size());
  }
  const std::vector<double>& ct = h["cracks.tensile"];
  const std::vector<double>& cs = h["cracks.shear"];
  const std::size_t n = std::min({s.size(), ea.size(), el.size(), ct.size(), cs.size()});
  if (n < 3) return r;
  for (std::size_t k = 0; k < n; ++k) s[k] = std::abs(s[k]), ea[k] = std::abs(ea[k]);
  std::size_t peak = 0;
  for (std::size_t k = 0; k < n; ++k)
    if (s[k] > s[peak]) peak = k;
  r.ucs = s[peak];
  // The first pre-peak crossing of a stress level, interpolated: returns the fractional row.
  auto crossing = [&](double level) {
    for (std::size_t k = 1; k <= peak; ++k)
      if (s[k] >= level && s[k - 1] < level) return (k - 1) + (level - s[k - 1]) / (s[k] - s[k - 1]);
    return kNaN;
  };
  auto at = [&](const std::vector<double>& y, double row) {
    if (!std::isfinite(row)) return kNaN;
    const auto k = static_cast<std::size_t>(row);
    const double f = row - static_cast<double>(k);
    return k + 1 < n ? y[k] + f * (y[k + 1] - y[k]) : y[k];
  };
  const double r25 = crossing(0.25 * r.ucs), r50 = crossing(0.5 * r.ucs);
  r.modulus = 0.25 * r.ucs / (at(ea, r50) - at(ea, r25));
  // Compression widens the specimen, tension narrows it: ν is the lateral expansion per axial shortening, or
  // the lateral contraction per axial elongation.
  r.poisson = (u.tension ? -1.0 : 1.0) * (at(el, r50) - at(el, r25)) / (at(ea, r50) - at(ea, r25));
  r.strain_at_peak = ea[peak];
  // Cracks: the breaks; in a run without any break but with first yields (a CPM specimen, whose contacts damage
  // without breaking by default), the first yields, i.e. the contacts that started to damage.
  const auto yi = h.find("cracks.yield");
  r.cracks_by_yield = ct[n - 1] + cs[n - 1] == 0 && yi != h.end() && yi->second.size() >= n && yi->second[n - 1] > 0;
  auto cracks = [&](std::size_t k) { return r.cracks_by_yield ? yi->second[k] : ct[k] + cs[k]; };
  r.cracks_at_peak = cracks(peak);
  for (std::size_t k = 0; k <= peak; ++k)
    if (cracks(k) >= std::max(1.0, 0.01 * r.cracks_at_peak)) {
      r.initiation_stress = s[k];
      break;
    }
  r.cracks_tensile = ct[n - 1];
  r.cracks_shear = cs[n - 1];
  if (u.tension) {
    // Šmilauer Fig. 19: the conventional G_f, the area under the σ–ε curve up to where the softening branch falls
    // to 0.2 f_t, times the gauge length (the supports' initial distance): the energy per unit cross-section
    // of a specimen whose crack localises. NaN when the run stopped before 0.2 f_t.
    double area = 0;
    for (std::size_t k = 1; k < n; ++k) {
      const double s0 = s[k - 1], s1 = s[k];
      if (k > peak && s1 <= 0.2 * r.ucs) {
        const double f = s0 > s1 ? (s0 - 0.2 * r.ucs) / (s0 - s1) : 1.0;
        area += 0.5 * (s0 + (s0 + f * (s1 - s0))) * f * (ea[k] - ea[k - 1]);
        r.strain_at_02ft = ea[k - 1] + f * (ea[k] - ea[k - 1]);
        break;
      }
      area += 0.5 * (s0 + s1) * (ea[k] - ea[k - 1]);
    }
    const auto len = h.find("uniaxial.length");
    r.gauge_length = len != h.end() && !len->second.empty() ? len->second.front() : kNaN;
    r.fracture_energy = std::isfinite(r.strain_at_02ft) ? area * r.gauge_length : kNaN;
  }
  return r;
}

namespace {

std::string uniaxial_json(const UniaxialSpec& u, const UniaxialResult& r) {
  if (!std::isfinite(r.ucs)) return "null";
  std::ostringstream o;
  o << "{\n    \"loading\": " << (u.tension ? "\"tension\"" : "\"compression\"");
  o << ",\n    \"E\": " << json_number(r.modulus) << ",\n    \"E_definition\": \"secant between 25 % and 50 % of the peak stress\""
    << ",\n    \"nu\": " << json_number(r.poisson);
  if (u.tension)
    o << ",\n    \"f_t\": " << json_number(r.ucs) << ",\n    \"G_f\": " << json_number(r.fracture_energy)
      << ",\n    \"G_f_definition\": \"area under stress-strain to 0.2 f_t post-peak, times the gauge length\""
      << ",\n    \"gauge_length\": " << json_number(r.gauge_length) << ",\n    \"strain_at_0.2_f_t\": " << json_number(r.strain_at_02ft);
  else
    o << ",\n    \"ucs\": " << json_number(r.ucs) << ",\n    \"f_c\": " << json_number(r.ucs);
  o << ",\n    \"strain_at_peak\": " << json_number(r.strain_at_peak)
    << ",\n    \"crack_initiation_stress\": " << json_number(r.initiation_stress)
    << ",\n    \"crack_initiation_ratio\": " << json_number(r.initiation_stress / r.ucs)
    << ",\n    \"cracks_counted\": " << (r.cracks_by_yield ? "\"first yields\"" : "\"breaks\"")
    << ",\n    \"cracks_at_peak\": " << json_number(r.cracks_at_peak)
    << ",\n    \"cracks_tensile\": " << json_number(r.cracks_tensile) << ",\n    \"cracks_shear\": " << json_number(r.cracks_shear) << "\n  }";
  return o.str();
}

// The scene stored in a mesocrack output file, and its histories.
Scene stored_scene(const H5File& f, const std::string& output_file, std::map<std::string, std::vector<double>>& h) {
  if (!f.has_attr("/", "format") || f.attr_string("/", "format") != "mesocrack-1")
    throw IoError(output_file + ": not a mesocrack output file (no format attribute 'mesocrack-1')");
  if (f.exists("/history"))
    for (const auto& n : f.list("/history")) h[n] = f.read_doubles("/history/" + n);
  return read_scene(TomlDoc::parse_text(f.read_string("/scene"), output_file + ":/scene"), output_file);
}

}  // namespace

UniaxialResult uniaxial_result(const std::string& output_file) {
  const H5File f(output_file, H5File::Mode::ReadOnly);
  std::map<std::string, std::vector<double>> h;
  const Scene scene = stored_scene(f, output_file, h);
  if (scene.uniaxial.stress.empty()) throw InputError(output_file + ": the scene declares no [uniaxial] analysis");
  return uniaxial_result(scene.uniaxial, h);
}

std::string summary_json(const std::string& output_file) {
  const H5File f(output_file, H5File::Mode::ReadOnly);
  std::map<std::string, std::vector<double>> h;
  const Scene scene = stored_scene(f, output_file, h);
  const auto& t = h["time"];
  std::ostringstream o;
  o << "{\n  \"file\": " << quote(output_file) << ",\n  \"title\": " << quote(scene.title)
    << ",\n  \"dimension\": " << scene.dimension << ",\n  \"status\": " << quote(f.attr_string("/", "status"))
    << ",\n  \"status_message\": " << quote(f.attr_string("/", "status_message"))
    << ",\n  \"particles\": " << f.rows("/specimen/radius")
    << ",\n  \"steps\": " << json_number(h["step"].empty() ? 0.0 : h["step"].back())
    << ",\n  \"time\": " << json_number(t.empty() ? 0.0 : t.back()) << ",\n  \"history_rows\": " << t.size()
    << ",\n  \"density_scaling\": " << json_number(scene.density_scaling);  // 1: off; else the inertia was scaled by it
  o << ",\n  \"results\": {";
  for (std::size_t i = 0; i < scene.summaries.size(); ++i) {
    const SummarySpec& s = scene.summaries[i];
    o << (i ? "," : "") << "\n    " << quote(s.name) << ": " << json_number(reduce(s.reduce, t, h[s.of]));
  }
  o << (scene.summaries.empty() ? "}" : "\n  }");
  if (!scene.uniaxial.stress.empty()) o << ",\n  \"uniaxial\": " << uniaxial_json(scene.uniaxial, uniaxial_result(scene.uniaxial, h));
  o << ",\n  \"final\": {";
  bool first = true;
  for (const auto& [name, y] : h) {
    o << (first ? "" : ",") << "\n    " << quote(name) << ": " << json_number(y.empty() ? kNaN : y.back());
    first = false;
  }
  o << (first ? "}" : "\n  }") << "\n}\n";
  return o.str();
}

}  // namespace mc
