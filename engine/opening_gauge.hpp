// An opening gauge: how far two sets of particles have moved apart along a fixed direction since the start, the
// mean displacement of set b minus that of set a (a clip gauge across a notch mouth measures the crack-mouth
// opening displacement, CMOD, this way: Tang §7.1; RILEM 50-FMC). A wall under opening control is driven by it.
#pragma once
#include <cstddef>
#include <vector>

#include "engine/dim.hpp"
#include "engine/exact_sum.hpp"
#include "engine/particles.hpp"

namespace mc {

template <int D>
struct OpeningGauge {
  std::vector<int> a, b;  // particle indices, non-empty (a split world's: those of its own)
  Vec<D> direction;       // unit vector from side a to side b
  double start = 0;       // the separation along `direction` at the start [m]
  // A split world's: the sides' sizes in the whole world (0: a.size(), b.size()).
  std::size_t whole_a = 0, whole_b = 0;

  // Mean position of b minus mean position of a [m].
  Vec<D> span(const Particles<D>& p) const {
    ExactSum sums[2 * D];
    add_sums(p, sums);
    return span_from(sums);
  }
  // That along the direction [m].
  double separation(const Particles<D>& p) const { return span(p).dot(direction); }
  // The opening since the start [m], positive when the sides part.
  double value(const Particles<D>& p) const { return separation(p) - start; }

  // The positions of a's particles, then b's, summed exactly per coordinate into sums[0, 2D): the same bits
  // however the particles are split between processes (World::move_walls shares the sums).
  void add_sums(const Particles<D>& p, ExactSum* sums) const {
    for (int i : a)
      for (int k = 0; k < D; ++k) sums[k].add(p.x[i][k]);
    for (int i : b)
      for (int k = 0; k < D; ++k) sums[D + k].add(p.x[i][k]);
  }
  // The opening from the sums over all the gauge's particles, kept as its reading for this step.
  void read(const ExactSum* sums) { reading_ = span_from(sums).dot(direction) - start; }
  double reading() const { return reading_; }

 private:
  Vec<D> span_from(const ExactSum* sums) const {
    const double na = static_cast<double>(whole_a ? whole_a : a.size()),
                 nb = static_cast<double>(whole_b ? whole_b : b.size());
    Vec<D> s;
    for (int k = 0; k < D; ++k) s[k] = sums[D + k].value() / nb - sums[k].value() / na;
    return s;
  }
  double reading_ = 0;
};

}  // namespace mc
