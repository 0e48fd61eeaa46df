#include "scene/analysis.hpp"

#include "scene/analyses/bending.hpp"
#include "scene/analyses/pullout.hpp"
#include "scene/analyses/uniaxial.hpp"
#include "scene/scene.hpp"

namespace mc {

namespace {

// The registry: an analysis's key table (its name is the analysis's table) and its reader. Adding an analysis is
// one line here.
struct Entry {
  const KeyTable& (*keys)();
  std::shared_ptr<const Analysis> (*read)(const KeyReader& k, const Scene& s);
};
constexpr Entry kAnalyses[] = {
    {uniaxial_keys, read_uniaxial},
    {bending_keys, read_bending},
    {pullout_keys, read_pullout},
};

}  // namespace

void read_analyses(const Table& root, Scene& s) {
  for (const Entry& e : kAnalyses)
    if (auto t = optional_table_of(root, e.keys())) {
      s.analyses.push_back(e.read(KeyReader(*t, e.keys()), s));
      t->finish();
    }
}

void check_analyses(const Table& root, const Scene& s, const std::vector<std::string>& histories) {
  for (const auto& a : s.analyses)
    for (const Entry& e : kAnalyses)
      if (e.keys().name == a->name()) a->check(KeyReader(table_of(root, e.keys()), e.keys()), s, histories);
}

std::vector<const KeyTable*> analysis_keys() {
  std::vector<const KeyTable*> out;
  for (const Entry& e : kAnalyses) out.push_back(&e.keys());
  return out;
}

}  // namespace mc
