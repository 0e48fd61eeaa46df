// The per-particle arrays that travel with a particle when a split world's processes exchange it (and that a
// checkpoint holds), in one order.
#pragma once
#include <tuple>

#include "engine/particles.hpp"

namespace mc {

// References to the arrays of p (const when p is).
template <class P>
auto particle_fields(P& p) {
  return std::tie(p.x, p.v, p.f, p.w, p.radius, p.mass, p.inertia, p.phase, p.stiffness, p.fix);
}

}  // namespace mc
