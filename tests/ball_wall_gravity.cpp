// A single ball under gravity: free flight (central differences are exact for a constant acceleration) and
// rest on a fixed wall (the wall carries m g through an overlap m g / k_n, springs of ball and wall in series).
#include <doctest/doctest.h>

#include <cmath>

#include "tests/common/relative.hpp"
#include "tests/common/test_worlds.hpp"

using namespace mc;

namespace {

LinearParams stiff_linear() {
  LinearParams p;
  p.modulus = 1e8;
  p.kn_ks_ratio = 1;
  p.friction = 0.5;
  return p;
}

WallMaterial wall_material(double kn) {
  WallMaterial m;
  m.kn = kn;
  m.ks = kn;
  m.friction = 0.5;
  return m;
}

// A world whose only phase interacts with nothing: no contact set, so nothing zeroes the particles' force sums in a
// force pass (World::compute_forces does), and no stiffness to take a timestep from (a fixed one).
template <int D>
World<D> world_without_contacts() {
  World<D> w;
  w.model_of = {{-1}};
  w.domain_lo = Vec<D>::Constant(-1e3);
  w.domain_hi = Vec<D>::Constant(1e3);
  w.timestep.fixed = 1e-5;
  return w;
}

// The engine stores p.v as the velocity at t − Δt/2 (particles.hpp; move_particles does v += a Δt, then
// x += v Δt, Tang 3.18–3.20). Starting from x(0) = x0 and v(−Δt/2) = v0 under a constant g, after n steps
//   v(t_n − Δt/2) = v0 + n g Δt
//   x(t_n)        = x0 + Σ_{k=1..n} (v0 + k g Δt) Δt = x0 + v0 t_n + ½ g t_n² + ½ g Δt t_n.
// This is the exact trajectory x0 + u0 t + ½ g t² with u0 = v(0) = v0 + g Δt/2 (the velocity half a step
// later): for a constant acceleration the scheme has no truncation error, only round-off.
template <int D>
void free_fall(World<D> w, const Vec<D>& g, const Vec<D>& x0, const Vec<D>& v0, int steps) {
  const double r = 1e-3;
  w.particles.add(x0, r, 2600, 0);
  w.particles.v[0] = v0;
  w.gravity = g;
  // A wall far below (outside the neighbour reach all along): present in the world, never touching.
  Vec<D> below = Vec<D>::Zero();
  below[D - 1] = -100;
  Vec<D> up = Vec<D>::Zero();
  up[D - 1] = 1;
  w.walls.push_back(Wall<D>::plane(below, up));
  w.walls.back().material = wall_material(1e9);
  w.init();
  const double dt = w.dt;
  REQUIRE(dt > 0);
  double worst_x = 0, worst_v = 0;
  bool same_dt = true;  // the estimate for a ball without contacts never changes
  for (int n = 1; n <= steps; ++n) {
    w.step();
    same_dt = same_dt && w.dt == dt;
    const double nn = n;
    const Vec<D> x_exact = x0 + nn * dt * v0 + 0.5 * nn * (nn + 1) * dt * dt * g;
    const Vec<D> v_exact = v0 + nn * dt * g;
    worst_x = std::max(worst_x, (w.particles.x[0] - x_exact).norm() / x_exact.norm());
    worst_v = std::max(worst_v, (w.particles.v[0] - v_exact).norm() / v_exact.norm());
  }
  MESSAGE("D = " << D << ", " << steps << " steps of " << dt << " s: worst relative error of x " << worst_x << ", of v "
                 << worst_v);
  // Round-off only: each step adds one rounded increment to v and one to x, each off by at most u = 2^-53 ≈
  // 1.1·10⁻¹⁶ of the result. Adding the same g Δt every step makes these roundings systematic rather than a
  // random walk, so the bound is n u = 5.5·10⁻¹³ for n = 5000 steps, under the 10⁻¹² asked. Positions are
  // compared relative to |x| (a coordinate cannot be stored closer than u|x|), velocities relative to |v|.
  CHECK(same_dt);
  CHECK(worst_x < 1e-12);
  CHECK(worst_v < 1e-12);
  // Gravity acts through the centre: no spin, and no contact ever formed.
  CHECK(w.particles.w[0].norm() == 0.0);
  CHECK(w.walls[0].force.norm() == 0.0);
}

// A ball dropped onto (placed just touching) a fixed wall, local damping 0.7, until it is at rest.
template <int D>
void rest_on_wall() {
  const LinearParams prm = stiff_linear();
  auto w = test::single_model_world<D, Linear>(prm);
  const double r = 1e-3, rho = 2600, g = 9.81;
  const double kw = D == 2 ? 1e9 : 1e6;  // wall springs of the order of the ball's (2 E_c, resp. 4 R E_c)
  Vec<D> x = Vec<D>::Zero();
  x[D - 1] = r + 2e-6;  // released 2 µm above the wall
  w.particles.add(x, r, rho, 0);
  Vec<D> gv = Vec<D>::Zero();
  gv[D - 1] = -g;
  w.gravity = gv;
  w.local_damping = 0.7;
  Vec<D> up = Vec<D>::Zero();
  up[D - 1] = 1;
  w.walls.push_back(Wall<D>::plane(Vec<D>::Zero(), up));
  w.walls.back().material = wall_material(kw);
  w.init();
  const double m = w.particles.mass[0];
  const double kn = Linear::wall<D>(prm, w.walls[0].material, r).kn;  // ball and wall springs in series
  int steps = 0;
  for (; steps < 200000; ++steps) {
    w.step();
    // At rest when the wall carries the weight to well below the tolerance and the ball no longer moves.
    if (steps > 100 && std::abs(-w.walls[0].force[D - 1] - m * g) < 1e-9 * m * g &&
        w.particles.v[0].norm() * w.dt < 1e-9 * (m * g / kn))
      break;
  }
  const double fw = -w.walls[0].force[D - 1];  // the ball pushes the wall down
  const double overlap = r - w.particles.x[0][D - 1];
  MESSAGE("D = " << D << ": settled in " << steps << " steps; wall force / m g − 1 = " << fw / (m * g) - 1
                 << ", overlap k_n / (m g) − 1 = " << overlap * kn / (m * g) - 1);
  // Local damping removes a fixed fraction of the out-of-balance force each step, so the residual decays
  // geometrically to round-off (the overlap, ~1e-9 m, is resolved to ε·R ≈ 2e-19 m): 1e-6 is far above it.
  CHECK(fw == mc::test::relative(m * g, 1e-6));
  CHECK(overlap == mc::test::relative(m * g / kn, 1e-6));
  // Nothing tangential: no shear force on the wall and no spin.
  CHECK(std::abs(w.walls[0].force[0]) <= 1e-12 * m * g);
  CHECK(w.particles.w[0].norm() == 0.0);
}

}  // namespace

TEST_CASE("ball_free_fall_is_exact_for_central_differences") {
  free_fall<2>(test::single_model_world<2, Linear>(stiff_linear()), Vec<2>(0.7, -9.81), Vec<2>(0.01, 0.2),
               Vec<2>(0.3, 1.5), 5000);
  free_fall<3>(test::single_model_world<3, Linear>(stiff_linear()), Vec<3>(0.4, -0.3, -9.81), Vec<3>(0.01, -0.02, 0.2),
               Vec<3>(0.3, 0.1, 1.5), 5000);
}

// The same flight in a world without any contact model: the weight must not pile up from step to step in the
// particle's force sum (which holds the last step's resultant until the next force pass zeroes it).
TEST_CASE("ball_free_fall_without_a_contact_model_is_exact_for_central_differences") {
  free_fall<2>(world_without_contacts<2>(), Vec<2>(0.7, -9.81), Vec<2>(0.01, 0.2), Vec<2>(0.3, 1.5), 5000);
  free_fall<3>(world_without_contacts<3>(), Vec<3>(0.4, -0.3, -9.81), Vec<3>(0.01, -0.02, 0.2), Vec<3>(0.3, 0.1, 1.5),
               5000);
}

TEST_CASE("ball_resting_on_wall_carries_mg") {
  rest_on_wall<2>();
  rest_on_wall<3>();
}
