// Cracks: what a bond model reports when a bond breaks (or, for softening bonds, first yields), and the
// record the engine keeps of it. Bonds break rarely, so reporting costs one branch per bond per step.
#pragma once
#include <cstdint>

#include "engine/dim.hpp"

namespace mc {

enum class CrackMode : std::uint8_t { None = 0, Tensile = 1, Shear = 2 };
enum class CrackKind : std::uint8_t { Break = 0, Yield = 1 };  // Yield: a softening bond's first yield

inline const char* mode_name(CrackMode m) {
  return m == CrackMode::Tensile ? "tensile" : m == CrackMode::Shear ? "shear" : "none";
}

// One contact's report for one step (None: nothing happened).
struct BondEvent {
  CrackMode mode = CrackMode::None;
  CrackKind kind = CrackKind::Break;
};

// A bond event as the contact set saw it: the pair, where, and along which normal.
template <int D>
struct PairEvent {
  int a, b;         // particle indices, a < b
  Vec<D> position;  // contact point [m]
  Vec<D> normal;    // unit normal from a to b
  BondEvent event;
};

// The crack log's record, with when and which model and phases.
template <int D>
struct Crack {
  std::int64_t step;
  double time;
  int a, b;  // particle indices
  Vec<D> position, normal;
  CrackMode mode;
  CrackKind kind;
  int set;  // index of the contact model (World::sets)
  int phase_a, phase_b;
};

}  // namespace mc
