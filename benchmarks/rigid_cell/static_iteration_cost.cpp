// What a secant iteration of the rigid-cell model costs as the specimen grows: a 3D prism of Voronoi cells
// (100 × 100 × 200 mm, Květoň's concrete of Tab. 9.1) held at its bottom cells and pulled at its top cells, from
// 10^3 to 10^5 degrees of freedom. For each size: the parts of an iteration timed alone (the stiffness refilled,
// CHOLMOD's numeric factorisation, one pair of triangular solves, the facets' strains and damage), then the static
// solver on the first steps past the elastic limit (secant iterations, factorisations, conjugate-gradient
// iterations, wall time per iteration) and the linear solver's share of that time. The order of the time per
// iteration in the degrees of freedom, fitted over the sizes run, projects it to 10^6. Then the same prism in
// Newmark's implicit dynamics (Květoň (8.4), β 0.3, γ 0.55, ρ 2 400 kg/m³, steps of ten cell transits of the bar
// wave): the top pulled so that it reaches the strain at the tensile strength halfway, the time per elastic step
// (one solve with the kept factor) and per damaged step (a secant iteration inside it).
// Usage: static_iteration_cost [--dofs 1000,3000,10000,30000,100000] [--steps N] [--newmark-steps N]
#include <omp.h>

#include <Eigen/CholmodSupport>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "benchmarks/options.hpp"
#include "benchmarks/rigid_cell/timing.hpp"
#include "engine/errors.hpp"
#include "rigid_cell/free_stiffness.hpp"
#include "rigid_cell/newmark.hpp"
#include "rigid_cell/node_placement.hpp"
#include "rigid_cell/static_solver.hpp"

using namespace mc;
using namespace mc::rigid_cell;
using mc::bench::best_of;
using mc::bench::Clock;
using mc::bench::seconds_since;

namespace {

const Vec<3> kSize(0.1, 0.1, 0.2);
const FacetParams kConcrete{44e9, 0.237, 2.64e6, 9.93};  // Tab. 9.1
// Random sequential nodes fill about half of the volume / l_min³ (measured: 0.48-0.53 on Květoň's discs).
constexpr double kNodesPerVolume = 0.5;

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

// The prism at one size: its cells, facets, and the held degrees of freedom (every one of the cells within l_min
// of the bottom and the top; the top's z translations are pulled).
struct Prism {
  double l_min;
  Tessellation<3> t;
  CellAssembly<3> model;
  std::vector<int> held, top;
  std::vector<bool> is_held;
  explicit Prism(int target_dofs)
      : l_min(std::cbrt(kNodesPerVolume * kSize.prod() * 6 / target_dofs)),
        t(tessellate(place_nodes(SpecimenShape<3>::box(kSize), l_min, 1, 3000), SpecimenShape<3>::box(kSize),
                     3 * l_min)),
        model(t, std::vector<FacetParams>(t.contacts, kConcrete)),
        is_held(model.dofs(), false) {
    constexpr int n = CellAssembly<3>::kDofs;
    for (int c = 0; c < model.cells(); ++c) {
      const double z = t.cells[c].node.z();
      if (z > l_min && z < kSize.z() - l_min) continue;
      for (int k = 0; k < n; ++k) held.push_back(n * c + k), is_held[n * c + k] = true;
      if (z >= kSize.z() - l_min) top.push_back(n * c + 2);
    }
  }
};

Row measure(const Prism& p, int max_steps) {
  Row r;
  const auto& [l_min, t, model, held, top, is_held] = p;
  r.cells = model.cells();
  r.facets = model.contacts();
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
  const double strain_at_ft = kConcrete.tensile_strength / kConcrete.E0;
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

// The prism in Newmark steps (8.4): per step the inertial load M (a₀u + a₁u̇ + a₂ü), the secant iteration on
// K(D) + a₀M (the factor kept while no facet's damage changes), then (8.2)-(8.3).
struct DynamicRow {
  double dt = 0;
  int elastic_steps = 0, damaged_steps = 0, iterations = 0, factorisations = 0, cg = 0;
  double elastic_wall = 0, damaged_wall = 0;
  double share = 0;  // the linear solver's, over the damaged steps
};

DynamicRow measure_newmark(const Prism& p, const Row& parts, int steps) {
  DynamicRow r;
  const auto& [l_min, t, model, held, top, is_held] = p;
  constexpr int n = CellAssembly<3>::kDofs;
  const double rho = 2400, c = std::sqrt(macroscopic(3, kConcrete.E0, kConcrete.alpha).E / rho);
  r.dt = 10 * l_min / c;
  const NewmarkScheme s(NewmarkScheme::kBeta, NewmarkScheme::kGamma, r.dt);
  std::vector<Eigen::Triplet<double>> mass;
  for (int cell = 0; cell < model.cells(); ++cell) {
    const auto M = t.cells[cell].mass.mass_matrix(rho);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) mass.emplace_back(n * cell + i, n * cell + j, M(i, j));
  }
  SparseMatrix M(model.dofs(), model.dofs());
  M.setFromTriplets(mass.begin(), mass.end());
  StaticSolver<3> solver(model, held);
  solver.set_inertia(M, s.a0(), 0);
  // The top reaches the strain at the tensile strength at half the steps.
  const double speed = 2 * kSize.z() * kConcrete.tensile_strength / kConcrete.E0 / (steps * r.dt);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(model.dofs()), v = u, a = u;
  std::vector<double> damage(model.contacts(), 0.0);
  std::vector<FacetState> states(model.contacts());
  StaticOptions options;
  options.damage_tolerance = 1e-4;
  for (int step = 1; step <= steps; ++step) {
    const auto t0 = Clock::now();
    Eigen::VectorXd q = u;
    for (int d : top) q[d] = speed * step * r.dt;
    const Eigen::VectorXd f = M * s.inertial_history(u, v, a);
    StaticResult res;
    try {
      res = solver.solve(q, f, damage, states, options);
    } catch (const InstabilityError& e) {
      std::fprintf(stderr, "  Newmark step %d stops the measurement: %s\n", step, e.what());
      break;
    }
    const Eigen::VectorXd a_next = s.acceleration(q, u, v, a);
    v = s.velocity(v, a, a_next);
    a = a_next, u = q;
    const double wall = seconds_since(t0);
    if (step == 1) continue;  // its factorisation is timed with the parts
    if (res.iterations <= 1) {
      r.elastic_steps += 1, r.elastic_wall += wall;
    } else {
      r.damaged_steps += 1, r.damaged_wall += wall;
      r.iterations += res.iterations, r.factorisations += res.factorisations, r.cg += res.cg_iterations;
    }
  }
  if (r.damaged_wall > 0)
    r.share = (r.factorisations * parts.factorise + (r.iterations + r.cg) * parts.solve + r.cg * parts.product) /
              r.damaged_wall;
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  omp_set_max_active_levels(0);
  std::vector<int> sizes{1000, 3000, 10000, 30000, 100000};
  int steps = 5, newmark_steps = 40;
  CLI::App app{"static_iteration_cost: what a secant iteration of the rigid-cell model costs as the prism grows"};
  app.add_option("--dofs", sizes, "N,N,...: free degrees of freedom of each prism")
      ->delimiter(',')
      ->check(CLI::Range(100, 10000000));
  app.add_option("--steps", steps, "static steps past the elastic limit")->check(CLI::Range(1, 40));
  app.add_option("--newmark-steps", newmark_steps, "Newmark steps (the top reaches the tensile strain at half)")
      ->check(CLI::Range(2, 100000));
  if (const auto code = mc::bench::read_options(app, argc, argv, "static_iteration_cost")) return *code;
  std::printf(
      "| free DOFs | cells | facets | nnz(K) | nnz(L) | factorisation GFlop | refill [ms] | factorise [ms] | "
      "solve pair [ms] | K x [ms] | strains + damage [ms] | steps | secant iterations | factorisations | "
      "CG iterations | per iteration [ms] | linear solver share "
      "|\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::vector<Row> rows;
  std::vector<DynamicRow> dynamic;
  for (int target : sizes) {
    const Prism prism(target);
    const Row r = measure(prism, steps);
    dynamic.push_back(measure_newmark(prism, r, newmark_steps));
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
  std::printf(
      "\nNewmark steps (β 0.3, γ 0.55), %d per size:\n\n| free DOFs | Δt [µs] | elastic steps | per elastic step "
      "[ms] | damaged steps | secant iterations per damaged step | per damaged step [ms] | linear solver share "
      "|\n|---|---|---|---|---|---|---|---|\n",
      newmark_steps);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const DynamicRow& d = dynamic[i];
    std::printf("| %d | %.2f | %d | %.2f | %d | %.1f | %.1f | %.0f %% |\n", rows[i].dofs, d.dt * 1e6, d.elastic_steps,
                d.elastic_steps ? d.elastic_wall / d.elastic_steps * 1e3 : 0.0, d.damaged_steps,
                d.damaged_steps ? double(d.iterations) / d.damaged_steps : 0.0,
                d.damaged_steps ? d.damaged_wall / d.damaged_steps * 1e3 : 0.0, 100 * d.share);
  }
  return 0;
}
