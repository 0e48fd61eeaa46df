#include "scene/nearest_name.hpp"

#include <algorithm>

namespace mc {

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string nearest_name(std::string_view given, const std::vector<std::string>& known, std::size_t most) {
  std::string best;
  std::size_t best_distance = most + 1;
  for (const std::string& k : known) {
    const std::size_t d = edit_distance(given, k);
    if (d > 0 && d < best_distance) best = k, best_distance = d;
  }
  return best;
}

}  // namespace mc
