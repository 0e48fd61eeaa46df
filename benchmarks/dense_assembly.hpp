// Dense random assemblies for the scaling benchmark (benchmarks/throughput.cpp, section b): a jammed periodic
// cell of polydisperse particles, tiled and clipped to the size wanted, numbered along a Morton curve.
#pragma once
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <random>
#include <vector>

#include "benchmarks/run_timing.hpp"
#include "engine/dim.hpp"

namespace mc::bench {

// Progress on stderr (the tables go to stdout).
void progress(const char* fmt, auto... args) {
  std::fprintf(stderr, fmt, args...);
  std::fflush(stderr);
}

// Dense random assemblies: a periodic cell of polydisperse particles (radii uniform in [0.8, 1.2] r0) is
// brought just past jamming by minimising the overlap energy (FIRE) at a packing fraction found by a secant
// search so that the mean overlap is slight (0.5 % of r0). Just past jamming the cell is in equilibrium with a
// coordination close to isostatic (≈ 4 in 2D, ≈ 6 in 3D, a little more). It is then tiled (the tiles match, the
// cell being periodic) and clipped to the size wanted, and the particles are numbered along a Morton curve, as a
// preprocessor would.

template <int D>
struct Cell {
  std::vector<Vec<D>> x;  // in [0, L)^D, units of r0
  std::vector<double> r;
  double L = 0, phi = 0;
  double z = 0;                              // mean coordination, rattlers included
  double mean_overlap = 0, max_overlap = 0;  // relative to r0
  int iterations = 0;                        // FIRE iterations in all
};

template <int D>
class CellRelax {
 public:
  CellRelax(int n, std::uint64_t seed) : rng_(seed) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    c_.r.resize(n);
    vol_ = 0;
    for (int i = 0; i < n; ++i) {
      c_.r[i] = 0.8 + 0.4 * u(rng_);
      vol_ += Dim<D>::volume(c_.r[i]);
    }
    c_.x.resize(n);
    c_.L = 1;
    for (auto& p : c_.x)
      for (int k = 0; k < D; ++k) p[k] = u(rng_);  // scaled by L at the first set_phi
  }

  // Affine rescaling of the cell to packing fraction phi, then energy minimisation.
  void relax_at(double phi) {
    const double L = std::pow(vol_ / phi, 1.0 / D);
    for (auto& p : c_.x) p *= L / c_.L;
    c_.L = L;
    c_.phi = phi;
    minimise();
    stats();
  }
  const Cell<D>& cell() const { return c_; }

 private:
  Vec<D> image(Vec<D> d) const {
    for (int k = 0; k < D; ++k) d[k] -= c_.L * std::round(d[k] / c_.L);
    return d;
  }
  void rebuild() {
    // O(n²) is fine for a cell of 1000.
    const int n = static_cast<int>(c_.x.size());
    list_.clear();
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j) {
        const double reach = c_.r[i] + c_.r[j] + kSkin;
        if (image(c_.x[j] - c_.x[i]).squaredNorm() < reach * reach) list_.push_back({i, j});
      }
    at_list_ = c_.x;
  }
  double forces(std::vector<Vec<D>>& f) const {
    for (auto& fi : f) fi.setZero();
    for (const auto& [i, j] : list_) {
      const Vec<D> d = image(c_.x[j] - c_.x[i]);
      const double dist = d.norm(), ov = c_.r[i] + c_.r[j] - dist;
      if (ov > 0) {
        const Vec<D> fij = stiffness(i, j) * ov * d / dist;  // unit masses
        f[i] -= fij;
        f[j] += fij;
      }
    }
    double fmax = 0;
    for (const auto& fi : f) fmax = std::max(fmax, fi.norm());
    return fmax;
  }
  // The engine's pair stiffness up to a constant: in 3D k_n = 4 E R_i R_j / (R_i + R_j) (balls in series), in 2D
  // it does not depend on the radii. The minimum found is then an equilibrium of the engine's contacts too.
  double stiffness(int i, int j) const { return D == 3 ? 2.0 * c_.r[i] * c_.r[j] / (c_.r[i] + c_.r[j]) : 1.0; }
  // FIRE (Bitzek et al. 2006).
  void minimise() {
    const int n = static_cast<int>(c_.x.size());
    std::vector<Vec<D>> f(n), v(n, Vec<D>::Zero());
    rebuild();
    double dt = 0.02, alpha = 0.1;
    int positive = 0;
    double fmax = forces(f);
    for (int it = 0; it < 200000 && fmax > 1e-9; ++it, ++c_.iterations) {
      double P = 0, vn = 0, fn = 0;
      for (int i = 0; i < n; ++i) P += f[i].dot(v[i]), vn += v[i].squaredNorm(), fn += f[i].squaredNorm();
      if (P > 0) {
        vn = std::sqrt(vn), fn = std::sqrt(fn);
        for (int i = 0; i < n; ++i) v[i] = (1 - alpha) * v[i] + alpha * vn / fn * f[i];
        if (++positive > 5) dt = std::min(dt * 1.1, 0.2), alpha *= 0.99;
      } else {
        for (auto& vi : v) vi.setZero();
        dt *= 0.5, alpha = 0.1, positive = 0;
      }
      double moved = 0;
      for (int i = 0; i < n; ++i) {
        v[i] += f[i] * dt;
        c_.x[i] += v[i] * dt;
        moved = std::max(moved, (c_.x[i] - at_list_[i]).squaredNorm());
      }
      if (std::sqrt(moved) > 0.5 * kSkin) rebuild();
      fmax = forces(f);
    }
    for (auto& p : c_.x)
      for (int k = 0; k < D; ++k) p[k] -= c_.L * std::floor(p[k] / c_.L);
  }
  void stats() {
    rebuild();
    std::size_t contacts = 0;
    double sum = 0;
    c_.max_overlap = 0;
    for (const auto& [i, j] : list_) {
      const double ov = c_.r[i] + c_.r[j] - image(c_.x[j] - c_.x[i]).norm();
      if (ov > 0) ++contacts, sum += ov, c_.max_overlap = std::max(c_.max_overlap, ov);
    }
    c_.z = 2.0 * static_cast<double>(contacts) / static_cast<double>(c_.x.size());
    c_.mean_overlap = contacts ? sum / static_cast<double>(contacts) : 0;
  }

  static constexpr double kSkin = 0.3;
  std::mt19937_64 rng_;
  Cell<D> c_;
  double vol_ = 0;
  std::vector<std::array<int, 2>> list_;
  std::vector<Vec<D>> at_list_;
};

// The mean overlap grows about linearly with φ − φ_J above jamming: a secant search on φ for the target.
template <int D>
Cell<D> jammed_cell(int n, double target_overlap, std::uint64_t seed) {
  CellRelax<D> relax(n, seed);
  double phi0 = D == 2 ? 0.87 : 0.68, phi1 = D == 2 ? 0.86 : 0.67;
  relax.relax_at(phi0);
  double m0 = relax.cell().mean_overlap;
  relax.relax_at(phi1);
  double m1 = relax.cell().mean_overlap;
  for (int k = 0; k < 8 && std::abs(m1 - target_overlap) > 0.1 * target_overlap; ++k) {
    double phi2 = m1 != m0 ? phi1 + (target_overlap - m1) * (phi1 - phi0) / (m1 - m0) : phi1 - 0.005;
    phi2 = std::clamp(phi2, phi1 - 0.02, phi1 + 0.02);
    relax.relax_at(phi2);
    phi0 = phi1, m0 = m1;
    phi1 = phi2, m1 = relax.cell().mean_overlap;
  }
  return relax.cell();
}

std::uint64_t morton(std::array<std::uint32_t, 3> c, int D) {
  std::uint64_t key = 0;
  for (int b = 0; b < 21; ++b)
    for (int k = 0; k < D; ++k) key |= std::uint64_t((c[k] >> b) & 1u) << (b * D + k);
  return key;
}

template <int D>
struct Assembly {
  std::vector<Vec<D>> x;
  std::vector<double> r;
  std::vector<char> edge;  // within R + 1.2 r0 of a face: some of its periodic partners may have been clipped away
  double side = 0;         // the assembly fills [0, side]^D
};

// Tiles the cell (scaled to r0) over the cube [0, side]^D with side chosen for about n particles. inside:
// keep the particles wholly inside the cube (for walls on its faces); else keep every centre inside it.
template <int D>
Assembly<D> tile(const Cell<D>& c, double r0, int n, bool inside) {
  Assembly<D> a;
  const double L = c.L * r0;
  a.side = L * std::pow(static_cast<double>(n) / static_cast<double>(c.x.size()), 1.0 / D);
  const int m = static_cast<int>(std::ceil(a.side / L));
  std::array<int, D> t{};
  while (true) {
    for (std::size_t i = 0; i < c.x.size(); ++i) {
      Vec<D> p = c.x[i] * r0;
      for (int k = 0; k < D; ++k) p[k] += t[k] * L;
      const double r = c.r[i] * r0;
      const double reach = r + 1.2 * r0;  // the farthest partner centre
      bool keep = true, edge = false;
      for (int k = 0; k < D; ++k) {
        keep = keep && (inside ? (p[k] - r >= 0 && p[k] + r <= a.side) : (p[k] >= 0 && p[k] < a.side));
        edge = edge || p[k] < reach || p[k] > a.side - reach;
      }
      if (keep) a.x.push_back(p), a.r.push_back(r), a.edge.push_back(edge);
    }
    int k = 0;
    while (k < D && ++t[k] == m) t[k] = 0, ++k;
    if (k == D) break;
  }
  // Morton numbering, cells of 2 r0.
  std::vector<std::pair<std::uint64_t, int>> key(a.x.size());
  for (std::size_t i = 0; i < a.x.size(); ++i) {
    std::array<std::uint32_t, 3> cc{};
    for (int k = 0; k < D; ++k) cc[k] = static_cast<std::uint32_t>(std::max(0.0, a.x[i][k]) / (2 * r0));
    key[i] = {morton(cc, D), static_cast<int>(i)};
  }
  std::sort(key.begin(), key.end());
  Assembly<D> s;
  s.side = a.side;
  for (const auto& [k, i] : key) s.x.push_back(a.x[i]), s.r.push_back(a.r[i]), s.edge.push_back(a.edge[i]);
  return s;
}

const double kTargetOverlap = 0.005;  // mean overlap of the generated assemblies, relative to r0

template <int D>
const Cell<D>& cell_for_dim(bool quick) {
  static std::optional<Cell<D>> cell;
  if (!cell) {
    const auto t0 = Clock::now();
    cell = jammed_cell<D>(quick ? 500 : 1000, kTargetOverlap, 20240601 + D);
    progress(
        "  %dD cell: %zu particles, phi = %.4f, z = %.2f, overlap mean %.4f r0, max %.4f r0, %d FIRE "
        "iterations, %.1f s\n",
        D, cell->x.size(), cell->phi, cell->z, cell->mean_overlap, cell->max_overlap, cell->iterations,
        std::chrono::duration<double>(Clock::now() - t0).count());
  }
  return *cell;
}

const double kR0 = 1e-3;  // mean radius of the generated assemblies [m]

}  // namespace mc::bench
