// What the test analyses share: naming scene items in their keys, and the blocks of `summary` read from a run's
// crack log (cracks per phase pair) and energy histories (the balance of the whole test).
#pragma once
#include <algorithm>
#include <sstream>
#include <string>
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
