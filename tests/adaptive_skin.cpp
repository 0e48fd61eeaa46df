// The adaptive Verlet skin (World::rebuild_interval): at each rebuild the skin becomes 2 × (largest displacement
// per step) × the interval, so particles moving at a steady speed rebuild the lists once per interval, where the
// fixed skin rebuilt them every few steps; a specimen at rest keeps its skin. The skin changes only the lists:
// particles in free flight stay on their straight lines x(t) = x0 + v t.
#include <doctest/doctest.h>

#include <cmath>

#include "contact_models/linear.hpp"
#include "tests/common/relative.hpp"
#include "tests/common/test_worlds.hpp"

using namespace mc;

namespace {

struct Flight {
  std::int64_t rebuilds;
  double skin, worst_path_error;
};

// A 6 × 6 × 6 lattice of spheres (r = 1 mm, spacing 4 mm) all moving at the same velocity, 0.01 r per step:
// never touching, so the step stays the nominal one and every particle flies straight.
Flight fly(int rebuild_interval, int steps) {
  LinearParams p;
  p.modulus = 1e9, p.friction = 0.5;
  auto w = test::single_model_world<3, Linear>(p);
  const double r = 1e-3;
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 6; ++j)
      for (int i = 0; i < 6; ++i) w.particles.add(Vec<3>(4 * r * i, 4 * r * j, 4 * r * k), r, 2600, 0);
  w.rebuild_interval = rebuild_interval;
  w.init();
  const Vec<3> v = Vec<3>(0.006, 0.0, 0.008) * r / w.dt;  // |v| Δt = 0.01 r
  const std::vector<Vec<3>> x0 = w.particles.x;
  for (auto& vi : w.particles.v) vi = v;
  const std::int64_t before = w.rebuilds;
  for (int s = 0; s < steps; ++s) w.step();
  double worst = 0;
  for (int i = 0; i < w.particles.size(); ++i)
    worst = std::max(worst, (w.particles.x[i] - (x0[i] + v * w.time)).norm());
  return {w.rebuilds - before, w.skin, worst};
}

}  // namespace

TEST_CASE("adaptive_skin_rebuilds_a_steady_flow_once_per_interval_and_leaves_its_paths_straight") {
  const int steps = 600;
  const Flight fixed = fly(0, steps), adaptive = fly(30, steps);
  MESSAGE("rebuilds: fixed skin ", fixed.rebuilds, ", adaptive ", adaptive.rebuilds, " (skin ", adaptive.skin, " m)");
  // Fixed skin 0.1 r: a rebuild once something moved more than 0.05 r, i.e. after 5 or 6 steps of 0.01 r (5 reach
  // 0.05 r exactly, and rounding decides): 600 / 6 = 100 to 600 / 5 = 120 rebuilds.
  CHECK(fixed.rebuilds >= 99);
  CHECK(fixed.rebuilds <= 120);
  // Adaptive: skin = 2 × 0.01 r × 30 = 0.6 r after the first rebuild, then a rebuild after 30 or 31 steps
  // (30 reach 0.3 r exactly): 19 or 20 in 600 steps, the first interval at the fixed skin counted.
  CHECK(adaptive.skin == mc::test::relative(0.6e-3, 1e-6));
  CHECK(adaptive.rebuilds >= 19);
  CHECK(adaptive.rebuilds <= 21);
  // Free flight is x0 + v t to rounding (600 additions of v Δt: far below 1e-12 m at 1e-2 m).
  CHECK(adaptive.worst_path_error < 1e-12);
  CHECK(fixed.worst_path_error < 1e-12);
}

TEST_CASE("adaptive_skin_of_a_specimen_at_rest_stays_the_declared_one") {
  const Flight rest = fly(30, 0);
  CHECK(rest.skin == mc::test::relative(0.1e-3, 1e-12));  // 0.1 R_min, as without adaptation
}
