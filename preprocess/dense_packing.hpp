// Dense random packings by PFC material genesis (Potyondy & Cundall 2004; Tang 2013 §5.2): particles with radii
// uniform in [R_min, R_max] are placed without overlap at half their radii inside a walled box, grown back in
// steps to their full size (the box then holds them at exactly the target porosity) and settled; then all radii
// are changed uniformly, the walls staying put, until the isotropic stress is the small one asked for.
// Particles with fewer than D + 1 near neighbours (floaters, rattlers of the jammed packing) are counted.
// The genesis uses frictionless linear contacts with the material's contact modulus, so the stress locked in
// when the packing is bonded is the isotropic stress asked for.
//
// The porosity asked for is the one of the grown packing (PFC's meaning). Relieving the stress of a packing
// grown denser than it jams at σ0 loosens it to its jammed porosity: 0.169 for R_max/R_min = 1.66 discs at
// σ0/E_c = 5e-6 when 0.16 is asked. The report gives both.
#pragma once
#include <cstdint>
#include <string>

#include "engine/dim.hpp"
#include "preprocess/random_box.hpp"  // Packing<D>

namespace mc {

template <int D>
struct DensePackingSpec {
  enum class Shape { Box, Cylinder } shape = Shape::Box;  // Cylinder (3D): axis along z, inscribed in the box
  Vec<D> lo, hi;                                          // the box [m]
  double radius_min = 0;                                  // [m]
  double radius_ratio = 1.66;                             // R_max / R_min, Tang Table 5.1
  double porosity = 0.16;  // target, 1 − (particle volume)/(box volume) with the full radii
  double stress = 1e5;     // isotropic stress the packing is settled to [Pa]
  double modulus = kNaN;   // contact modulus E_c of the genesis contacts [Pa]
  double density = 2600;   // [kg/m³]
  std::uint64_t seed = 1;
};

struct PackingReport {
  std::int64_t count = 0;     // particles (after carving a cylinder)
  double porosity_grown = 0;  // in the box, once grown to full size (the target, up to the count's rounding)
  double porosity_final = 0;  // in the box at the end (before carving a cylinder)
  double stress_final = 0;    // mean wall stress at the end [Pa]
  int floaters = 0;           // particles with fewer than D + 1 neighbours within 1e-3 R_min
  std::int64_t steps = 0;     // genesis steps
};

// Throws InputError when the parameters cannot make a packing (box too small, porosity out of range) or the
// genesis does not settle.
template <int D>
Packing<D> dense_packing(const DensePackingSpec<D>& spec, PackingReport* report = nullptr);

}  // namespace mc
