// The histories of an explicit run: the named time series a scene records (time, step, dt and the contact count,
// then what it declares: bonds and cracks, walls, groups, its analyses, wall strains, energy, measurement regions
// and probes). Names are decided by the scene alone, so they can be validated before the run; samplers read the
// world when a row is recorded.
#pragma once
#include <string>
#include <vector>

#include "engine/measure.hpp"
#include "engine/system.hpp"
#include "engine/world.hpp"
#include "scene/analysis.hpp"
#include "scene/build_world.hpp"
#include "scene/scene.hpp"

namespace mc {

// What the scene observes beyond the world itself: the strains of its measurement regions, integrated every step.
template <int D>
struct Observers {
  std::vector<Region<D>> regions;
  std::vector<StrainIntegrator<D>> strain;  // one per region (used only where the region declares strain)
  explicit Observers(const Scene& s);
  void every_step(const World<D>& w, const Scene& s);
};

// The series of a run of `s` on `w`; with `w` null, the names alone. Groups, probes and analyses read `view`: the
// world's particles, walls and gauges, or (a split world) a whole copy of them kept up to date for each row. The
// energy series bring the world's energy terms up to date when sampled (World::update_energy), so they need it
// writable. The samplers of a split world call its processes together (World::agree_sums), in the list's order.
template <int D>
std::vector<Series> make_series(const Scene& s, World<D>* w, const Observed<D>& view, const SpecimenInfo* info,
                                const Observers<D>* obs);

std::vector<std::string> history_names(const Scene& s);

}  // namespace mc
