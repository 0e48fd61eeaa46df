#include "engine/summary.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "engine/errors.hpp"
#include "engine/h5_file.hpp"
#include "engine/scene.hpp"
#include "engine/toml_reader.hpp"

namespace mc {

namespace {

std::string num(double x) {
  if (!std::isfinite(x)) return "null";
  char b[32];
  std::snprintf(b, sizeof b, "%.10g", x);
  return b;
}

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

std::string summary_json(const std::string& output_file) {
  const H5File f(output_file, H5File::Mode::ReadOnly);
  if (!f.has_attr("/", "format") || f.attr_string("/", "format") != "mesocrack-1")
    throw IoError(output_file + ": not a mesocrack output file (no format attribute 'mesocrack-1')");
  const Scene scene = read_scene(TomlDoc::parse_text(f.read_string("/scene"), output_file + ":/scene"), output_file);
  std::map<std::string, std::vector<double>> h;
  if (f.exists("/history"))
    for (const auto& n : f.list("/history")) h[n] = f.read_doubles("/history/" + n);
  const auto& t = h["time"];
  std::ostringstream o;
  o << "{\n  \"file\": " << quote(output_file) << ",\n  \"title\": " << quote(scene.title)
    << ",\n  \"dimension\": " << scene.dimension << ",\n  \"status\": " << quote(f.attr_string("/", "status"))
    << ",\n  \"status_message\": " << quote(f.attr_string("/", "status_message"))
    << ",\n  \"particles\": " << f.rows("/specimen/radius")
    << ",\n  \"steps\": " << num(h["step"].empty() ? 0.0 : h["step"].back())
    << ",\n  \"time\": " << num(t.empty() ? 0.0 : t.back()) << ",\n  \"history_rows\": " << t.size();
  o << ",\n  \"results\": {";
  for (std::size_t i = 0; i < scene.summaries.size(); ++i) {
    const SummarySpec& s = scene.summaries[i];
    o << (i ? "," : "") << "\n    " << quote(s.name) << ": " << num(reduce(s.reduce, t, h[s.of]));
  }
  o << (scene.summaries.empty() ? "}" : "\n  }") << ",\n  \"final\": {";
  bool first = true;
  for (const auto& [name, y] : h) {
    o << (first ? "" : ",") << "\n    " << quote(name) << ": " << num(y.empty() ? kNaN : y.back());
    first = false;
  }
  o << (first ? "}" : "\n  }") << "\n}\n";
  return o.str();
}

}  // namespace mc
