// What a static secant iteration of the rigid-cell model costs as the specimen grows: a 3D prism of Voronoi cells
// (100 × 100 × 200 mm, Květoň's concrete of Tab. 9.1) held at its bottom cells and pulled at its top cells, from
// 10^3 to 10^5 degrees of freedom. For each size: the parts of an iteration timed alone (the stiffness refilled,
// CHOLMOD's numeric factorisation, one pair of triangular solves, the facets' strains and damage), then the static
// solver on the first steps past the elastic limit (secant iterations, factorisations, conjugate-gradient
// iterations, wall time per iteration) and the linear solver's share of that time. The order of the time per
// iteration in the degrees of freedom, fitted over the sizes run, projects it to 10^6.
// Usage: static_iteration_cost [--dofs 1000,3000,10000,30000,100000] [--steps N]
#include <omp.h>

#include <Eigen/CholmodSupport>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "engine/errors.hpp"
#include "rigid_cell/free_stiffness.hpp"
#include "rigid_cell/node_placement.hpp"
#include "rigid_cell/static_solver.hpp"

using namespace mc;
using namespace mc::rigid_cell;
using Clock = std::chrono::steady_clock;

namespace {

const Vec<3> kSize(0.1, 0.1, 0.2);
const FacetParams kConcrete{44e9, 0.237, 2.64e6, 9.93};  // Tab. 9.1
// Random sequential nodes fill about half of the volume / l_min³ (measured: 0.48-0.53 on Květoň's discs).
constexpr double kNodesPerVolume = 0.5;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The best of `repeats` timings of f (a noisy machine makes single timings long, never short).
template <typename F>
double best_of(int repeats, F&& f) {
  double best = 1e300;
  for (int i = 0; i < repeats; ++i) {
    const auto t0 = Clock::now();
    f();
    best = std::min(best, seconds_since(t0));
  }
  return best;
}

struct Row {
  int cells = 0, dofs = 0;
  std::size_t facets = 0;
  long nnz_K = 0;
  double nnz_L = 0, flops = 0;
  double refill = 0, factorise = 0, solve = 0, product = 0, damage = 0;  // seconds, each part alone
  int steps = 0, iterations = 0, factorisations = 0, cg = 0;
  double wall = 0;  // of the static solver over those steps
  double per_iteration() const { return wall / iterations; }
  // The linear solver's share: its factorisations, its triangular solves (one per secant iteration and one per CG
  // iteration) and its products K x (one per CG iteration), at the parts' own times.
  double solver_share() const { return (factorisations * factorise + (iterations + cg) * solve + cg * product) / wall; }
};

Row measure(int target_dofs, int max_steps) {
  Row r;
  const double l_min = std::cbrt(kNodesPerVolume * kSize.prod() * 6 / target_dofs);
  const auto shape = SpecimenShape<3>::box(kSize);
  const auto t = tessellate(place_nodes(shape, l_min, 1, 3000), shape, 3 * l_min);
  const CellAssembly<3> model(t, std::vector<FacetParams>(t.contacts, kConcrete));
  constexpr int n = CellAssembly<3>::kDofs;
  r.cells = model.cells();
  r.facets = model.contacts();

  // Held: every degree of freedom of the cells within l_min of the bottom and the top.
  std::vector<int> held, top;
  std::vector<bool> is_held(model.dofs(), false);
  for (int c = 0; c < model.cells(); ++c) {
    const double z = t.cells[c].node.z();
    if (z > l_min && z < kSize.z() - l_min) continue;
    for (int k = 0; k < n; ++k) held.push_back(n * c + k), is_held[n * c + k] = true;
    if (z >= kSize.z() - l_min) top.push_back(n * c + 2);
  }
  r.dofs = model.dofs() - static_cast<int>(held.size());
  // Made first: it sets the BLAS to one thread, as in a run.
  StaticSolver<3> solver(model, held);

  // The parts alone, on one thread as in a run (no OpenMP level for CHOLMOD's regions; static_solver.cpp).
  std::vector<Eigen::Triplet<double>> pick;
  for (int d = 0, col = 0; d < model.dofs(); ++d)
    if (!is_held[d]) pick.emplace_back(d, col++, 1.0);
  SparseMatrix to_cells(model.dofs(), r.dofs);
  to_cells.setFromTriplets(pick.begin(), pick.end());
  FreeStiffness<3> stiffness(model, to_cells);
  std::vector<double> damage(model.contacts(), 0.0);
  r.refill = best_of(3, [&] { stiffness(damage); });
  const SparseMatrix& K = stiffness(damage);
  r.nnz_K = K.nonZeros();
  Eigen::CholmodDecomposition<SparseMatrix, Eigen::Lower> cholesky;
  cholesky.setMode(Eigen::CholmodAuto);
  cholesky.analyzePattern(K);
  r.nnz_L = cholesky.cholmod().lnz;
  r.flops = cholesky.cholmod().fl;
  r.factorise = best_of(2, [&] { cholesky.factorize(K); });
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(r.dofs);
  Eigen::VectorXd x;
  r.solve = best_of(3, [&] { x = cholesky.solve(b); });
  Eigen::VectorXd Kx;
  r.product = best_of(3, [&] { Kx = K.selfadjointView<Eigen::Lower>() * x; });
  const Eigen::VectorXd u = Eigen::VectorXd::Random(model.dofs()) * 1e-6;
  std::vector<FacetState> states(model.contacts());
  std::vector<double> next(model.contacts());
  Eigen::VectorXd f;
  r.damage = best_of(3, [&] {
    f = model.internal_forces(u, damage);
    for (std::size_t c = 0; c < model.contacts(); ++c)
      next[c] = rigid_cell::damage(model.strain(c, u), kConcrete, model.length(c), states[c]);
  });

  // The solver in situ: a jump to 90 % of the strain at the tensile strength, then steps of 2 % of it.
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model.dofs());
  const Eigen::VectorXd f_ext = Eigen::VectorXd::Zero(model.dofs());
  const double strain_at_ft = kConcrete.ft / kConcrete.E0;
  StaticOptions options;
  options.damage_tolerance = 1e-4;
  for (int step = 0; step < 40 && r.steps < max_steps; ++step) {
    for (int d : top) q[d] = kSize.z() * strain_at_ft * (0.9 + 0.02 * step);
    const auto t0 = Clock::now();
    StaticResult s;
    try {
      s = solver.solve(q, f_ext, damage, states, options);
    } catch (const InstabilityError& e) {
      std::fprintf(stderr, "  %d DOFs: step %d stops the measurement: %s\n", r.dofs, step, e.what());
      break;
    }
    if (s.iterations <= 1) continue;  // elastic: one solve with the factor, no secant iteration to time
    r.wall += seconds_since(t0);
    r.steps += 1, r.iterations += s.iterations, r.factorisations += s.factorisations, r.cg += s.cg_iterations;
  }
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  omp_set_max_active_levels(0);
  std::vector<int> sizes{1000, 3000, 10000, 30000, 100000};
  int steps = 5;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--dofs") {
      sizes.clear();
      for (std::string s = argv[i + 1]; !s.empty();) {
        const auto comma = s.find(',');
        sizes.push_back(std::stoi(s.substr(0, comma)));
        s = comma == std::string::npos ? "" : s.substr(comma + 1);
      }
    } else if (a == "--steps") {
      steps = std::stoi(argv[i + 1]);
    } else {
      std::fprintf(stderr, "usage: %s [--dofs 1000,3000,...] [--steps N]\n", argv[0]);
      return 2;
    }
  }
  std::printf(
      "| free DOFs | cells | facets | nnz(K) | nnz(L) | factorisation GFlop | refill [ms] | factorise [ms] | "
      "solve pair [ms] | K x [ms] | strains + damage [ms] | steps | secant iterations | factorisations | "
      "CG iterations | per iteration [ms] | linear solver share "
      "|\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::vector<Row> rows;
  for (int target : sizes) {
    const Row r = measure(target, steps);
    rows.push_back(r);
    std::printf(
        "| %d | %d | %zu | %ld | %.3g | %.3g | %.2f | %.1f | %.2f | %.2f | %.2f | %d | %d | %d | %d | %.1f | %.0f %% "
        "|\n",
        r.dofs, r.cells, r.facets, r.nnz_K, r.nnz_L, r.flops * 1e-9, r.refill * 1e3, r.factorise * 1e3, r.solve * 1e3,
        r.product * 1e3, r.damage * 1e3, r.steps, r.iterations, r.factorisations, r.cg,
        r.iterations ? r.per_iteration() * 1e3 : 0.0, r.iterations ? 100 * r.solver_share() : 0.0);
    std::fflush(stdout);
  }
  // The order p of t ∝ DOFs^p from the two largest sizes with iterations, and its projection to 10^6.
  std::vector<const Row*> timed;
  for (const Row& r : rows)
    if (r.iterations > 0) timed.push_back(&r);
  if (timed.size() >= 2) {
    const Row &a = *timed[timed.size() - 2], &b = *timed.back();
    const double p = std::log(b.per_iteration() / a.per_iteration()) / std::log(double(b.dofs) / a.dofs);
    const double pf = std::log(b.factorise / a.factorise) / std::log(double(b.dofs) / a.dofs);
    std::printf(
        "\nper iteration ∝ DOFs^%.2f, factorisation ∝ DOFs^%.2f (between %d and %d DOFs): at 10^6 DOFs %.2f s per "
        "iteration, %.0f s per factorisation\n",
        p, pf, a.dofs, b.dofs, b.per_iteration() * std::pow(1e6 / b.dofs, p), b.factorise * std::pow(1e6 / b.dofs, pf));
  }
  return 0;
}
