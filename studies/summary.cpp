#include "studies/summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "scene/analyses/records.hpp"
#include "scene/analysis.hpp"
#include "scene/json.hpp"
#include "studies/stored_run.hpp"

namespace mc {

namespace {

// Total time the series is positive, with the sign changes located by linear interpolation between samples.
double duration_positive(const std::vector<double>& t, const std::vector<double>& y) {
  double total = 0;
  for (std::size_t k = 1; k < y.size(); ++k) {
    const double a = y[k - 1], b = y[k], dt = t[k] - t[k - 1];
    if (a > 0 && b > 0)
      total += dt;
    else if (a > 0 || b > 0)
      total += dt * std::max(a, b) / std::abs(b - a);
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
  const StoredRun run = read_stored_run(output_file);  // checks every series read below and their lengths
  const Scene& scene = run.scene;
  const Histories& h = run.histories;
  const auto& t = h.at("time");
  std::ostringstream o;
  o << "{\n  \"file\": " << json_quote(output_file) << ",\n  \"title\": " << json_quote(scene.title)
    << ",\n  \"dimension\": " << scene.dimension << ",\n  \"status\": " << json_quote(run.status)
    << ",\n  \"status_message\": " << json_quote(run.status_message)
    // Finished or stopped by a condition: else the values below are those of a run cut short (interrupted,
    // unstable, failed, or still running).
    << ",\n  \"complete\": " << (run.status == "finished" || run.status == "stopped" ? "true" : "false")
    << ",\n  \"particles\": " << run.particles
    << ",\n  \"steps\": " << json_number(h.at("step").empty() ? 0.0 : h.at("step").back())
    << ",\n  \"time\": " << json_number(t.empty() ? 0.0 : t.back()) << ",\n  \"history_rows\": " << t.size()
    << ",\n  \"density_scaling\": " << json_number(scene.density_scaling);  // 1: off; else the inertia was scaled by it
  o << ",\n  \"specimen\": {";  // what generating it measured: porosity, floaters, coordination, bonds
  for (std::size_t i = 0; i < run.specimen_facts.size(); ++i) {
    const auto& [name, value] = run.specimen_facts[i];
    o << (i ? "," : "") << "\n    " << json_quote(name) << ": " << json_number(value);
  }
  o << (run.specimen_facts.empty() ? "}" : "\n  }");
  o << ",\n  \"results\": {";
  for (std::size_t i = 0; i < scene.summaries.size(); ++i) {
    const SummarySpec& s = scene.summaries[i];
    o << (i ? "," : "") << "\n    " << json_quote(s.name) << ": " << json_number(reduce(s.reduce, t, h.at(s.of)));
  }
  o << (scene.summaries.empty() ? "}" : "\n  }");
  // A largest or smallest value is a peak only if the series turned after it (passed_peak): else the largest so far.
  o << ",\n  \"results_peak_passed\": {";
  bool any_extreme = false;
  for (const SummarySpec& s : scene.summaries) {
    if (s.reduce != SummarySpec::Reduce::Max && s.reduce != SummarySpec::Reduce::Min) continue;
    const std::vector<double>& y = h.at(s.of);
    bool passed = false;
    if (!y.empty()) {
      const auto at = s.reduce == SummarySpec::Reduce::Max ? std::max_element(y.begin(), y.end())
                                                          : std::min_element(y.begin(), y.end());
      passed = passed_peak(y, static_cast<std::size_t>(at - y.begin()), y.size());
    }
    o << (any_extreme ? "," : "") << "\n    " << json_quote(s.name) << ": " << (passed ? "true" : "false");
    any_extreme = true;
  }
  o << (any_extreme ? "\n  }" : "}");
  for (const auto& a : scene.analyses)
    o << ",\n  " << json_quote(a->name()) << ": " << a->summary_json(RunRecord{h, run.cracks});
  o << ",\n  \"final\": {";
  bool first = true;
  for (const auto& [name, y] : h) {
    o << (first ? "" : ",") << "\n    " << json_quote(name) << ": " << json_number(y.empty() ? kNaN : y.back());
    first = false;
  }
  o << (first ? "}" : "\n  }");
  o << ",\n  \"units\": {\"steps\": \"-\", \"time\": \"s\", \"particles\": \"-\", \"density_scaling\": \"-\",";
  if (scene.dimension == 2)
    o << "\n    \"thickness\": \"2D: the specimen is a slice 1 m thick; every force, work and energy of the histories, "
         "the plots and the *_simulated values is the slice's, i.e. per metre of thickness (an analysis's values "
         "without _simulated are for the thickness it declares)\",";
  o
    << "\n    \"results\": {";
  for (std::size_t i = 0; i < scene.summaries.size(); ++i) {
    const SummarySpec& s = scene.summaries[i];
    using R = SummarySpec::Reduce;
    const std::string unit = s.reduce == R::TimeOfMax || s.reduce == R::DurationPositive ? "s"
                             : s.reduce == R::FinalOverInitial                          ? "-"
                                                                                        : run.units.at(s.of);
    o << (i ? ", " : "") << json_quote(s.name) << ": " << json_quote(unit);
  }
  o << "},\n    \"final\": {";
  first = true;
  for (const auto& [name, unit] : run.units) {
    o << (first ? "" : ", ") << json_quote(name) << ": " << json_quote(unit);
    first = false;
  }
  o << "},\n    \"analyses\": \"in each analysis block's own units member\"}\n}\n";
  return o.str();
}

}  // namespace mc
