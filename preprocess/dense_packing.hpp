// Dense random packings by PFC material genesis (Potyondy & Cundall 2004; Tang 2013 §5.2): particles with radii
// uniform in [R_min, R_max] are placed without overlap at half their radii inside a walled box, grown back in
// steps to their full size (the box then holds them at exactly the target porosity) and settled; then all radii
// are changed uniformly, the walls staying put, until the isotropic stress is the small one asked for.
// Floaters (rattlers of the jammed packing) are counted: particles with fewer than n_f near neighbours, n_f =
// floater_contacts, or D + 1 when that is 0. With floater_contacts > 0 they are removed as Potyondy & Cundall's
// genesis step 4 does, by enlarging each until it touches n_f neighbours: here each takes the largest ball its
// cage holds (touching D + 1 neighbours or walls, no overlap, never larger than the largest radius), so the
// isotropic stress is kept.
// Near neighbours: other particles (not the walls, which bond nothing) closer than 1e-3 R_min.
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
  enum class Shape { Box, Cylinder } shape = Shape::Box;  // Cylinder: inscribed in the box, axis along z (2D: a disc)
  Vec<D> lo, hi;                                          // the box [m]
  double radius_min = 0;                                  // [m]
  double radius_ratio = 1.66;                             // R_max / R_min, Tang Table 5.1
  double porosity = 0.16;    // target, 1 − (particle volume)/(box volume) with the full radii
  double stress = 1e5;       // isotropic stress the packing is settled to [Pa]
  double modulus = kNaN;     // contact modulus E_c of the genesis contacts [Pa]
  double density = 2600;     // [kg/m³]
  int floater_contacts = 0;  // PFC's n_f (1 … D + 1): particles with fewer neighbours fill their cage; 0: off
  std::uint64_t seed = 1;
};

// Near-neighbour contacts of the packing in its box (before carving a cylinder).
struct ContactCensus {
  int floaters = 0;              // particles with fewer than n_f near neighbours
  double floater_share = 0;      // floaters / particles
  double coordination = 0;       // mean near neighbours per particle, 2 C / N
  double coordination_held = 0;  // the same over the particles that are not floaters (PFC's convention)
};

struct PackingReport {
  std::int64_t count = 0;     // particles (after carving a cylinder)
  double porosity_grown = 0;  // in the box, once grown to full size (the target, up to the count's rounding)
  double porosity_final = 0;  // in the box at the end (before carving a cylinder)
  double stress_final = 0;    // mean wall stress at the end [Pa]
  int floater_contacts = 0;   // n_f the floaters are counted with: floater_contacts, or D + 1 when that is 0
  ContactCensus before;       // settled to the isotropic stress, before any floater is grown
  ContactCensus after;        // at the end (= before when floater_contacts is 0)
  int floaters_grown = 0;     // particles grown (at least once) to touch n_f neighbours
  std::int64_t steps = 0;     // genesis steps
};

// Throws InputError when the parameters cannot make a packing (box too small, porosity out of range) or the
// genesis does not settle.
template <int D>
Packing<D> dense_packing(const DensePackingSpec<D>& spec, PackingReport* report = nullptr);

}  // namespace mc
