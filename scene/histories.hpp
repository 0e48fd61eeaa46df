// History series: the named time series a scene records (walls, energy, measurement regions, probes, plus
// time, step, dt and the contact count). Names are decided by the scene alone, so they can be validated
// before the run; samplers read the world when a row is recorded.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "engine/measure.hpp"
#include "scene/scene.hpp"
#include "engine/world.hpp"

namespace mc {

struct Series {
  std::string name, unit;
  std::function<double()> sample;  // empty when only the names are wanted
};

// What the scene observes beyond the world itself: strain integrators of measurement regions.
template <int D>
struct Observers {
  std::vector<Region<D>> regions;
  std::vector<StrainIntegrator<D>> strain;  // one per region (used only where the region declares strain)
  explicit Observers(const Scene& s);
  void every_step(const World<D>& w, const Scene& s);  // integrates the declared strains
};

template <int D>
std::vector<Series> make_series(const Scene& s, const World<D>* w, const Observers<D>* obs);

std::vector<std::string> history_names(const Scene& s);

}  // namespace mc
