// Measurement circles and spheres (Tang 2013 §3.4): the average stress inside a compressed packing against the
// stress on its walls (a random packing, and a lattice whose stress is uniform), the best-fit velocity gradient
// of an affine velocity field, and the porosity from the exact part of each particle inside the region.
#include <doctest/doctest.h>
#include <omp.h>

#include <cmath>
#include <random>

#include "engine/measure.hpp"
#include "tests/common/relative.hpp"
#include "tests/common/test_worlds.hpp"

using namespace mc;

namespace {

// A box of walls (index 2k at the low end of axis k, 2k + 1 at the high end) around a random packing (a
// jittered grid, radii uniform in [0.8, 1.2] r0 and then grown by a common factor), brought to an isotropic
// stress and relaxed until it is at rest.
template <int D>
struct Packing {
  World<D> world;
  double r0 = 1e-3;
  int steps = 0;
  double unbalanced = 0;  // mean |resultant force| / mean |contact force|

  double extent(int k) const { return world.walls[2 * k + 1].origin[k] - world.walls[2 * k].origin[k]; }
  // The servo holds, and normal_stress() reports, force over the face the balls actually press on: the
  // current box cross-section, not the (longer) wall.
  void update_areas() {
    for (int k = 0; k < D; ++k) {
      double a = 1;
      for (int j = 0; j < D; ++j)
        if (j != k) a *= extent(j);
      world.walls[2 * k].servo_area = world.walls[2 * k + 1].servo_area = a;
    }
  }
  double wall_stress(int k) const {
    return 0.5 * (world.walls[2 * k].normal_stress() + world.walls[2 * k + 1].normal_stress());
  }
  // Σ over all particles and contacts of (x^c − x^p) F^cᵀ / V_box. In equilibrium the ball–ball terms cancel
  // into the ball–wall ones, so this is −(the wall stresses) whatever the fabric: an exact check of the
  // forces and levers the measurement uses, and a measure of the inner stress without the walls' lag.
  Tensor<D> box_stress() const {
    Tensor<D> t = Tensor<D>::Zero();
    double v = 1;
    for (int i = 0; i < world.particles.size(); ++i)
      world.for_each_contact_of(i, [&](const Vec<D>& f, const Vec<D>& l) { t += l * f.transpose(); });
    for (int k = 0; k < D; ++k) v *= extent(k);
    return t / v;
  }
  Region<D> centre_region(double fraction) const {
    Region<D> r;
    double size = kInf;
    for (int k = 0; k < D; ++k) {
      r.centre[k] = 0.5 * (world.walls[2 * k].origin[k] + world.walls[2 * k + 1].origin[k]);
      size = std::min(size, extent(k));
    }
    r.radius = fraction * size;
    return r;
  }
};

template <int D>
Packing<D> compressed_packing(int per_side, double target, unsigned seed) {
  LinearParams prm;
  prm.modulus = 1e8;  // overlaps ≈ 2 % of r at 1 MPa
  // Frictionless: with friction (μ = 0.1 tried) the layers along each flat wall lock into stiff plates that
  // carry 20–50 % more of the stress parallel to the wall, and the centre of a 10-particle box reads only
  // 0.70–0.80 of the wall stress. That is the packing, not the measurement; without friction it is 3–5 %.
  prm.friction = 0.0;
  Packing<D> pk{test::single_model_world<D, Linear>(prm)};
  World<D>& w = pk.world;
  const double r0 = pk.r0, s = 2.6 * r0, L = per_side * s;  // 2.6 r0 > 2.4 r0 + jitter: no initial overlap
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> radius(0.8 * r0, 1.2 * r0), jitter(-0.05 * r0, 0.05 * r0);
  int count = 1;
  for (int k = 0; k < D; ++k) count *= per_side;
  for (int c = 0; c < count; ++c) {
    Vec<D> x;
    for (int k = 0, rest = c; k < D; ++k, rest /= per_side) x[k] = (rest % per_side + 0.5) * s + jitter(rng);
    w.particles.add(x, radius(rng), 2600, 0);
  }
  for (int k = 0; k < D; ++k)
    for (int side = 0; side < 2; ++side) {
      Vec<D> point = Vec<D>::Constant(0.5 * L), normal = Vec<D>::Zero();
      point[k] = side * L;
      normal[k] = side ? -1 : 1;
      Wall<D> wl;
      if constexpr (D == 2) {
        // Segments reaching well past the corners, so the box stays closed as the walls move in.
        Vec<2> along(-normal[1], normal[0]);
        wl = Wall<2>::segment(point - L * along, point + L * along, Vec<2>::Constant(0.5 * L));
      } else {
        wl = Wall<3>::plane(point, normal);
      }
      wl.material.kn = wl.material.ks = Linear::ball_kn<D>(prm, r0);
      w.walls.push_back(wl);
    }
  w.local_damping = 0.7;
  w.init();
  const int max_steps = 150000;
  // Radius expansion (PFC): every particle grows in place inside the fixed walls, so the packing densifies
  // everywhere at once. Pushing the walls in instead compacts from the outside and leaves a stiffer, more
  // stressed skin around a less stressed core that the walls do not see (tried: the centre then read 5–15 %
  // below the walls, and closing the initial gaps fast enough kinetically overshoots the target stress).
  for (double s_in = 0; s_in < target && pk.steps < max_steps; s_in = -pk.box_stress().trace() / D) {
    // 2e-4 per step moves the contacts by ≈ 4e-4 r0 per step, a few % of the final overlap; slower near the end.
    const double g = 1 + 2e-4 * std::max(0.05, 1 - s_in / target);
    for (int i = 0; i < w.particles.size(); ++i) {
      w.particles.radius[i] *= g;
      w.particles.mass[i] *= std::pow(g, D);
      w.particles.inertia[i] *= std::pow(g, D + 2);
    }
    w.init();  // the neighbour lists do not know that the radii grew
    w.step();
    ++pk.steps;
  }
  // Then servo walls hold the target while the packing comes to rest, moving at most 1e-4 r0 per step (the
  // overlaps are ≈ 2e-2 r0), so they never run ahead of the packing.
  for (auto& wl : w.walls) {
    wl.control = WallControl::Servo;
    wl.target_stress = target;
    wl.servo_max_speed = 1e-4 * r0 / w.dt;
  }
  for (;;) {
    pk.update_areas();
    w.step();
    ++pk.steps;
    if (pk.steps % 200 != 0) continue;
    bool held = true;
    for (int k = 0; k < D; ++k) held = held && std::abs(pk.wall_stress(k) / target - 1) < 2e-4;
    double f_res = 0, f_con = 0;
    int n_con = 0;
    for (int i = 0; i < w.particles.size(); ++i) f_res += w.particles.f[i].norm();
    w.for_each_contact_force([&](const Vec<D>& force) {
      if (const double f = force.norm(); f > 0) f_con += f, ++n_con;
    });
    pk.unbalanced = (f_res / w.particles.size()) / (f_con / std::max(n_con, 1));
    // At rest: walls at the target, and the mean unbalanced force below 1e-5 of the mean contact force.
    if ((held && pk.unbalanced < 1e-5) || pk.steps >= max_steps) break;
  }
  pk.update_areas();
  return pk;
}

template <int D>
void circle_stress_equals_wall_stress(int per_side) {
  const double target = 1e6;
  Packing<D> pk = compressed_packing<D>(per_side, target, 2024);
  const World<D>& w = pk.world;
  REQUIRE(pk.unbalanced < 1e-5);  // the comparison below assumes equilibrium
  double ke = 0, strain = 0;
  for (int i = 0; i < w.particles.size(); ++i) ke += 0.5 * w.particles.mass[i] * w.particles.v[i].squaredNorm();
  for (const auto& s : w.sets) strain += s->strain_energy(w.particles, w.walls).value();
  const Region<D> region = pk.centre_region(0.35);
  const Tensor<D> sigma = average_stress(w, region), box = pk.box_stress();
  int inside = 0;
  for (int i = 0; i < w.particles.size(); ++i) inside += region.contains(w.particles.x[i]);
  MESSAGE(D << "D: " << w.particles.size() << " particles, " << pk.steps << " steps, unbalanced force ratio "
            << pk.unbalanced << ", kinetic/strain energy " << ke / strain);
  MESSAGE("region: " << inside << " particle centres, porosity " << porosity(w, region) << ", coordination number "
                     << coordination_number(w, region));
  MESSAGE("region stress [Pa] (tension positive):\n" << sigma << "\nwhole box:\n" << box);
  double wall_mean = 0, region_mean = 0;
  for (int k = 0; k < D; ++k) {
    MESSAGE("axis " << k << ": wall " << pk.wall_stress(k) << " Pa, region " << -sigma(k, k) << " Pa, ratio "
                    << -sigma(k, k) / pk.wall_stress(k));
    wall_mean += pk.wall_stress(k) / D;
    region_mean -= sigma(k, k) / D;
  }
  // The whole assembly carries exactly the wall stress (box_stress), but for the box: a ball–wall contact point
  // lies δ/2 behind the wall (Tang 3.4, as in PFC), so the sum spans L + δ, not L (measured +0.05 % in 2D,
  // +0.2 % in 3D); the unbalanced forces left add ~1e-5.
  for (int k = 0; k < D; ++k) CHECK(-box(k, k) == mc::test::relative(pk.wall_stress(k), 5e-3));
  // The region does not, to 2 %, in a random packing of this size: force chains make the stress of ~350
  // (2D) / ~180 (3D) particles fluctuate, and the layers along the walls carry more than the core, so the
  // region reads low on average (by ≈ 3 % in 2D, 5 % in 3D). Over 9 packings (seeds 1–8 and this one) the
  // region/wall ratio of single components spanned 0.90–1.05 (2D, 900 particles; 1600 did not narrow it:
  // 0.92–1.03) and 0.86–1.10 (3D, 1000); of the mean stress 0.91–1.03 and 0.90–1.01. The tolerances are
  // about 1.5 times the largest deviation seen. They catch a wrong sign, a factor of 2 or, in 3D, a lost
  // porosity factor (1 − n ≈ 0.65); the uniform lattice below checks the formula itself to 2 %.
  const double tol_component = D == 2 ? 0.15 : 0.20, tol_mean = D == 2 ? 0.12 : 0.15;
  CHECK(region_mean == mc::test::relative(wall_mean, tol_mean));
  for (int k = 0; k < D; ++k) CHECK(-sigma(k, k) == mc::test::relative(pk.wall_stress(k), tol_component));
  // Off-diagonal: zero on average under an isotropic load; over the same packings at most 5 % (2D) and 9 %
  // (3D) of the mean stress.
  for (int k = 0; k < D; ++k)
    for (int l = 0; l < D; ++l)
      if (k != l) CHECK(std::abs(sigma(k, l)) < (D == 2 ? 0.08 : 0.12) * wall_mean);
}

// Equal particles on a square (2D) / simple cubic (3D) lattice of spacing s = 2r − δ between fixed walls that
// overlap the outer particles by δ too: every contact carries the same force F, every particle is at rest,
// and the stress is uniform, σ = −F/s^(D−1) in each direction. The measurement must reproduce it exactly
// but for how the region cuts the lattice.
template <int D>
void lattice_stress(int per_side) {
  LinearParams prm;
  prm.modulus = 1e8;
  auto w = test::single_model_world<D, Linear>(prm);
  // 5 % overlaps: a lever taken as r instead of r − δ/2 (Tang 3.56) would be off by 2.5 %.
  const double r = 1e-3, delta = 0.05 * r, s = 2 * r - delta;
  int count = 1;
  for (int k = 0; k < D; ++k) count *= per_side;
  for (int c = 0; c < count; ++c) {
    Vec<D> x;
    for (int k = 0, rest = c; k < D; ++k, rest /= per_side) x[k] = (rest % per_side + 0.5) * s;
    w.particles.add(x, r, 2600, 0);
  }
  const double lo = 0.5 * delta, hi = per_side * s - 0.5 * delta, L = hi - lo;
  for (int k = 0; k < D; ++k)
    for (int side = 0; side < 2; ++side) {
      Vec<D> point = Vec<D>::Constant(0.5 * (lo + hi)), normal = Vec<D>::Zero();
      point[k] = side ? hi : lo;
      normal[k] = side ? -1 : 1;
      Wall<D> wl = Wall<D>::plane(point, normal);
      wl.material.kn = wl.material.ks = Linear::ball_kn<D>(prm, r);  // same series stiffness as ball–ball
      wl.servo_area = std::pow(L, D - 1);
      w.walls.push_back(wl);
    }
  w.init();
  w.step();  // forces from the positions; they balance, so nothing moves
  const double F = Linear::pair<D>(prm, r, r).kn * delta, exact = F / std::pow(s, D - 1);
  const Region<D> region{Vec<D>::Constant(0.5 * (lo + hi)), 0.35 * L};
  const Tensor<D> sigma = average_stress(w, region);
  const double solid = 1 - porosity(w, region);
  MESSAGE(D << "D lattice: exact " << exact << " Pa, walls " << w.walls[0].normal_stress() << " Pa, region "
            << -sigma(0, 0) << " Pa (ratio " << -sigma(0, 0) / exact << "), solid fraction " << solid << " (lattice "
            << Dim<D>::volume(r) / std::pow(s, D) << ")");
  // Each wall carries n^(D−1) forces F over (n s − δ)^(D−1): exact arithmetic.
  for (const auto& wl : w.walls)
    CHECK(wl.normal_stress() == mc::test::relative(exact * std::pow(per_side * s / L, D - 1), 1e-9));
  // Every particle in the region has the same Σ (x^c − x^p) F^c = −s F per axis, so (3.63) must give exactly
  // (1 − n) s F / V_p: this checks the levers, the sign and the factor to round-off.
  CHECK(coordination_number(w, region) == 2 * D);
  for (int k = 0; k < D; ++k) {
    CHECK(-sigma(k, k) == mc::test::relative(solid * s * F / Dim<D>::volume(r), 1e-12));
    for (int l = 0; l < D; ++l)
      if (l != k) CHECK(sigma(k, l) == 0.0);
  }
  // Against the true stress the only error left is how the region cuts the lattice: its solid fraction is not
  // quite the lattice's V_p/s^D. Measured 0.5 % (2D) and 1.2 % (3D) here, and within ±2 % for any radius
  // from 0.22 L to 0.47 L.
  for (int k = 0; k < D; ++k) CHECK(-sigma(k, k) == mc::test::relative(exact, 0.02));
}

template <int D>
void affine_field(int n) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  Tensor<D> L;
  Vec<D> c, shift;
  for (int i = 0; i < D; ++i) {
    c[i] = u(rng);
    shift[i] = 10 + u(rng);  // far from the origin: the fit must centre the positions (3.69)–(3.70)
    for (int j = 0; j < D; ++j) L(i, j) = u(rng);
  }
  World<D> w;
  for (int p = 0; p < n; ++p) {
    Vec<D> x;
    for (int k = 0; k < D; ++k) x[k] = u(rng);
    const int id = w.particles.add(shift + x, 0.01, 1000, 0);
    w.particles.v[id] = L * w.particles.x[id] + c;
  }
  // The region leaves out part of the cloud: only the particles inside enter the fit.
  const Region<D> region{shift, 0.8};
  const Tensor<D> fit = best_fit_velocity_gradient(w, region);
  MESSAGE(D << "D best-fit velocity gradient relative error " << (fit - L).norm() / L.norm());
  // The field is exactly affine, so the least-squares fit is exact up to round-off: ~1e-15 times the
  // condition number of Σ x̃ x̃ᵀ (of order 1 for a uniform cloud) and the ratio |x|/|x̃| ≈ 10.
  CHECK((fit - L).norm() < 1e-10 * L.norm());

  StrainIntegrator<D> strain{region};
  w.dt = 1e-2;
  const int calls = 100;
  for (int k = 0; k < calls; ++k) strain.update(w);
  const Tensor<D> expected = 0.5 * (L + L.transpose()) * (calls * w.dt);
  // 100 additions of a term exact to ~1e-15: the sum drifts by at most ~1e-13 relative.
  CHECK((strain.strain - expected).norm() < 1e-10 * expected.norm());

  // Sums in fixed blocks of particles, added in order: the same bits on one thread as on two (n > kParallelMin).
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const Tensor<D> fit1 = best_fit_velocity_gradient(w, region);
  const double n1 = porosity(w, region);
  omp_set_num_threads(2);
  CHECK(best_fit_velocity_gradient(w, region) == fit1);
  CHECK(porosity(w, region) == n1);
  omp_set_num_threads(threads);

  // Too few particles to fit a gradient: NaN, not a made-up number.
  World<D> few;
  for (int p = 0; p < D; ++p) few.particles.add(shift + Vec<D>::Constant(0.1 * p), 0.01, 1000, 0);
  CHECK(std::isnan(best_fit_velocity_gradient(few, region)(0, 0)));
}

// Part of a disc (2D) / ball (3D) of radius r centred at (d, 0[, 0]) inside the region of radius R at the
// origin, by chords along the last axis: the length of the overlap of the two chords over a fine midpoint
// grid of the remaining coordinates. Independent of the lens formulas.
double chord_area_2d(double R, double r, double d, int n) {
  const double lo = std::max(-R, d - r), hi = std::min(R, d + r), h = (hi - lo) / n;
  double a = 0;
  for (int i = 0; i < n; ++i) {
    const double x = lo + (i + 0.5) * h;
    const double h1 = R * R - x * x, h2 = r * r - (x - d) * (x - d);
    if (h1 > 0 && h2 > 0) a += 2 * std::sqrt(std::min(h1, h2)) * h;
  }
  return a;
}

double chord_volume_3d(double R, double r, double d, int n) {
  const double lo = std::max(-R, d - r), hi = std::min(R, d + r), hx = (hi - lo) / n, hy = std::min(R, r) / n;
  double v = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = lo + (i + 0.5) * hx, y = (j + 0.5) * hy;  // y ≥ 0 half, doubled below
      const double h1 = R * R - x * x - y * y, h2 = r * r - (x - d) * (x - d) - y * y;
      if (h1 > 0 && h2 > 0) v += 2 * 2 * std::sqrt(std::min(h1, h2)) * hx * hy;
    }
  return v;
}

template <int D>
double single_particle_porosity(double R, double r, double d) {
  World<D> w;
  Vec<D> centre = Vec<D>::Constant(0.3), x = centre;
  x[0] += d;
  w.particles.add(x, r, 1000, 0);
  return porosity(w, Region<D>{centre, R});
}

}  // namespace

TEST_CASE("measurement_circle_stress_tracks_wall_stress_in_a_random_packing_2d") {
  circle_stress_equals_wall_stress<2>(30);
}
TEST_CASE("measurement_sphere_stress_tracks_wall_stress_in_a_random_packing_3d") {
  circle_stress_equals_wall_stress<3>(10);
}

TEST_CASE("measurement_circle_stress_equals_wall_stress_in_a_uniformly_compressed_lattice_2d") {
  lattice_stress<2>(20);
}
TEST_CASE("measurement_sphere_stress_equals_wall_stress_in_a_uniformly_compressed_lattice_3d") {
  lattice_stress<3>(10);
}

TEST_CASE("best_fit_strain_rate_recovers_affine_field_2d") { affine_field<2>(5000); }
TEST_CASE("best_fit_strain_rate_recovers_affine_field_3d") { affine_field<3>(5000); }

TEST_CASE("porosity_of_a_single_particle_inside_and_straddling") {
  const double R = 1.0, r = 0.3;
  // Inside, outside, and a particle containing the whole region: closed forms, to round-off.
  CHECK(single_particle_porosity<2>(R, r, 0.5) == mc::test::relative(1 - r * r / (R * R), 1e-14));
  CHECK(single_particle_porosity<3>(R, r, 0.5) == mc::test::relative(1 - r * r * r / (R * R * R), 1e-14));
  CHECK(single_particle_porosity<2>(R, r, 1.31) == 1.0);
  CHECK(single_particle_porosity<3>(R, r, 1.31) == 1.0);
  CHECK(single_particle_porosity<2>(R, 2.0, 0.5) == doctest::Approx(0.0).epsilon(1e-14));
  CHECK(single_particle_porosity<3>(R, 2.0, 0.5) == doctest::Approx(0.0).epsilon(1e-14));
  // Straddling the boundary, centre inside and outside, and a particle larger than the region.
  for (const auto& [rr, d] : {std::pair{r, 0.85}, std::pair{r, 1.15}, std::pair{r, 0.71}, std::pair{1.5, 1.2}}) {
    const double lens2 = (1 - single_particle_porosity<2>(R, rr, d)) * M_PI * R * R;
    const double lens3 = (1 - single_particle_porosity<3>(R, rr, d)) * 4.0 / 3.0 * M_PI * R * R * R;
    const double grid2 = chord_area_2d(R, rr, d, 1000000), grid3 = chord_volume_3d(R, rr, d, 2000);
    MESSAGE("r = " << rr << ", d = " << d << ": area " << lens2 << " vs grid " << grid2 << ", volume " << lens3
                   << " vs grid " << grid3);
    // The chord length is continuous with √-type edges, so the midpoint grid errs by O(h^1.5) relative:
    // ~1e-9 with 10^6 cells (2D), ~1e-5 with 2000² cells (3D); 1e-4 leaves room for both.
    CHECK(lens2 == mc::test::relative(grid2, 1e-4));
    CHECK(lens3 == mc::test::relative(grid3, 1e-4));
  }
}
