// What fibres cost a step of the rigid-cell model as their number grows: the prism of Květoň §6.3 (60 × 20 × 10 mm,
// l_min 2.5 mm, f_t 3.8 MPa, G_t 20 J/m²; §6.1's PVA aligned with the pull, l_f 10 mm) held by 10 mm grips at its
// ends, with 10³ to 10⁵ fibres. For each count: the placement and the crossing walk; the parts of a secant iteration
// timed alone, every crossing taking part (the fibres' evaluation at an iterate, their secants spread into the
// stiffness on top of the facets' refill, the factorisation and a solve); then the scene fibre_prism_tension_3d.toml
// itself with that many fibres, stepped as a run steps it, over its first load steps of 5 µm (the first crack and
// the hardening after it): secant iterations, cut steps, wall time per step and per iteration, and the fibres' share
// of it (the time the system spent in its fibres, FibreBridges::seconds, over the steps' wall time).
// Usage: fibre_step_cost [--fibres 1000,3000,10000,30000,100000] [--steps N]
#include <Eigen/CholmodSupport>
#include <algorithm>
#include <chrono>
#include <memory>
#include <stdexcept>
#include <cstdio>
#include <string>
#include <vector>

#include "benchmarks/options.hpp"
#include "benchmarks/rigid_cell/timing.hpp"
#include "engine/errors.hpp"
#include "rigid_cell/fibre_bridges.hpp"
#include "rigid_cell/fibre_crossings.hpp"
#include "rigid_cell/free_stiffness.hpp"
#include "rigid_cell/node_placement.hpp"
#include "rigid_cell/plate_constraints.hpp"
#include "rigid_cell/rigid_cell_system.hpp"
#include "rigid_cell/static_solver.hpp"
#include "scene/make_system.hpp"
#include "scene/scene.hpp"
#include "scene/toml_reader.hpp"

using namespace mc;
using namespace mc::rigid_cell;
using mc::bench::best_of;
using mc::bench::Clock;
using mc::bench::seconds_since;

namespace {

const Vec<3> kSize(0.06, 0.02, 0.01);
constexpr double kLmin = 2.5e-3, kGrip = 0.01, kStep = 5e-6;
const FacetParams kMortar{48e9, 0.237, 3.8e6, 20};  // §6.3

FibreMaterial pva() {  // §6.1
  FibreMaterial f;
  f.modulus = 30e9, f.diameter = 40e-6, f.tensile_strength = 1000e6, f.friction_stress = 2e6, f.debonding_energy = 5;
  return f;
}

// The prism's cells, and its two grips as plates: the left held, the right pulled along x.
struct Prism {
  Tessellation<3> t;
  CellAssembly<3> model;
  std::vector<int> plate_of;
  std::vector<Vec<3>> references;
  Prism()
      : t(tessellate(place_nodes(SpecimenShape<3>::box(kSize), kLmin, 3, 3000), SpecimenShape<3>::box(kSize),
                     3 * kLmin)),
        model(t, std::vector<FacetParams>(t.contacts, kMortar)) {
    Vec<3> sum[2] = {Vec<3>::Zero(), Vec<3>::Zero()};
    int count[2] = {0, 0};
    for (const auto& c : t.cells) {
      const int p = c.node.x() < kGrip ? 0 : c.node.x() > kSize.x() - kGrip ? 1 : -1;
      plate_of.push_back(p);
      if (p >= 0) sum[p] += c.node, ++count[p];
    }
    references = {sum[0] / count[0], sum[1] / count[1]};
  }
  std::vector<Vec<3>> nodes() const {
    std::vector<Vec<3>> n;
    for (const auto& c : t.cells) n.push_back(c.node);
    return n;
  }
};

struct Row {
  long fibres = 0;
  std::size_t crossings = 0, bridged = 0;
  double place = 0, cross = 0;                           // s, once
  double evaluate = 0, refill = 0, refill_bare = 0;      // s, each part alone, every crossing taking part
  double factorise = 0, solve = 0;
  int steps = 0, iterations = 0, cuts = 0;
  double wall = 0, in_fibres = 0;  // s, in situ: the steps', and the fibres' part of them (FibreBridges::seconds)
  double fibre_share() const { return in_fibres / wall; }
};

Row measure(const Prism& p, long fibres, int steps) {
  Row r;
  r.fibres = fibres;
  FibrePlacement placement;
  placement.count = fibres, placement.length = 0.01, placement.diameter = 40e-6;
  placement.orientation = FibreOrientation::Aligned;
  RandomStream rng(7);
  auto t0 = Clock::now();
  const std::vector<Fibre> placed = place_fibres(SpecimenShape<3>::box(kSize), placement, rng);
  r.place = seconds_since(t0);
  t0 = Clock::now();
  const std::vector<FibreCrossing> crossings = fibre_crossings(p.t, placed);
  const std::vector<int> family(placed.size(), 0);
  FibreBridges<3> bridges(p.t, p.model, {pva()}, bridge_sites(placed, family, crossings));
  r.cross = seconds_since(t0);
  r.crossings = bridges.sites(), r.bridged = bridges.contacts().size();

  const PlateConstraints<3> plates(p.nodes(), p.plate_of, p.references);
  std::vector<int> prescribed;
  for (int k = 0; k < 6; ++k) prescribed.push_back(plates.plate_dof(0, k)), prescribed.push_back(plates.plate_dof(1, k));

  // The parts alone, every crossing taking part (as once the prism has cracked throughout).
  {
    bridges.commit(std::vector<double>(p.model.contacts(), 0.5));
    // Every cell moved along x by 40 µm over the prism's length: every crossing opens by a micron or two, debonding.
    Eigen::VectorXd u_cells = Eigen::VectorXd::Zero(6 * p.model.cells());
    for (int c = 0; c < p.model.cells(); ++c) u_cells[6 * c] = 40e-6 / kSize.x() * p.t.cells[c].node.x();
    // Best of ten: the first calls pay for OpenMP's threads starting (measured up to 25 times the rest).
    r.evaluate = best_of(10, [&] { bridges.evaluate(u_cells); });
    std::vector<int> is_free(plates.reduced(), 1);
    for (int d : prescribed) is_free[d] = 0;
    std::vector<Eigen::Triplet<double>> pick;
    for (int d = 0, col = 0; d < plates.reduced(); ++d)
      if (is_free[d]) pick.emplace_back(d, col++, 1.0);
    SparseMatrix to_free(plates.reduced(), plates.reduced() - static_cast<int>(prescribed.size()));
    to_free.setFromTriplets(pick.begin(), pick.end());
    const SparseMatrix to_cells = plates.map() * to_free;
    const std::vector<double> damage(p.model.contacts(), 0.5);
    FreeStiffness<3> with(p.model, to_cells, &bridges), bare(p.model, to_cells);
    r.refill = best_of(10, [&] { with(damage); });
    r.refill_bare = best_of(10, [&] { bare(damage); });
    const SparseMatrix& K = with(damage);
    Eigen::CholmodDecomposition<SparseMatrix, Eigen::Lower> cholesky;
    cholesky.analyzePattern(K);
    r.factorise = best_of(3, [&] { cholesky.factorize(K); });
    const Eigen::VectorXd b = Eigen::VectorXd::Ones(K.rows());
    r.solve = best_of(3, [&] { Eigen::VectorXd x = cholesky.solve(b); });
  }

  // In situ: the scene itself, its volume fraction set to this count, stepped by the system a run steps (with its
  // cuts of a step that does not converge and its snap-throughs).
  const double fraction = static_cast<double>(fibres) * 0.25 * M_PI * 40e-6 * 40e-6 * 0.01 / kSize.prod();
  const std::string file = std::string(MESOCRACK_SOURCE_DIR) + "/scenes/fibre_prism_tension_3d.toml";
  const Scene scene = read_scene(
      TomlDoc::load(file, {"rigid_cell.fibres[0].volume_fraction=" + std::to_string(fraction),
                           "run.steps=" + std::to_string(steps)}),
      file);
  const std::unique_ptr<System> system = make_system(scene);
  system->start();
  const auto* cells = dynamic_cast<const RigidCellSystem<3>*>(system.get());
  if (!cells || !cells->bridges()) throw std::logic_error(file + ": not a rigid-cell scene with fibres");
  const double before = cells->bridges()->seconds();
  const auto series = [&](const std::string& name) {
    for (const Series& h : system->histories())
      if (h.name == name) return h.sample;
    throw std::logic_error("no history " + name);
  };
  const auto iterations = series("iterations"), cuts = series("step_cuts");
  for (int step = 1; step <= steps; ++step) {
    t0 = Clock::now();
    try {
      system->step();
    } catch (const InstabilityError& e) {
      std::fprintf(stderr, "  %ld fibres: step %d stops the measurement: %s\n", fibres, step, e.what());
      break;
    }
    r.wall += seconds_since(t0);
    r.steps += 1, r.iterations += static_cast<int>(iterations()), r.cuts += static_cast<int>(cuts());
  }
  r.in_fibres = cells->bridges()->seconds() - before;
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<long> counts{1000, 3000, 10000, 30000, 100000};
  int steps = 6;
  CLI::App app{"fibre_step_cost: what fibres cost a step of the rigid-cell model as their number grows"};
  app.add_option("--fibres", counts, "N,N,...: fibres in the prism")->delimiter(',')->check(CLI::Range(1L, 10000000L));
  app.add_option("--steps", steps, "load steps of 5 um in situ")->check(CLI::Range(1, 200));
  if (const auto code = mc::bench::read_options(app, argc, argv, "fibre_step_cost")) return *code;
  const Prism prism;
  std::printf("Květoň §6.3 prism, %d cells, %zu contact facets, %d free DOFs; %d load steps of %.0f µm\n\n",
              prism.model.cells(), prism.model.contacts(),
              prism.model.dofs() - 6 * static_cast<int>(std::count_if(prism.plate_of.begin(), prism.plate_of.end(),
                                                                       [](int p) { return p >= 0; })),
              steps, kStep * 1e6);
  std::printf("| fibres | crossings | facets bridged | place [ms] | cross [ms] | evaluate [ms] | refill +fibres / bare "
              "[ms] | factorise [ms] | solve [ms] | steps | iterations | cuts | per step [s] | per iteration [ms] | "
              "fibres' share |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (long n : counts) {
    const Row r = measure(prism, n, steps);
    std::printf("| %ld | %zu | %zu | %.1f | %.1f | %.2f | %.2f / %.2f | %.2f | %.2f | %d | %d | %d | %.2f | %.1f | %.0f %% |\n",
                r.fibres, r.crossings, r.bridged, 1e3 * r.place, 1e3 * r.cross, 1e3 * r.evaluate, 1e3 * r.refill,
                1e3 * r.refill_bare, 1e3 * r.factorise, 1e3 * r.solve, r.steps, r.iterations, r.cuts,
                r.steps ? r.wall / r.steps : 0.0, r.iterations ? 1e3 * r.wall / r.iterations : 0.0,
                r.iterations ? 100 * r.fibre_share() : 0.0);
    std::fflush(stdout);
  }
  return 0;
}
