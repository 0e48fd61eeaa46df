// Bonded blocks stepped whole and split across the processes of an MPI launch (World::split), side by side on
// every process: each process's own particles must carry the whole world's bits after every step, and so must the
// timestep, the walls, the energy terms and the crack log, entry for entry. Run by tests/split_specimen.cpp under
// mpirun with 1, 2 and 4 ranks. Two scenes:
// - drifting: a 3D block drifts along its length through the fixed cuts between the regions while its held ends
//   pull it apart, so particles change hands at every rebuild, bonds break in tension and shear, and the pieces
//   slide and part (adaptive skin); and the same with the CPM, whose bonds reach past the ghost layer;
// - boxed (2D and 3D): a block under gravity crushed by a wall moving at a set velocity, against a fixed floor,
//   a fixed side, a stress servo on the other side and, in 3D, a wall under opening control reading a gauge across
//   the block; energy traced, local damping;
// - stops: the drifting block leaves its domain, a sphere shot through it moves too far in a step or passes
//   through its neighbour; the split run must stop where the whole one stops, with its message.
// Exit 0 and a line "same bits ..." per rank and scene when everything agreed; 1 and the first difference otherwise.
#include <cstdio>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "contact_models/cpm.hpp"
#include "contact_models/linear.hpp"
#include "contact_models/parallel_bond.hpp"
#include "engine/errors.hpp"
#include "engine/random_stream.hpp"
#include "engine/world.hpp"
#include "studies/ranks.hpp"

using namespace mc;

namespace {

constexpr double kR = 1e-3;

ParallelBondParams parallel_bond() {
  ParallelBondParams prm;
  prm.contact.modulus = 5e9, prm.contact.kn_ks_ratio = 2.5, prm.contact.friction = 0.5;
  prm.bond_modulus.mean = 10e9, prm.bond_kn_ks_ratio = 2.5;
  prm.bond_tensile_strength.mean = 10e6, prm.bond_tensile_strength.std = 2e6;
  prm.bond_shear_strength.mean = 4e6, prm.bond_shear_strength.std = 1e6;
  return prm;
}

// Spheres (discs) on a layered hexagonal lattice, radii 0.85–1 kR at random, all at the given velocity; one
// contact model.
template <int D, class Model = ParallelBond>
World<D> bonded_world(RandomStream& rng, int nx, int ny, int nz, Vec<D> velocity,
                      const typename Model::Params& prm = parallel_bond()) {
  World<D> w;
  w.sets.push_back(std::make_unique<ContactSet<Model, D>>(prm));
  w.model_of = {{0}};
  w.domain_lo = Vec<D>::Constant(-1);
  w.domain_hi = Vec<D>::Constant(1);
  const double dx = 2 * kR, dy = std::sqrt(3.0) * kR;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        Vec<D> x;
        x[0] = (i + 0.5 * (j % 2)) * dx;
        x[1] = j * dy;
        if constexpr (D == 3) x[2] = k * dx;
        const int n = w.particles.add(x, kR * (1 - 0.15 * rng.uniform()), 2600, 0);
        w.particles.v[n] = velocity;
      }
  return w;
}

// The drifting block; with the CPM, bonded up to R_I = 1.5 (R_A + R_B): bonds reach past the ghost layer, so
// their far partners must be sent as ghosts of their own.
template <class Model = ParallelBond>
World<3> drifting_block() {
  RandomStream rng(11);
  const int nx = 30;
  typename Model::Params prm;
  if constexpr (std::is_same_v<Model, Cpm>) {
    prm.modulus = 30e9, prm.crack_onset_strain = 1e-4, prm.relative_ductility = 30;
    prm.cohesion = 3e6, prm.tan_friction = 0.8, prm.interaction_radius = 2.0;
  } else {
    prm = parallel_bond();
  }
  World<3> w = bonded_world<3, Model>(rng, nx, 7, 6, Vec<3>(5.0, 0, 0), prm);
  // Both ends hold their velocities; a driven group (the middle of the top layer, held along z only) is pressed
  // down from rest to 0.5 m/s over 20 µs while it drifts with the rest.
  DrivenGroup<3> press;
  press.velocity = Vec<3>(0, 0, -0.5);
  press.ramp_time = 2e-5;
  for (int n = 0; n < w.particles.size(); ++n) {
    const int i = n % nx, k = n / (nx * 7);
    if (i == 0) w.particles.fix[n] = 0xff, w.particles.v[n] = Vec<3>(4.5, 0, 0);
    if (i == nx - 1) w.particles.fix[n] = 0xff, w.particles.v[n] = Vec<3>(5.5, 0.3, 0);
    if (k == 5 && i >= 10 && i < 20) w.particles.fix[n] = 0x04, press.members.push_back(n);
  }
  w.driven.push_back(press);
  w.local_damping = 0.05;
  w.rebuild_interval = 30;
  // The drift carries particles into the upper regions: rebalanced past 2 % (the bits must not notice).
  w.imbalance_limit = 0.02;
  w.init();
  w.install_bonds(0.5, 5);
  return w;
}

template <int D>
World<D> boxed_block() {
  RandomStream rng(5);
  const int nx = D == 2 ? 40 : 20, ny = D == 2 ? 20 : 7, nz = D == 2 ? 1 : 6;
  World<D> w = bonded_world<D>(rng, nx, ny, nz, Vec<D>::Zero());
  Vec<D> lo = Vec<D>::Constant(kInf), hi = Vec<D>::Constant(-kInf);
  for (const auto& x : w.particles.x) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
  lo.array() -= kR, hi.array() += kR;
  const auto& prm = static_cast<const ContactSet<ParallelBond, D>&>(*w.sets[0]).params();
  WallMaterial wm;
  wm.kn = Linear::ball_kn<D>(prm.contact, kR);
  wm.ks = wm.kn / prm.contact.kn_ks_ratio;
  wm.friction = 0.3;
  for (int d = 0; d < D; ++d) {
    const Vec<D> e = Vec<D>::Unit(d);
    w.walls.push_back(Wall<D>::plane(lo[d] * e, e));
    w.walls.push_back(Wall<D>::plane(hi[d] * e, -e));
  }
  for (auto& wall : w.walls) wall.material = wm;
  auto& top = w.walls[3];
  top.control = WallControl::Velocity;
  top.target_velocity = -0.5 * Vec<D>::Unit(1);
  top.ramp_time = 2e-5;
  auto& side = w.walls[1];
  side.control = WallControl::Servo;
  side.target_stress = 2e6;
  side.servo_area = D == 2 ? hi[1] - lo[1] : (hi[1] - lo[1]) * (hi[2] - lo[2]);
  side.servo_max_speed = 0.5;
  if constexpr (D == 3) {
    // A gauge across the block along x (its first and last columns), read by the front wall under opening control.
    OpeningGauge<3> g;
    for (int n = 0; n < w.particles.size(); ++n) {
      if (n % nx == 0) g.a.push_back(n);
      if (n % nx == nx - 1) g.b.push_back(n);
    }
    g.direction = Vec<3>::UnitX();
    g.start = g.separation(w.particles);
    w.gauges.push_back(g);
    auto& front = w.walls[4];
    front.control = WallControl::Opening;
    front.gauge = 0;
    front.opening_rate = 0.05;
    front.opening_gain = 2000;
    front.servo_max_speed = front.retreat_speed = 0.05;
  }
  w.gravity = -9.81 * Vec<D>::Unit(1);
  w.local_damping = 0.1;
  w.trace_energy = true;
  w.init();
  w.install_bonds(0.5, 9);
  return w;
}

template <class T>
bool same(const T& a, const T& b) {
  return std::memcmp(static_cast<const void*>(&a), static_cast<const void*>(&b), sizeof(T)) == 0;
}

// The first difference between the split world and the whole one, or "".
template <int D>
std::string difference(const World<D>& whole, const World<D>& split) {
  const auto &p = split.particles, &q = whole.particles;
  for (int i = 0; i < p.size(); ++i) {
    if (p.is_ghost(i)) continue;
    const auto g = split.global_index(i);
    if (!same(p.x[i], q.x[g]) || !same(p.v[i], q.v[g]) || !same(p.w[i], q.w[g]))
      return "particle " + std::to_string(g) + " moved otherwise";
  }
  if (!same(whole.dt, split.dt)) return "timestep";
  for (std::size_t k = 0; k < whole.walls.size(); ++k) {
    const auto &a = whole.walls[k], &b = split.walls[k];
    if (!same(a.origin, b.origin) || !same(a.force, b.force) || !same(a.moment, b.moment) ||
        !same(a.velocity, b.velocity) || !same(a.contact_kn, b.contact_kn))
      return "wall " + std::to_string(k);
  }
  const auto &e = whole.energy, &f = split.energy;
  if (!same(e.body_work, f.body_work) || !same(e.boundary_work, f.boundary_work) ||
      !same(e.dissipated_contacts, f.dissipated_contacts) || !same(e.dissipated_bonds, f.dissipated_bonds) ||
      !same(e.dissipated_local, f.dissipated_local) || !same(e.kinetic, f.kinetic) || !same(e.strain, f.strain))
    return "energy";
  if (whole.cracks.size() != split.cracks.size())
    return "crack log: " + std::to_string(split.cracks.size()) + " entries against " +
           std::to_string(whole.cracks.size());
  for (std::size_t k = 0; k < whole.cracks.size(); ++k) {
    const auto &a = whole.cracks[k], &b = split.cracks[k];
    if (a.step != b.step || a.a != b.a || a.b != b.b || a.mode != b.mode || !same(a.position, b.position))
      return "crack log entry " + std::to_string(k);
  }
  return "";
}

template <int D, class Make>
void check(const char* scene, Make&& make, int steps, const Ranks& ranks, const Exchange& exchange) {
  World<D> whole = make(), split = make();
  const std::size_t bonds = whole.bond_count();
  split.split(exchange);
  auto own_now = [&] {
    std::vector<std::uint8_t> o(whole.particles.size(), 0);
    for (int i = 0; i < split.particles.size(); ++i)
      if (!split.particles.is_ghost(i)) o[split.global_index(i)] = 1;
    return o;
  };
  std::vector<std::uint8_t> owned = own_now();
  const int own_at_start = split.own_count(), held_at_start = split.held_count();
  long arrived = 0;
  for (int s = 1; s <= steps; ++s) {
    whole.step();
    split.step();
    if (whole.trace_energy && s % 100 == 0) whole.update_energy(), split.update_energy();
    const std::string d = difference(whole, split);
    if (!d.empty()) {
      std::printf("%s: rank %d of %d: step %d: %s\n", scene, ranks.rank(), ranks.size(), s, d.c_str());
      std::fflush(stdout);
      ranks.abort(1);
    }
    const auto now = own_now();
    for (std::size_t g = 0; g < now.size(); ++g) arrived += now[g] && !owned[g];
    owned = now;
  }
  std::printf(
      "same bits: %s, rank %d of %d, %d steps, %lld rebuilds, %zu bonds, %zu cracks; own %d then %d (held %d), "
      "%lld rebalances, %ld arrived\n",
      scene, ranks.rank(), ranks.size(), steps, static_cast<long long>(split.rebuilds), bonds, split.cracks.size(),
      own_at_start, split.own_count(), held_at_start, static_cast<long long>(split.rebalances()), arrived);
}

// The whole and the split world stepped until one throws InstabilityError (at most 5 000 steps, checked every
// 10): both must stop at the same step, on every rank, with the same message.
void check_stop(const char* scene, World<3> (*make)(), const Ranks& ranks, const Exchange& exchange) {
  World<3> whole = make(), split = make();
  split.split(exchange);
  auto stop = [](World<3>& w) -> std::pair<long, std::string> {
    try {
      for (long s = 1; s <= 5000; ++s) {
        w.step();
        if (s % 10 == 0) w.check_stability();
      }
    } catch (const InstabilityError& e) {
      return {w.step_count, e.what()};
    }
    return {-1, ""};
  };
  const auto a = stop(whole), b = stop(split);
  if (a.first < 0 || a != b) {
    std::printf("%s: rank %d of %d: the whole world stopped at step %ld (%s), the split one at %ld (%s)\n", scene,
                ranks.rank(), ranks.size(), a.first, a.second.c_str(), b.first, b.second.c_str());
    std::fflush(stdout);
    ranks.abort(1);
  }
  std::printf("same stop: %s, rank %d of %d, step %ld: %.70s...\n", scene, ranks.rank(), ranks.size(), b.first,
              b.second.c_str());
}

// The drifting block in a domain that ends 1.5 mm past its leading end: it leaves it.
World<3> escaping_block() {
  World<3> w = drifting_block<ParallelBond>();
  w.domain_hi[0] = 0.0605;
  return w;
}
// One sphere inside the block shot sideways: at 5 000 m/s it moves more than half its radius in the first step;
// at 2 000 m/s it runs into its neighbour until the pair passes through.
World<3> shot_block(double speed) {
  World<3> w = drifting_block<ParallelBond>();
  w.particles.v[700] = Vec<3>(0, speed, 0);
  return w;
}

}  // namespace

int main(int argc, char** argv) {
  Ranks::start(&argc, &argv);
  const Ranks& ranks = Ranks::world();
  const RanksExchange exchange(ranks);
  check<3>("drifting 3D", drifting_block<ParallelBond>, 3000, ranks, exchange);
  check<3>("drifting 3D CPM", drifting_block<Cpm>, 3200, ranks, exchange);
  check<2>("boxed 2D", boxed_block<2>, 2400, ranks, exchange);
  check<3>("boxed 3D", boxed_block<3>, 2400, ranks, exchange);
  check_stop("escaping 3D", escaping_block, ranks, exchange);
  check_stop(
      "too fast 3D", [] { return shot_block(5000); }, ranks, exchange);
  check_stop(
      "passing through 3D", [] { return shot_block(2000); }, ranks, exchange);
  return 0;
}
