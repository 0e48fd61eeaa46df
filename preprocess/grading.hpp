// Aggregate grading, Tang (2013) §4.3–4.4: size ranges with their shares of the aggregate content, the Fuller
// curve (4.7), Walraven's transform (4.8) to the grading seen in a section, and the list of aggregates that fills
// a target fraction of a domain. Sizes are sieve sizes = auxiliary circle / sphere diameters, in any length unit.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "engine/random_stream.hpp"

namespace mc {

// Aggregates of size d in [lo, hi) taking `share` of the aggregate content (area in 2D, volume in 3D).
struct SizeRange {
  double lo = 0, hi = 0, share = 0;
};

// Ranges in any order, not overlapping; shares summing to 1.
struct Grading {
  std::vector<SizeRange> ranges;
};

// Throws InputError unless 0 < lo < hi, shares ≥ 0 summing to 1 (to 1e-9), ranges not overlapping.
void check_grading(const Grading& g);

// Tang Table 4.1: 4–8, 8–16, 16–32, 32–64 mm at 2 : 2 : 3 : 3 (§4.4). `mm` is the length of a millimetre in the
// unit wanted (1 for millimetres, 1e-3 for metres).
Grading tang_table_4_1(double mm = 1.0);

// Tang (4.7), Fuller: the content fraction passing sieve d, P = (d / D)^n (n ≈ 0.5: densest packing).
double fuller_passing(double d, double d_max, double n);

// Ranges between consecutive sieves (increasing), shares from (4.7) with D = sieves.back(), normalised over
// [sieves.front(), sieves.back()] (the fines below the first sieve belong to the mortar).
Grading fuller_grading(const std::vector<double>& sieves, double n);

// Tang (4.8), Walraven and Reinhardt (1981): the probability that a point of a section through concrete whose
// aggregate (volume fraction P_k) follows Fuller's curve with n = 0.5 lies in an intersection circle of diameter
// D < D0: P_c = P_k [1.455 r^0.5 − 0.5 r² + 0.036 r⁴ + 0.006 r⁶ + 0.002 r⁸ + 0.001 r¹⁰], r = D0 / D_max ∈ [0, 1].
double walraven_passing(double d0_over_dmax, double pk);

// The section grading of aggregates sieved at `sieves` (increasing, D_max = sieves.back()) at volume fraction P_k:
// each range's area fraction of the section P_c(hi) − P_c(lo) from (4.8), their sum `fraction` (the coarse
// aggregate area fraction of the section) and `grading`, the same normalised to shares.
struct SectionGrading {
  Grading grading;
  double fraction = 0;
};
SectionGrading walraven_section(const std::vector<double>& sieves, double pk);

// How sizes are drawn within a range: uniform in d, or with the number density that makes the content follow
// Fuller's curve within the range, ∝ d^(n − 1 − D) (content ∝ d^D).
enum class SizeDraw { uniform, fuller };

// One aggregate of a filled grading.
struct SizedAggregate {
  int made = 0;        // which call of `make` produced it (0, 1, …)
  int range = 0;       // index in Grading::ranges
  double size = 0;     // its size d (the drawn size × scale)
  double scale = 1;    // by how much the aggregate made for the drawn size is to be scaled
  double content = 0;  // its area / volume: make(drawn size) · scale^D
};

// The aggregates that fill `target` content (e.g. fraction × domain area / volume), range by range from the
// largest: sizes are drawn in [lo, hi) and each handed to `make(d)`, which makes an aggregate and returns its
// content (the exact area / volume of a random shape, or an estimate such as c·d^D), until the range holds
// share × target. The aggregate that would overshoot is shrunk to fill the rest exactly if it stays ≥ lo; if not,
// the rest goes to the smallest aggregate of the range, grown if it stays < hi, or else to all of the range's
// aggregates grown by a common factor if they stay < hi; if not, it is carried to the next finer range (after the
// finest it is dropped: less than one smallest aggregate). So each range holds its share exactly, up to round-off
// (short of a range too small for a single aggregate). Sorted largest first.
std::vector<SizedAggregate> fill_grading(const Grading& g, double target, int dim,
                                         const std::function<double(double)>& make, RandomStream& rng,
                                         SizeDraw draw = SizeDraw::uniform, double fuller_n = 0.5);

// The sizes to place for an aggregate fraction of a domain of content `domain` (area / volume), taking an
// aggregate of size d to have content shape_factor · d^dim (a disc π/4, a sphere π/6; the random shapes of
// aggregate_shape.hpp with default limits average about 0.53 in 2D and 0.20 in 3D). For planning (counts, cost);
// place_aggregates fills with the exact contents of its shapes. Largest first.
std::vector<SizedAggregate> aggregate_sizes(const Grading& g, double fraction, double domain, int dim,
                                            double shape_factor, std::uint64_t seed, SizeDraw draw = SizeDraw::uniform,
                                            double fuller_n = 0.5);

}  // namespace mc
