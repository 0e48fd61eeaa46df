// Short fibres as straight segments in a specimen's volume, independent of the cells (Květoň §5.4): as many as
// the volume fraction asks, N = V_f V/(π d_f²/4 · l_f), each at a uniformly drawn centre with a direction drawn
// isotropically, along one direction, or about one direction with a von Mises–Fisher spread. A fibre partly
// outside the specimen is drawn again (Květoň's rule: fibres near a surface then lie along it, the wall effect),
// or cut at the surface (its centre kept: no bias in direction, but fibres shortened and the volume fraction
// lowered there).
#pragma once
#include <vector>

#include "engine/dim.hpp"
#include "engine/random_stream.hpp"
#include "rigid_cell/specimen_shape.hpp"

namespace mc::rigid_cell {

enum class FibreOrientation { Isotropic, Aligned, Preferential };
enum class FibreBoundary { Redraw, Cut };

struct FibrePlacement {
  double volume_fraction = 0;  // V_f [-]
  long count = 0;              // a number of fibres instead (0: as many as V_f asks)
  double length = 0;           // l_f [m]
  double diameter = 0;         // d_f [m]
  FibreOrientation orientation = FibreOrientation::Isotropic;
  Vec<3> direction = Vec<3>::UnitX();  // aligned or preferential: the axis (unit)
  double concentration = 0;            // preferential: κ of the von Mises–Fisher density ∝ exp(κ cos θ) [-]
  FibreBoundary boundary = FibreBoundary::Redraw;
};

struct Fibre {
  Vec<3> a, b;  // its ends [m]
};

// The number of fibres a placement asks for in a volume: its count, else V_f V/(π d_f²/4 · l_f).
long fibre_count(const FibrePlacement& p, double volume);
// A unit direction drawn as the placement says.
Vec<3> draw_direction(const FibrePlacement& p, RandomStream& rng);
// The fibres of one family in the shape, drawn from `rng` one after another (the same stream, the same fibres).
// Throws InputError when a fibre that must lie wholly inside found no place in 10⁴ draws.
std::vector<Fibre> place_fibres(const SpecimenShape<3>& shape, const FibrePlacement& p, RandomStream& rng);

}  // namespace mc::rigid_cell
