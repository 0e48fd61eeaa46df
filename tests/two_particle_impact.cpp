// Normal impact of two equal particles: closed forms for the linear spring (half period, restitution 1),
// the spring–dashpot (restitution exp(−πζ/√(1−ζ²))) and the Hertz contact (duration and maximum overlap).
#include <doctest/doctest.h>

#include <cmath>

#include "tests/common/relative.hpp"
#include "tests/common/test_worlds.hpp"

using namespace mc;

namespace {

struct Impact {
  double duration = 0, max_overlap = 0, rebound_speed = 0;
};

// Two particles of radius r approaching head-on at ±v/2 along x; runs until they separate.
template <int D, class Model>
Impact collide(const typename Model::Params& prm, double r, double rho, double v, double safety, int every = 1) {
  auto w = test::single_model_world<D, Model>(prm);
  Vec<D> a = Vec<D>::Zero(), b = Vec<D>::Zero();
  b[0] = 2 * r + 1e-9;  // just apart
  w.particles.add(a, r, rho, 0);
  w.particles.add(b, r, rho, 0);
  w.particles.v[0][0] = 0.5 * v;
  w.particles.v[1][0] = -0.5 * v;
  w.timestep.safety = safety;
  w.timestep.every = every;
  w.init();
  Impact out;
  double t_start = -1;
  for (int s = 0; s < 10000000; ++s) {
    w.step();
    const double overlap = 2 * r - (w.particles.x[1] - w.particles.x[0]).norm();
    if (overlap > 0 && t_start < 0) t_start = w.time - w.dt;  // contact began within the last step
    out.max_overlap = std::max(out.max_overlap, overlap);
    if (t_start >= 0 && overlap <= 0) {
      out.duration = w.time - t_start;
      break;
    }
  }
  out.rebound_speed = (w.particles.v[1] - w.particles.v[0])[0];
  return out;
}

template <int D>
void linear_elastic_impact() {
  LinearParams p;
  p.modulus = 1e8;
  p.kn_ks_ratio = 1;
  const double r = 1e-3, rho = 2600, v = 0.1;
  const Impact im = collide<D, Linear>(p, r, rho, v, 0.05);
  const double m = rho * Dim<D>::volume(r);
  const double kn = Linear::series(Linear::ball_kn<D>(p, r), Linear::ball_kn<D>(p, r));
  const double t_c = M_PI * std::sqrt(0.5 * m / kn);  // half period of the relative oscillation
  // The contact start and end are known only to within one step each: 2 dt out of ~60 steps of 0.05 t_crit.
  CHECK(im.duration == mc::test::relative(t_c, 0.02));
  // Central differences conserve the energy of a linear spring exactly; only the step in which the contact
  // opens or closes can gain or lose a little (≈ (ω dt)² / 8 with ω dt ≈ 0.05 here).
  CHECK(im.rebound_speed == mc::test::relative(v, 1e-3));
}

template <int D>
void viscous_impact(double zeta) {
  LinearParams p;
  p.modulus = 1e8;
  p.damping_ratio = zeta;
  const double v = 0.1;
  const Impact im = collide<D, Linear>(p, 1e-3, 2600, v, 0.02);
  const double e = std::exp(-M_PI * zeta / std::sqrt(1 - zeta * zeta));
  // Same one-step uncertainty as above, at 0.02 t_crit per step.
  CHECK(im.rebound_speed / v == mc::test::relative(e, 5e-3));
}

template <int D>
void hertz_impact() {
  HertzMindlinParams p;
  p.shear_modulus = 1e9;
  p.poisson = 0.2;
  const double r = 1e-3, rho = 2600, v = 0.5;
  // A constant step (estimated once, at 1 % overlap): central differences with a step that changes during
  // the impact are no longer symplectic, and the closed form is for an exact integration.
  const Impact im = collide<D, HertzMindlin>(p, r, rho, v, 0.02, 0);
  const double m = rho * Dim<D>::volume(r), m_eff = 0.5 * m;
  const auto c = HertzMindlin::pair<D>(p, r, r);
  // F = c u^{3/2}: energy ½ m* v² = ⅖ c u_max^{5/2}; duration 2.94320 u_max / v (Hertz 1882, Johnson 1985).
  const double u_max = std::pow(1.25 * m_eff * v * v / c.cn, 0.4);
  const double t_c = 2.9432 * u_max / v;
  CHECK(im.max_overlap == mc::test::relative(u_max, 0.01));
  CHECK(im.duration == mc::test::relative(t_c, 0.01));
  CHECK(im.rebound_speed == mc::test::relative(v, 1e-3));
}

}  // namespace

TEST_CASE("two_disc_linear_impact_duration_and_restitution") { linear_elastic_impact<2>(); }
TEST_CASE("two_sphere_linear_impact_duration_and_restitution") { linear_elastic_impact<3>(); }
TEST_CASE("two_disc_viscous_impact_restitution") {
  viscous_impact<2>(0.1);
  viscous_impact<2>(0.5);
}
TEST_CASE("two_sphere_viscous_impact_restitution") {
  viscous_impact<3>(0.1);
  viscous_impact<3>(0.5);
}
TEST_CASE("two_sphere_hertz_impact_duration_and_max_overlap") { hertz_impact<3>(); }
TEST_CASE("two_disc_hertz_impact_duration_and_max_overlap") { hertz_impact<2>(); }
