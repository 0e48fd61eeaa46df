// Determinism across thread counts (ARCHITECTURE: "same scene + same seed → identical results, for any
// thread count"): one thread computes all the pairs whose A is of one group of particles and adds their forces to
// A's sum, and to B's when B is of the group; the other pairs write slots, which each particle adds in a fixed
// order; sums over contacts or particles are taken in fixed blocks added in order. So one and two threads must give the
// same bits, not merely close numbers.
#include <doctest/doctest.h>
#include <omp.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#include "tests/common/test_worlds.hpp"

using namespace mc;

namespace {

// 4356 spheres of radii 0.95–1.05 r on a face-centred cubic lattice of 11 × 11 × 9 cells compressed by 0.5 %
// (most neighbours overlap, some do not touch), in a box of six planes; the top and one side wall move in.
// Friction, local damping, gravity and energy tracing are all on, so every optional path of the cycle runs.
// More particles than the engine's threshold for splitting a loop between threads (kParallelMin = 4096 in
// engine/parallel.hpp), so the particle loops run on the whole team too, not only the contact loops.
World<3> compressed_packing() {
  LinearParams prm;
  prm.modulus = 1e8;
  prm.kn_ks_ratio = 2;
  prm.friction = 0.5;
  auto w = test::single_model_world<3, Linear>(prm);
  const double r = 1e-3, c = 0.005;
  const double a = 2 * std::sqrt(2.0) * r * (1 - c);
  const Vec<3> basis[4] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  const int n[3] = {11, 11, 9};
  RandomStream rng(4242);
  for (int i = 0; i < n[0]; ++i)
    for (int j = 0; j < n[1]; ++j)
      for (int k = 0; k < n[2]; ++k)
        for (const auto& b : basis)
          w.particles.add(a * (Vec<3>(i, j, k) + b), r * (0.95 + 0.1 * rng.uniform()), 2600, 0);
  WallMaterial wm;
  wm.kn = Linear::ball_kn<3>(prm, r);
  wm.ks = wm.kn / prm.kn_ks_ratio;
  wm.friction = 0.5;
  for (int d = 0; d < 3; ++d) {
    const Vec<3> e = Vec<3>::Unit(d);
    const double lo = -r, hi = (n[d] - 0.5) * a + r;
    w.walls.push_back(Wall<3>::plane(lo * e, e));
    w.walls.push_back(Wall<3>::plane(hi * e, -e));
    w.walls[w.walls.size() - 2].material = wm;
    w.walls.back().material = wm;
  }
  w.walls[5].control = WallControl::Velocity;  // top, z = hi
  w.walls[5].target_velocity = Vec<3>(0, 0, -0.1);
  w.walls[1].control = WallControl::Velocity;  // x = hi
  w.walls[1].target_velocity = Vec<3>(-0.05, 0, 0);
  w.gravity = Vec<3>(0, 0, -9.81);
  w.local_damping = 0.7;
  w.trace_energy = true;
  w.domain_lo = Vec<3>::Constant(-0.1);
  w.domain_hi = Vec<3>::Constant(0.1);
  return w;
}

struct Run {
  std::vector<Vec<3>> x, v, f;
  std::vector<Vec<3>> w;
  std::vector<Vec<3>> wall_force, wall_moment, wall_origin;
  EnergyTrace energy;
  double time = 0;
  std::int64_t rebuilds = 0;
  std::size_t contacts = 0;
};

Run run_with(int threads, int steps) {
  omp_set_num_threads(threads);
  auto w = compressed_packing();
  w.init();
  w.walls[5].ramp_time = w.walls[1].ramp_time = 100 * w.dt;
  w.update_energy();
  w.energy.initial = w.energy.kinetic + w.energy.strain;  // as the runner does when the scene traces energy
  for (int s = 0; s < steps; ++s) w.step();
  w.update_energy();
  w.check_stability();
  Run out;
  out.x = w.particles.x;
  out.v = w.particles.v;
  out.f = w.particles.f;
  out.w = w.particles.w;
  for (const auto& wl : w.walls) {
    out.wall_force.push_back(wl.force);
    out.wall_moment.push_back(wl.moment);
    out.wall_origin.push_back(wl.origin);
  }
  out.energy = w.energy;
  out.time = w.time;
  out.rebuilds = w.rebuilds;
  out.contacts = w.contact_count();
  return out;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

}  // namespace

TEST_CASE("one_and_two_threads_give_bit_identical_positions") {
  const int before = omp_get_max_threads();
  const int steps = 1000;
  const Run one = run_with(1, steps);
  const Run two = run_with(2, steps);
  omp_set_num_threads(before);

  double moved = 0;  // how much happened: the largest displacement of a particle relative to its radius
  const Run start = [] {
    auto w = compressed_packing();
    Run r;
    r.x = w.particles.x;
    return r;
  }();
  for (std::size_t i = 0; i < one.x.size(); ++i) moved = std::max(moved, (one.x[i] - start.x[i]).norm() / 1e-3);
  MESSAGE(one.x.size() << " spheres, " << one.contacts << " contacts, " << steps << " steps, " << one.rebuilds
                       << " neighbour-list rebuilds; largest displacement " << moved << " R; wall forces top "
                       << one.wall_force[5].transpose() << " N");
  CHECK(one.contacts > 2 * one.x.size());  // dense: several contacts per sphere
  CHECK(moved > 0.05);                     // and it moved (enough for the lists to be rebuilt)
  CHECK(one.rebuilds > 1);

  // Bit for bit, not approximately: compared as raw bytes.
  CHECK(same_bits(one.x, two.x));
  CHECK(same_bits(one.v, two.v));
  CHECK(same_bits(one.f, two.f));
  CHECK(same_bits(one.w, two.w));
  CHECK(same_bits(one.wall_force, two.wall_force));
  CHECK(same_bits(one.wall_moment, two.wall_moment));
  CHECK(same_bits(one.wall_origin, two.wall_origin));
  CHECK(std::memcmp(&one.energy, &two.energy, sizeof(EnergyTrace)) == 0);
  CHECK(one.time == two.time);
  CHECK(one.rebuilds == two.rebuilds);
  CHECK(one.contacts == two.contacts);
}

// A particle that is A in more pairs than its group has particles (kGroup = 512, engine/parallel.hpp): a sphere of
// radius 1 m pressed by 5 000 spheres of radius 2 cm, each overlapping it by δ = 0.1 mm, on the upper half of a
// Fibonacci lattice over its surface (5 000 pairs: more than kParallelMin, so the pass is split between threads). Its
// first 511 partners are of its group (near pairs, summed in the force pass on both sides), the others write slots.
// Its pairs as A must all be summed by one thread, in pair order: the resultant is then the closed form −Σ k_n δ n_k
// (about 2 500 contacts' force, downwards), and the same bits on one and two threads.
TEST_CASE("resultant_on_a_sphere_touching_more_contacts_than_a_block_holds") {
  const int before = omp_get_max_threads();
  const double big = 1.0, small = 0.02, overlap = 1e-4;
  const int shell = 5000;
  LinearParams prm;
  prm.modulus = 1e9;
  auto resultant = [&](int threads) {
    omp_set_num_threads(threads);
    auto w = test::single_model_world<3, Linear>(prm);
    w.domain_lo = Vec<3>::Constant(-1.5);
    w.domain_hi = Vec<3>::Constant(1.5);
    w.particles.add(Vec<3>::Zero(), big, 2600, 0);  // index 0: A in every pair it has
    const double golden = M_PI * (3.0 - std::sqrt(5.0));
    for (int k = 0; k < shell; ++k) {  // the upper half of a lattice of 2 × shell points
      const double z = 1.0 - (k + 0.5) / shell, rho = std::sqrt(1.0 - z * z);
      const Vec<3> n(rho * std::cos(golden * k), rho * std::sin(golden * k), z);
      w.particles.add((big + small - overlap) * n, small, 2600, 0);
    }
    w.init();
    const std::vector<Vec<3>> x = w.particles.x;  // where the force pass finds them
    w.step();
    CHECK(w.candidate_count() > std::size_t(shell));
    return std::make_pair(w.particles.f[0], x);
  };
  const auto [one, x] = resultant(1);
  const Vec<3> two = resultant(2).first;
  omp_set_num_threads(before);

  // The closed form from the positions as stored: each contact pushes the big sphere by k_n δ_k along −n_k.
  const double kn = Linear::pair<3>(prm, big, small).kn;
  Vec<3> expected = Vec<3>::Zero();
  for (int k = 1; k <= shell; ++k) {
    const Vec<3> d = x[k] - x[0];
    expected -= kn * (big + small - d.norm()) * d.normalized();
  }
  const double one_contact = kn * overlap;
  MESSAGE("resultant " << one.transpose() << " N, one contact's force " << one_contact << " N");
  CHECK(-expected.z() > 2000 * one_contact);
  // Each term is k_n δ to the round-off of positions near 1 m (1e-16 m against δ = 1e-4 m: 1e-12 of one contact's
  // force F), and n = 5 000 terms of size ≤ F summed in another order differ by at most about n² ε F ≈ 3e-9 F: 1e-8 F
  // bounds both, while a block of contacts left out or added twice would miss by a million newtons.
  CHECK((one - expected).norm() < 1e-8 * one_contact);
  CHECK(std::memcmp(one.data(), two.data(), sizeof(Vec<3>)) == 0);
}
