// A group of particles driven at a prescribed velocity on its held degrees of freedom, reached over a ramp as a
// wall's (Tang §8.1: the FRP's loaded end pulled "in a controlled fashion to neglect possible inertia effect").
// Held degrees of freedom keep their velocity in the law of motion; this sets it each step, so the group's
// reaction is what it takes to drive it.
#pragma once
#include <vector>

#include "engine/dim.hpp"
#include "engine/particles.hpp"
#include "engine/ramp.hpp"

namespace mc {

template <int D>
struct DrivenGroup {
  std::vector<int> members;
  Vec<D> velocity = Vec<D>::Zero();  // [m/s], on the members' held translations only
  double ramp_time = 0;              // [s], engine/ramp.hpp

  Vec<D> velocity_at(double t) const { return velocity * ramp_factor(t, ramp_time); }

  void drive(Particles<D>& p, double t) const {
    const Vec<D> v = velocity_at(t);
    for (int i : members)
      for (int k = 0; k < D; ++k)
        if (p.fix[i] & (1u << k)) p.v[i][k] = v[k];
  }
};

}  // namespace mc
