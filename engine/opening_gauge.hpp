// An opening gauge: how far two sets of particles have moved apart along a fixed direction since the start, the
// mean displacement of set b minus that of set a (a clip gauge across a notch mouth measures the crack-mouth
// opening displacement, CMOD, this way: Tang §7.1; RILEM 50-FMC). A wall under opening control is driven by it.
#pragma once
#include <vector>

#include "engine/dim.hpp"
#include "engine/particles.hpp"

namespace mc {

template <int D>
struct OpeningGauge {
  std::vector<int> a, b;  // particle indices, non-empty
  Vec<D> direction;       // unit vector from side a to side b
  double start = 0;       // the separation along `direction` at the start [m]

  // Mean position of b minus mean position of a [m].
  Vec<D> span(const Particles<D>& p) const { return centre(p, b) - centre(p, a); }
  // That along the direction [m].
  double separation(const Particles<D>& p) const { return span(p).dot(direction); }
  // The opening since the start [m], positive when the sides part.
  double value(const Particles<D>& p) const { return separation(p) - start; }

 private:
  static Vec<D> centre(const Particles<D>& p, const std::vector<int>& set) {
    Vec<D> c = Vec<D>::Zero();
    for (int i : set) c += p.x[i];
    return c / static_cast<double>(set.size());
  }
};

}  // namespace mc
