// Analyses: the kinds of test a scene may declare, each in its own table ([uniaxial], [bending], [pullout]). An
// analysis declares its keys (a key table), reads them, records the histories it defines, checks that the histories
// it reads exist, and writes its block of `summary`. Each is a plug-in: scene/analyses/<name>.{hpp,cpp} and one line
// in the registry (scene/analysis.cpp). It observes bodies and groups only, not a solver's internals, so it serves
// every solver.
#pragma once
#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "engine/crack.hpp"
#include "engine/opening_gauge.hpp"
#include "engine/particles.hpp"
#include "engine/system.hpp"  // Series
#include "engine/wall.hpp"
#include "scene/key_reader.hpp"

namespace mc {

struct Scene;

// A run's histories by name (the output file's /history).
using Histories = std::map<std::string, std::vector<double>>;

// One entry of a run's crack log (the output file's /cracks): a bond's break or first yield.
struct LoggedCrack {
  double time = 0;                          // [s]
  std::array<double, 3> position{};         // the contact point [m]; 2D: z = 0
  CrackMode mode = CrackMode::None;
  CrackKind kind = CrackKind::Break;
  int phase_a = 0, phase_b = 0;             // indices into Scene::phases
};

// What a run recorded, as its analyses read it for `summary`.
struct RunRecord {
  const Histories& histories;
  const std::vector<LoggedCrack>& cracks;  // empty without a crack log
};

// What an analysis may observe of a running system: its bodies (particles, or rigid cells), the members of the
// scene's [[groups]], its walls and its opening gauges (one per opening probe, Scene::opening_gauge). All null
// when only the names of the histories are wanted.
template <int D>
struct Observed {
  const Particles<D>* bodies = nullptr;
  const std::vector<std::vector<int>>* groups = nullptr;
  const std::vector<Wall<D>>* walls = nullptr;
  const std::vector<OpeningGauge<D>>* gauges = nullptr;
};

class Analysis {
 public:
  virtual ~Analysis() = default;
  // Its table in the scene and its block in `summary`.
  virtual std::string name() const = 0;
  // The histories it defines itself, appended to `out` (samplers empty when `o.bodies` is null). Throws InputError
  // when the specimen does not allow it (a support group at the wrong end).
  virtual void add_histories(std::vector<Series>& out, const Observed<2>& o) const = 0;
  virtual void add_histories(std::vector<Series>& out, const Observed<3>& o) const = 0;
  // Once the whole scene is read: what it reads is recorded and what it needs is declared. Fails through `k`,
  // its own table, naming the key.
  virtual void check(const KeyReader& k, const Scene& s, const std::vector<std::string>& histories) const = 0;
  // Its block of `summary`: a JSON value computed from what the run recorded.
  virtual std::string summary_json(const RunRecord& run) const = 0;
};

// Reads every analysis table the scene has (the rest of the scene read already: groups, bonds …).
void read_analyses(const Table& root, Scene& s);
// The key tables of the analyses, in registry order.
std::vector<const KeyTable*> analysis_keys();
// Checks each of them against the scene's histories.
void check_analyses(const Table& root, const Scene& s, const std::vector<std::string>& histories);

}  // namespace mc
