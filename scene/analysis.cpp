#include "scene/analysis.hpp"

#include "scene/analyses/bending.hpp"
#include "scene/analyses/pullout.hpp"
#include "scene/analyses/uniaxial.hpp"
#include "scene/scene.hpp"

namespace mc {

namespace {

// The registry: an analysis's table name and its reader. Adding an analysis is one line here.
struct Entry {
  const char* table;
  std::shared_ptr<const Analysis> (*read)(const Table& t, const Scene& s);
};
constexpr Entry kAnalyses[] = {
    {"uniaxial", read_uniaxial},
    {"bending", read_bending},
    {"pullout", read_pullout},
};

}  // namespace

void read_analyses(const Table& root, Scene& s) {
  for (const Entry& e : kAnalyses)
    if (auto t = root.optional_table(e.table)) {
      s.analyses.push_back(e.read(*t, s));
      t->finish();
    }
}

void check_analyses(const Table& root, const Scene& s, const std::vector<std::string>& histories) {
  for (const auto& a : s.analyses) a->check(root.table(a->name()), s, histories);
}

}  // namespace mc
