// Rolling resistance (contact_models/rolling_resistance.hpp) on a ball on a slope θ, friction high enough that it
// never slides. About the centre, I α = F R − M_r; along the slope, m a = m g sin θ − F; rolling, a = α R. With the
// rolling moment at its bound M_r = μ_r R m g cos θ:
//   a = g (sin θ − μ_r cos θ)/(1 + I/(m R²)),
// and where tan θ ≤ μ_r the moment m g sin θ R that holds the ball stays within the bound: it does not roll.
#include <doctest/doctest.h>

#include <cmath>

#include "contact_models/rolling_resistance.hpp"
#include "tests/common/test_worlds.hpp"

using namespace mc;

namespace {

constexpr double kR = 1e-3, kRho = 2600, kG = 9.81;

struct Slope {
  double a;       // mean acceleration down the slope over the window [m/s²]
  double travel;  // distance rolled over the window [m]
  double vmax;    // largest speed over the window [m/s]
};

// A ball released at rest at its equilibrium overlap on a plane tilted θ about the out-of-plane axis (2D) or y (3D).
// The dashpots (ζ = 0.3) damp the contact's elastic transient; in steady rolling the contact point does not move,
// so they do no work there.
template <int D>
Slope roll(double theta, double mu_r, int transient, int window) {
  RollingResistanceParams prm;
  prm.contact.modulus = 1e8;
  prm.contact.kn_ks_ratio = 1;
  prm.contact.friction = 0.9;  // rolling needs (I/(I + m R²)) (tan θ − μ_r) ≤ μ: far below 0.9 here
  prm.contact.damping_ratio = 0.3;
  prm.rolling_friction = mu_r;
  auto w = test::single_model_world<D, RollingResistance>(prm);
  WallMaterial wm;
  wm.kn = wm.ks = D == 2 ? 1e9 : 1e6;
  wm.friction = prm.contact.friction;
  Vec<D> n = Vec<D>::Zero(), s = Vec<D>::Zero(), gv = Vec<D>::Zero();
  n[0] = -std::sin(theta), n[D - 1] = std::cos(theta);  // the plane's normal
  s[0] = std::cos(theta), s[D - 1] = std::sin(theta);   // up the slope
  s = -s;                                                // down it
  gv[D - 1] = -kG;
  w.walls.push_back(Wall<D>::plane(Vec<D>::Zero(), n));
  w.walls.back().material = wm;
  w.gravity = gv;
  const double m = kRho * Dim<D>::volume(kR);
  const double u = m * kG * std::cos(theta) / RollingResistance::wall<D>(prm, wm, kR).contact.kn;
  w.particles.add(n * (kR - u), kR, kRho, 0);
  w.init();
  for (int i = 0; i < transient; ++i) w.step();
  const double t0 = w.time, v0 = w.particles.v[0].dot(s);
  const Vec<D> x0 = w.particles.x[0];
  double vmax = 0;
  for (int i = 0; i < window; ++i) {
    w.step();
    vmax = std::max(vmax, w.particles.v[0].norm());
  }
  return {(w.particles.v[0].dot(s) - v0) / (w.time - t0), (w.particles.x[0] - x0).dot(s), vmax};
}

template <int D>
double rolling_acceleration(double theta, double mu_r) {
  return kG * (std::sin(theta) - mu_r * std::cos(theta)) / (1 + Dim<D>::inertia_factor);
}

template <int D>
void rolls_at_the_closed_form() {
  const double theta = 20 * M_PI / 180;  // tan θ = 0.364
  for (const double mu_r : {0.0, 0.1, 0.3}) {
    const Slope r = roll<D>(theta, mu_r, 2000, 4000);
    const double a = rolling_acceleration<D>(theta, mu_r);
    MESSAGE("D = " << D << ", μ_r = " << mu_r << ": a / a_exact − 1 = " << r.a / a - 1);
    // The engine's lever for the friction force is R − U/2 (contact point at mid-overlap), not R, while the
    // moment's bound is μ_r R F_n: a differs from the closed form by (1 + μ_r cos θ/(sin θ − μ_r cos θ)) U/2R,
    // with U/R ≈ 5·10⁻⁷ up to 1.3·10⁻⁶ at μ_r = 0.3. The moment sits at its bound all the window (it does not
    // oscillate: the rotation only grows), so what is left besides is the decayed transient and round-off.
    CHECK(std::abs(r.a / a - 1) < 3e-6);
  }
}

template <int D>
void stays_where_tan_theta_is_below_mu_r() {
  const double theta = 4 * M_PI / 180;  // tan θ = 0.070 < μ_r = 0.1
  const Slope held = roll<D>(theta, 0.1, 20000, 4000);
  const Slope free = roll<D>(theta, 0.0, 20000, 4000);
  MESSAGE("D = " << D << ", tan θ < μ_r: rolled " << held.travel << " m in the window (free: " << free.travel
                 << " m), largest speed " << held.vmax << " m/s");
  // Free, the ball rolls ½ a t² + v t down the slope in the window; held, only the elastic rocking of the rolling
  // spring is left, damped through the shear dashpot: six orders of magnitude less is far from either.
  CHECK(free.travel > 0);
  CHECK(std::abs(held.travel) < 1e-6 * free.travel);
}

}  // namespace

TEST_CASE("ball_with_rolling_resistance_rolls_down_a_slope_at_g_sin_minus_mu_r_cos") {
  rolls_at_the_closed_form<2>();
  rolls_at_the_closed_form<3>();
}

TEST_CASE("ball_with_rolling_resistance_stays_on_a_slope_flatter_than_mu_r") {
  stays_where_tan_theta_is_below_mu_r<2>();
  stays_where_tan_theta_is_below_mu_r<3>();
}
