// Determinism across thread counts (ARCHITECTURE: "same scene + same seed → identical results, for any
// thread count"): every contact writes its own slot, each particle sums its slots in a fixed order, and sums
// over contacts or particles are taken in fixed blocks added in order. So one and two threads must give the
// same bits, not merely close numbers.
#include <doctest/doctest.h>
#include <omp.h>

#include <cmath>
#include <cstdint>
#include <cstring>
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
