// What the test analyses share: naming scene items in their keys, and the blocks of `summary` read from a run's
// crack log (cracks per phase pair) and energy histories (the balance of the whole test).
#pragma once
#include <algorithm>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "scene/analysis.hpp"

namespace mc {

// Names separated by spaces, exactly `n` of them, each found in `known` (by `name_of`); their indices.
template <class T, class Name>
std::vector<int> named(const KeyReader& k, std::string_view key, std::size_t n, const std::vector<T>& known,
                       Name name_of, const std::string& what) {
  std::stringstream ss(k.string(key));
  std::vector<std::string> names;
  for (std::string x; ss >> x;) names.push_back(x);
  if (names.size() != n) k.fail(key, "give the names of " + std::to_string(n) + " " + what + ", separated by spaces");
  std::vector<int> out;
  for (const auto& x : names) {
    int found = -1;
    for (std::size_t k = 0; k < known.size(); ++k)
      if (name_of(known[k]) == x) found = static_cast<int>(k);
    if (found < 0) k.fail(key, "'" + x + "' is not the name of one of the " + what);
    if (std::find(out.begin(), out.end(), found) != out.end()) k.fail(key, "names '" + x + "' twice");
    out.push_back(found);
  }
  return out;
}

// Whether a load passed its peak: after its largest magnitude (row `peak`) some row of y[0, end) fell at least
// kPeakDrop below it. Without that, a run that ended (or was interrupted) while its load still rose holds a largest
// value so far, not a strength: every summary says which beside its peaks, strengths and capacities.
constexpr double kPeakDrop = 0.05;
bool passed_peak(const std::vector<double>& y, std::size_t peak, std::size_t end);
constexpr const char* kPeakPassedDefinition =
    "true when the load fell at least 5 % below its largest value after it; false: the run ended (or was "
    "interrupted) before a peak, and the strength, capacity or peak read is only the largest value so far";

// A summary block's "units" member: each of its numbers' SI unit ("-" for a ratio or a count, as in the histories),
// in the order given.
std::string units_json(const std::vector<std::pair<std::string, std::string>>& units);

// "a-b" for a phase pair, in name order.
std::string pair_name(const std::vector<std::string>& names, int a, int b);

// The crack log up to `until` [s] as JSON: per phase pair, the tensile and shear breaks and the first yields.
std::string crack_counts_json(const std::vector<LoggedCrack>& cracks, double until,
                              const std::vector<std::string>& names);

// The energy balance of the whole test from the energy histories ([physics] energy = true): the work of the
// boundaries against what is stored, dissipated and moving; the worst |residual| / work; and `g_name`, the
// bonds' dissipation over `area` (of the `area_name`). "null" without the histories.
std::string energy_json(const Histories& h, double area, const std::string& g_name, const std::string& area_name);

}  // namespace mc
