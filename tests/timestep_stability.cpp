// The critical timestep estimate, Tang (3.22)–(3.24): Δt = min over particles of √(m/Σk) and √(I/Σk_rot).
// A dense assembly runs stably just under it (safety 0.99), twice it is caught by the stability guard with a
// message naming the step and the particle, and a fixed step above it is refused at init.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>

#include "engine/errors.hpp"
#include "tests/common/test_worlds.hpp"

using namespace mc;

namespace {

// Six fixed planes around [lo, hi]³, as stiff as a sphere, with friction μ.
void box_walls(World<3>& w, const LinearParams& prm, double r, double lo, double hi) {
  WallMaterial wm;
  wm.kn = Linear::ball_kn<3>(prm, r);
  wm.ks = wm.kn / prm.kn_ks_ratio;
  wm.friction = prm.friction;
  test::add_box_walls(w, lo, hi, wm);
  w.domain_lo = Vec<3>::Constant(lo - 10 * r);
  w.domain_hi = Vec<3>::Constant(hi + 10 * r);
}

LinearParams linear(double mu) {
  LinearParams prm;
  prm.modulus = 1e8;
  prm.kn_ks_ratio = 1;  // shear springs as stiff as the normal ones: the rotational estimate governs
  prm.friction = mu;
  return prm;
}

// The densest regular packing: equal spheres on a face-centred cubic lattice of n³ cells, compressed by 0.1 %
// (overlaps of 2 µm on r = 1 mm, every neighbour touching), in a box of six fixed planes that overlap the outer
// spheres by r c. The box does not balance the lattice at its faces, so released it vibrates in all its
// modes, some contacts near the walls opening and closing. All candidate pairs touch, so the estimate
// (which sums k_n + k_s over the candidates) is as tight as it gets.
World<3> dense_fcc(int n, double mu) {
  const LinearParams prm = linear(mu);
  auto w = test::single_model_world<3, Linear>(prm);
  const double r = 1e-3, c = 1e-3;
  const double a = 2 * std::sqrt(2.0) * r * (1 - c);
  const Vec<3> basis[4] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        for (const auto& b : basis) w.particles.add(a * (Vec<3>(i, j, k) + b), r, 2600, 0);
  box_walls(w, prm, r, -r * (1 - c), (n - 0.5) * a + r * (1 - c));
  return w;
}

// Simple cubic lattice of n³ spheres compressed by 0.1 % between walls that balance it exactly, positions
// perturbed by ±5 % of the overlap: a linear system whose contacts do not open while the step is stable.
World<3> perturbed_cubic(int n, double mu) {
  const LinearParams prm = linear(mu);
  auto w = test::single_model_world<3, Linear>(prm);
  const double r = 1e-3, c = 1e-3;
  const double a = 2 * r * (1 - c);
  RandomStream rng(12345);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        Vec<3> x = a * Vec<3>(i, j, k);
        for (int d = 0; d < 3; ++d) x[d] += (rng.uniform() - 0.5) * 0.1 * (2 * r * c);
        w.particles.add(x, r, 2600, 0);
      }
  box_walls(w, prm, r, -r * (1 - 2 * c), (n - 1) * a + r * (1 - 2 * c));
  return w;
}

// How far the estimate is from the true limit (measured by raising the safety factor until the run blows up or
// creates energy): simple cubic lattice 1.7–1.8 (theory: the mode in which all spheres spin alike has
// ω² = 8 k_s R²/I against the estimate's 6 k_s R²/I, so the limit is 2/√(4/3) = 1.73), face-centred cubic
// (3³ cells) 1.8–2.0, and a polydisperse packing with gaps 2.0–2.3 (its estimate also counts candidates not touching).
// So 0.99 leaves a margin of at least 1.7, and 2.0 is beyond the limit of both lattices.

}  // namespace

TEST_CASE("step_just_under_critical_estimate_is_stable") {
  auto w = dense_fcc(2, 0.5);  // 32 spheres
  w.timestep.safety = 0.99;
  w.trace_energy = true;  // also arms the guard's energy check
  w.init();
  w.update_energy();
  w.energy.initial = w.energy.kinetic + w.energy.strain;
  const double e0 = w.energy.initial;
  double ke_max = 0;
  const int steps = 100000;
  for (int s = 1; s <= steps; ++s) {
    w.step();
    ke_max = std::max(ke_max, w.energy.kinetic);
    if (s % 100 == 0) REQUIRE_NOTHROW(w.check_stability());
  }
  w.update_energy();
  MESSAGE("32 spheres (fcc), " << w.contact_count() << " contacts, Δt = 0.99 × " << w.dt_critical << " s, " << steps
                               << " steps: peak kinetic energy " << ke_max / e0
                               << " of the initial strain energy; friction took " << w.energy.dissipated_contacts / e0
                               << ", energy residual " << w.energy.residual() / e0 << " (not asserted here)");
  // Nothing puts energy in (fixed walls, no gravity), so the kinetic energy stays below what was stored at the
  // start; an instability would grow it (or, held by friction, feed the friction) without bound.
  CHECK(ke_max > 0.01 * e0);  // it did vibrate
  CHECK(ke_max < e0);
}

TEST_CASE("twice_the_critical_estimate_is_caught_by_the_guard") {
  // The step itself refuses a particle moving too far or passing through another; the domain, wall and
  // energy checks run every 100 steps, as a runner would. The loop is bounded whatever happens.
  auto run = [](World<3>& w, std::int64_t& caught_at, bool& finite) {
    std::string message;
    for (int s = 1; s <= 100000 && caught_at < 0; ++s) {
      try {
        w.step();
        if (s % 100 == 0) w.check_stability();
      } catch (const InstabilityError& e) {
        message = e.what();
        caught_at = s;
      }
    }
    finite = true;
    for (int i = 0; i < w.particles.size(); ++i) finite = finite && w.particles.x[i].allFinite();
    return message;
  };

  SUBCASE("frictional dense packing, energy traced: the unstable mode is held by friction") {
    // With friction the unstable shear–rotation mode cannot grow past the Coulomb limit: it settles into a
    // cycle that reverses the velocities every step and pours energy into friction (measured: 10 E0 after
    // 2000 steps, the velocities staying ~10⁻⁴ R per step). Only the energy balance shows it.
    auto w = dense_fcc(2, 0.5);
    w.timestep.safety = 2.0;
    w.trace_energy = true;
    w.init();
    w.update_energy();
    w.energy.initial = w.energy.kinetic + w.energy.strain;
    std::int64_t caught_at = -1;
    bool finite = false;
    const std::string message = run(w, caught_at, finite);
    MESSAGE("fcc, μ = 0.5, safety 2.0: caught at step " << caught_at << ": " << message);
    REQUIRE(caught_at > 0);
    CHECK(caught_at <= 2000);
    CHECK(finite);
    CHECK(message.find("step " + std::to_string(caught_at)) != std::string::npos);
    CHECK(message.find("particle ") != std::string::npos);
  }
  SUBCASE("no slip, energy not traced: the unstable mode grows until the packing flies apart") {
    auto w = perturbed_cubic(5, 1e3);  // 125 spheres, friction too high to slip
    w.timestep.safety = 2.0;
    w.init();
    std::int64_t caught_at = -1;
    bool finite = false;
    const std::string message = run(w, caught_at, finite);
    MESSAGE("simple cubic, no slip, safety 2.0: caught at step " << caught_at << ": " << message);
    REQUIRE(caught_at > 0);
    CHECK(caught_at <= 2000);
    CHECK(finite);  // caught by the one-step displacement check, before anything overflowed
    CHECK(message.find("step " + std::to_string(caught_at)) != std::string::npos);
    CHECK(message.find("particle ") != std::string::npos);
  }
}

TEST_CASE("fixed_timestep_above_estimate_is_refused") {
  auto probe = dense_fcc(2, 0.5);
  probe.init();
  const double estimate = probe.dt_critical;
  REQUIRE(estimate > 0);

  auto w = dense_fcc(2, 0.5);
  w.timestep.fixed = 1.5 * estimate;
  std::string message;
  try {
    w.init();
  } catch (const TimestepError& e) {
    message = e.what();
  }
  MESSAGE("fixed 1.5 × estimate: " << message);
  REQUIRE(!message.empty());
  auto shown = [](double x) {  // how the engine prints a number (default stream precision)
    std::ostringstream s;
    s << x;
    return s.str();
  };
  CHECK(message.find("fixed timestep") != std::string::npos);
  CHECK(message.find(shown(1.5 * estimate)) != std::string::npos);
  CHECK(message.find(shown(estimate)) != std::string::npos);

  // Just under the estimate it is taken as given.
  auto ok = dense_fcc(2, 0.5);
  ok.timestep.fixed = 0.99 * estimate;
  CHECK_NOTHROW(ok.init());
  CHECK(ok.dt == 0.99 * estimate);
}
