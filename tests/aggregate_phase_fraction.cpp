// Tang §4.3.1, Fig. 4.14: particles take the aggregate phase by their centres, so the share of particle area in
// the aggregate phase tends to the aggregate area fraction as the particles get smaller against the specimen
// (L/R grows): the error shrinks with R and is small at fine resolution.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "preprocess/aggregate_placement.hpp"
#include "preprocess/regular_packing.hpp"

using namespace mc;

namespace {

// |share of particle area in the aggregate phase − aggregate fraction| for one layout and one particle radius.
double phase_error(const AggregateLayout<2>& layout, double r) {
  const Packing<2> pk = hexagonal_packing(layout.lo, layout.hi, r);
  double all = 0, agg = 0;
  for (std::size_t i = 0; i < pk.x.size(); ++i) {
    all += pk.radius[i] * pk.radius[i];
    if (layout.aggregate_at(pk.x[i]) > 0) agg += pk.radius[i] * pk.radius[i];
  }
  return std::abs(agg / all - layout.achieved_fraction);
}

}  // namespace

TEST_CASE("particle_phase_fraction_tends_to_the_aggregate_fraction_as_L_over_R_grows") {
  // Five layouts of Table 4.1 scaled to 1–16 mm at 40 % in a 100 mm square; particles of R = 2 mm (L/R = 50)
  // down to 0.25 mm (L/R = 400). One layout's error at coarse R can cancel by chance; the mean over layouts
  // shows the trend (the error ∝ R × aggregate perimeter / area, plus the lattice's sampling noise).
  const std::vector<double> radii{2e-3, 1e-3, 0.5e-3, 0.25e-3};
  std::vector<double> mean(radii.size(), 0.0);
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    PlacementSpec<2> spec;
    spec.lo = Vec<2>(0, 0), spec.hi = Vec<2>(0.1, 0.1);
    spec.grading = tang_table_4_1(1e-3 / 4);
    spec.fraction = 0.4;
    spec.seed = seed;
    const AggregateLayout<2> layout = place_aggregates<2>(spec);
    REQUIRE(layout.reached);
    for (std::size_t k = 0; k < radii.size(); ++k) mean[k] += phase_error(layout, radii[k]) / 5;
  }
  for (std::size_t k = 0; k < radii.size(); ++k) MESSAGE("L/R = ", 0.1 / radii[k], ": mean error ", mean[k]);
  CHECK(mean.back() < 0.5 * mean.front());  // finer particles, closer phase fractions
  CHECK(mean.back() < 0.01);                // L/R = 400: within 1 % of the aggregate fraction
}
