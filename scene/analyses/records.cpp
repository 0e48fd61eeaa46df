#include "scene/analyses/records.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <sstream>

#include "scene/json.hpp"

namespace mc {

bool passed_peak(const std::vector<double>& y, std::size_t peak, std::size_t end) {
  const double top = std::abs(y.at(peak));
  for (std::size_t k = peak + 1; k < std::min(end, y.size()); ++k)
    if (std::abs(y[k]) <= (1 - kPeakDrop) * top) return true;
  return false;
}

std::string units_json(const std::vector<std::pair<std::string, std::string>>& units) {
  std::ostringstream o;
  o << "{";
  for (std::size_t k = 0; k < units.size(); ++k)
    o << (k ? ", " : "") << json_quote(units[k].first) << ": " << json_quote(units[k].second);
  o << "}";
  return o.str();
}

std::string pair_name(const std::vector<std::string>& names, int a, int b) {
  auto name = [&](int k) { return k >= 0 && k < int(names.size()) ? names[k] : "phase" + std::to_string(k); };
  return a <= b ? name(a) + "-" + name(b) : name(b) + "-" + name(a);
}

std::string crack_counts_json(const std::vector<LoggedCrack>& cracks, double until,
                              const std::vector<std::string>& names) {
  std::map<std::string, std::array<long, 3>> n;  // tensile breaks, shear breaks, first yields
  for (const LoggedCrack& c : cracks) {
    if (c.time > until) continue;
    auto& k = n[pair_name(names, c.phase_a, c.phase_b)];
    ++k[c.kind == CrackKind::Yield ? 2 : c.mode == CrackMode::Shear ? 1 : 0];
  }
  std::ostringstream o;
  o << "{";
  bool first = true;
  for (const auto& [pair, k] : n) {
    o << (first ? "" : ",") << "\n      " << json_quote(pair) << ": {\"tensile_breaks\": " << k[0]
      << ", \"shear_breaks\": " << k[1] << ", \"first_yields\": " << k[2] << "}";
    first = false;
  }
  o << (first ? "}" : "\n    }");
  return o.str();
}

// Boundary work: the walls' and the held degrees of freedom's (a loading point, a pulled group; fixed supports do
// none).
std::string energy_json(const Histories& h, double area, const std::string& g_name, const std::string& area_name) {
  const char* names[] = {"energy.boundary_work",    "energy.body_work",        "energy.strain",
                         "energy.kinetic",          "energy.dissipated_bonds", "energy.dissipated_contacts",
                         "energy.dissipated_local", "energy.residual"};
  for (const char* n : names)
    if (!h.count(n) || h.at(n).empty()) return "null";
  const std::vector<double>& work = h.at("energy.boundary_work");
  const std::vector<double>& residual = h.at("energy.residual");
  // |residual| / work at every recorded row once the work is 1 % of its final value (before, both are noise).
  double worst = 0;
  for (std::size_t k = 0; k < work.size(); ++k)
    if (work[k] >= 0.01 * work.back()) worst = std::max(worst, std::abs(residual[k]) / work[k]);
  std::ostringstream o;
  o << "{";
  for (const char* n : names)
    o << "\n      " << json_quote(std::string(n).substr(7)) << ": " << json_number(h.at(n).back()) << ",";
  o << "\n      \"worst_residual_over_work\": " << json_number(worst) << ",\n      " << json_quote(g_name) << ": "
    << json_number(h.at("energy.dissipated_bonds").back() / area)
    << ",\n      \"definition\": \"final values [J, simulated thickness]; worst |residual|/work over the rows where "
       "the work is at least 1 % of its final value; "
    << g_name << " = energy dissipated by bond breakage and softening over the " << area_name << " area\"\n    }";
  return o.str();
}

}  // namespace mc
