// One bonded 3D block stepped whole and split across the processes of an MPI launch (World::split), side by side
// on every process: each process's own particles must carry the whole world's bits at every check, and the crack
// logs must be the same, entry for entry. Run by tests/split_specimen.cpp under mpirun with 1, 2 and 4 ranks.
//
// The block drifts along its length through the fixed cuts between the regions while its ends pull it apart, so
// particles change hands at every rebuild, bonds break in tension and shear, and the pieces slide and part.
// Checked after every step. Exit 0 and a line "same bits ..." per rank when everything agreed; 1 and the first
// difference otherwise.
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "contact_models/parallel_bond.hpp"
#include "engine/random_stream.hpp"
#include "engine/world.hpp"
#include "studies/ranks.hpp"

using namespace mc;

namespace {

World<3> drifting_block() {
  ParallelBondParams prm;
  prm.contact.modulus = 5e9, prm.contact.kn_ks_ratio = 2.5, prm.contact.friction = 0.5;
  prm.modulus = 10e9, prm.kn_ks_ratio = 2.5;
  prm.tensile_mean = 10e6, prm.tensile_std = 2e6;
  prm.shear_mean = 4e6, prm.shear_std = 1e6;
  World<3> w;
  w.sets.push_back(std::make_unique<ContactSet<ParallelBond, 3>>(prm));
  w.model_of = {{0}};
  w.domain_lo = Vec<3>::Constant(-1);
  w.domain_hi = Vec<3>::Constant(1);
  RandomStream rng(11);
  const double r = 1e-3, dx = 2 * r, dy = std::sqrt(3.0) * r;
  const int nx = 30, ny = 7, nz = 6;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int n =
            w.particles.add(Vec<3>((i + 0.5 * (j % 2)) * dx, j * dy, k * dx), r * (1 - 0.15 * rng.uniform()), 2600, 0);
        w.particles.v[n] = Vec<3>(5.0, 0, 0);
        if (i == 0) w.particles.fix[n] = 0xff, w.particles.v[n] = Vec<3>(4.5, 0, 0);
        if (i == nx - 1) w.particles.fix[n] = 0xff, w.particles.v[n] = Vec<3>(5.5, 0.3, 0);
      }
  w.local_damping = 0.05;
  w.rebuild_interval = 30;
  w.init();
  w.install_bonds(0.5, 5);
  return w;
}

template <class T>
bool same(const T& a, const T& b) {
  return std::memcmp(static_cast<const void*>(&a), static_cast<const void*>(&b), sizeof(T)) == 0;
}

// The first difference between the split world's own particles and the whole world's, or "".
std::string difference(const World<3>& whole, const World<3>& split) {
  const auto &p = split.particles, &q = whole.particles;
  for (int i = 0; i < p.size(); ++i) {
    if (p.is_ghost(i)) continue;
    const auto g = split.global_index(i);
    if (!same(p.x[i], q.x[g]) || !same(p.v[i], q.v[g]) || !same(p.w[i], q.w[g]) || !same(p.q[i], q.q[g]))
      return "particle " + std::to_string(g) + " moved otherwise";
  }
  if (whole.dt != split.dt) return "timestep";
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

}  // namespace

int main(int argc, char** argv) {
  Ranks::start(&argc, &argv);
  const Ranks& ranks = Ranks::world();
  const RanksExchange exchange(ranks);
  World<3> whole = drifting_block(), split = drifting_block();
  const std::size_t bonds = whole.bond_count();
  split.split(exchange);
  std::vector<std::uint8_t> owned(whole.particles.size(), 0);
  auto own_now = [&] {
    std::vector<std::uint8_t> o(whole.particles.size(), 0);
    for (int i = 0; i < split.particles.size(); ++i)
      if (!split.particles.is_ghost(i)) o[split.global_index(i)] = 1;
    return o;
  };
  owned = own_now();
  const int own_at_start = split.own_count(), held_at_start = split.held_count();
  long arrived = 0;
  const int steps = 4000;
  for (int s = 1; s <= steps; ++s) {
    whole.step();
    split.step();
    const std::string d = difference(whole, split);
    if (!d.empty()) {
      std::printf("rank %d of %d: step %d: %s\n", ranks.rank(), ranks.size(), s, d.c_str());
      ranks.abort(1);
    }
    const auto now = own_now();
    for (std::size_t g = 0; g < now.size(); ++g) arrived += now[g] && !owned[g];
    owned = now;
  }
  std::printf(
      "same bits: rank %d of %d, %d steps, %lld rebuilds, %zu bonds, %zu cracks; own %d then %d (held %d), %ld "
      "arrived\n",
      ranks.rank(), ranks.size(), steps, static_cast<long long>(split.rebuilds), bonds, split.cracks.size(),
      own_at_start, split.own_count(), held_at_start, arrived);
  return 0;
}
