// Cost and capability of the mesostructure generator (Tang 2013 §4.4), printed as markdown tables.
//
//  a) generator: time to make the aggregate database (random shapes filling Table 4.1) versus the number of
//     aggregates, 2D and 3D (Tang Figs. 4.15, 4.16);
//  b) success: the share of seeds that reach a target fraction, versus the fraction (Figs. 4.17, 4.18), on a
//     200 mm square and the 100 mm cube, Table 4.1;
//  c) disposition: time versus fraction on squares of 300, 400, 500 mm and cubes of 100, 150 mm (Figs. 4.19, 4.20),
//     and so versus the number of aggregates;
//  d) the specimens of Tang's tests: the 400 x 100 mm notched beam at 60 % (Tang §7.1: 3 x 10 mm notch, 10 mm of
//     mortar around its tip; Table 4.1 in full, 4–64 mm at 2:2:3:3 — §7.1's four grades at 3:3:2:2 coarsest first;
//     64 mm fits the 100 mm depth) and, beside it, the same beam with Table 4.1 cut at 32 mm (4–8, 8–16, 16–32 mm at
//     2:2:3, a maximum size of a third of the depth); the 100 mm cube at 50 % with Table 4.1.
//
// The generator runs on one thread: times are wall times of one process (std::chrono::steady_clock); "cpu/wall"
// below 0.9 means the machine was busy with something else. Lengths in mm.
//
//   aggregate_generation [--quick] [--seeds N]    (N: seeds per success-rate point, default 50 (2D) / 20 (3D))
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <string>
#include <vector>

#include "benchmarks/options.hpp"
#include "preprocess/aggregate_placement.hpp"

namespace {

using namespace mc;
using Clock = std::chrono::steady_clock;

struct Run {
  double seconds = 0, cpu_seconds = 0;
  std::size_t aggregates = 0;
  double achieved = 0;
  bool reached = false;
  std::int64_t attempts = 0;
};

template <int D>
Run run(const PlacementSpec<D>& spec) {
  const auto t0 = Clock::now();
  const std::clock_t c0 = std::clock();
  const AggregateLayout<D> lay = place_aggregates(spec);
  Run r;
  r.cpu_seconds = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  r.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  r.aggregates = lay.aggregates.size();
  r.achieved = lay.achieved_fraction;
  r.reached = lay.reached;
  r.attempts = lay.attempts;
  return r;
}

template <int D>
PlacementSpec<D> box(double side, double fraction, std::uint64_t seed, const Grading& g = tang_table_4_1()) {
  PlacementSpec<D> s;
  s.lo = Vec<D>::Zero();
  s.hi = Vec<D>::Constant(side);
  s.fraction = fraction;
  s.seed = seed;
  s.grading = g;
  return s;
}

// Several seeds: mean and max wall time, mean count, how many reached.
struct Summary {
  double mean = 0, max = 0, cpu = 0, aggregates = 0, min_achieved = 1;
  int reached = 0, runs = 0;
};

template <int D>
Summary repeat(PlacementSpec<D> spec, int seeds) {
  Summary s;
  for (int k = 1; k <= seeds; ++k) {
    spec.seed = static_cast<std::uint64_t>(k);
    const Run r = run(spec);
    s.mean += r.seconds / seeds;
    s.cpu += r.cpu_seconds / seeds;
    s.max = std::max(s.max, r.seconds);
    s.aggregates += static_cast<double>(r.aggregates) / seeds;
    s.min_achieved = std::min(s.min_achieved, r.achieved);
    s.reached += r.reached;
    ++s.runs;
  }
  return s;
}

double cpu_share(const Summary& s) { return s.mean > 0 ? s.cpu / s.mean : 1; }

void generator_table(bool quick) {
  std::printf("\n### a) Aggregate generator: time versus number of aggregates (Tang Figs. 4.15, 4.16)\n\n");
  std::printf(
      "Random convex shapes (default limits L_max = 0.5 d, L_min = 0.15 d) filling Table 4.1 shares of a target\n"
      "area / volume; time per shape includes drawing the sizes.\n\n");
  std::printf("| dim | target content | aggregates | time [ms] | per aggregate [us] | mean vertices |\n");
  std::printf("|---|---|---|---|---|---|\n");
  for (int dim = 2; dim <= 3; ++dim) {
    const std::vector<double> targets =
        dim == 2 ? std::vector<double>{2e4, 6e4, 2e5, 6e5, 2e6} : std::vector<double>{1e5, 3e5, 1e6, 3e6, 1e7};
    for (double target : targets) {
      if (quick && target > (dim == 2 ? 2e5 : 1e6)) continue;
      RandomStream rng(1);
      std::size_t vertices = 0;
      const auto t0 = Clock::now();
      const auto list = fill_grading(
          tang_table_4_1(), target, dim,
          [&](double d) {
            if (dim == 2) {
              const Polygon p = random_polygon(d, ShapeParams{}, rng);
              vertices += p.v.size();
              return area(p);
            }
            const Polyhedron p = random_polyhedron(d, ShapeParams{}, rng);
            vertices += p.v.size();
            return volume(p);
          },
          rng);
      const double ms = 1e3 * std::chrono::duration<double>(Clock::now() - t0).count();
      std::printf("| %dD | %.0e mm%s | %zu | %.1f | %.1f | %.1f |\n", dim, target, dim == 2 ? "²" : "³", list.size(),
                  ms, 1e3 * ms / list.size(), static_cast<double>(vertices) / list.size());
    }
  }
}

void success_table(bool quick, int seeds2, int seeds3) {
  std::printf("\n### b) Success rate versus target fraction (Tang Figs. 4.17, 4.18), Table 4.1\n\n");
  std::printf(
      "| dim | domain | fraction | reached | seeds | lowest fraction achieved | mean time [s] | max time [s] |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (double f : {0.5, 0.6, 0.65, 0.7, 0.75, 0.8, 0.85}) {
    const Summary s = repeat(box<2>(200, f, 1), seeds2);
    std::printf("| 2D | 200 mm square | %.2f | %d | %d | %.4f | %.3f | %.3f |\n", f, s.reached, s.runs, s.min_achieved,
                s.mean, s.max);
  }
  for (double f : {0.3, 0.4, 0.5, 0.55, 0.6}) {
    if (quick && f > 0.5) continue;
    const Summary s = repeat(box<3>(100, f, 1), seeds3);
    std::printf("| 3D | 100 mm cube | %.2f | %d | %d | %.4f | %.3f | %.3f |\n", f, s.reached, s.runs, s.min_achieved,
                s.mean, s.max);
  }
}

void cost_table(bool quick) {
  std::printf("\n### c) Disposition cost versus fraction and specimen size (Tang Figs. 4.19, 4.20), Table 4.1\n\n");
  std::printf("Whole generation (shapes and placement), mean of 3 seeds.\n\n");
  std::printf("| dim | domain | fraction | aggregates | reached | mean time [s] | cpu/wall |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  for (double side : {300.0, 400.0, 500.0}) {
    for (double f : {0.4, 0.5, 0.6, 0.7, 0.8}) {
      if (quick && side > 300) continue;
      const Summary s = repeat(box<2>(side, f, 1), 3);
      std::printf("| 2D | %.0f mm square | %.1f | %.0f | %d/3 | %.3f | %.2f |\n", side, f, s.aggregates, s.reached,
                  s.mean, cpu_share(s));
    }
  }
  for (double side : {100.0, 150.0}) {
    for (double f : {0.3, 0.4, 0.45, 0.5, 0.55, 0.6}) {
      if (quick && (side > 100 || f > 0.5)) continue;
      const Summary s = repeat(box<3>(side, f, 1), 3);
      std::printf("| 3D | %.0f mm cube | %.2f | %.0f | %d/3 | %.3f | %.2f |\n", side, f, s.aggregates, s.reached,
                  s.mean, cpu_share(s));
    }
  }
}

void specimens_table(int seeds) {
  std::printf("\n### d) The specimens of Tang's tests (one thread; the machine has 2 cores)\n\n");
  std::printf(
      "| specimen | grading | fraction | aggregates | reached | mean time [s] | max time [s] | target | cpu/wall |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  auto beam = [](const Grading& g) {
    PlacementSpec<2> s;
    s.hi = Vec<2>(400, 100);
    s.grading = g;
    s.fraction = 0.6;
    s.keep_out_boxes.push_back({Vec<2>(198.5, 0), Vec<2>(201.5, 10)});  // 3 mm wide, 10 mm deep notch
    s.keep_out_balls.push_back({Vec<2>(200, 10), 10});                  // mortar within 10 mm of its tip
    return s;
  };
  const Grading to32{{{4, 8, 2.0 / 7}, {8, 16, 2.0 / 7}, {16, 32, 3.0 / 7}}};
  for (int which = 0; which < 2; ++which) {
    const Summary s = repeat(beam(which == 0 ? tang_table_4_1() : to32), seeds);
    std::printf("| 400 x 100 mm beam, notched | %s | 0.60 | %.0f | %d/%d | %.4f | %.4f | < 1 s: %s | %.2f |\n",
                which == 0 ? "Table 4.1, 4-64 mm" : "Table 4.1 to 32 mm, 2:2:3", s.aggregates, s.reached, s.runs,
                s.mean, s.max, s.max < 1 ? "yes" : "NO", cpu_share(s));
  }
  const Summary c = repeat(box<3>(100, 0.5, 1), seeds);
  std::printf("| 100 mm cube | Table 4.1, 4-64 mm | 0.50 | %.0f | %d/%d | %.3f | %.3f | < 60 s: %s | %.2f |\n",
              c.aggregates, c.reached, c.runs, c.mean, c.max, c.max < 60 ? "yes" : "NO", cpu_share(c));
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  int seeds = 0;
  CLI::App app{"aggregate_generation: the mesostructure generator's cost and capability, as markdown tables"};
  app.add_flag("--quick", quick, "fewer sizes and seeds");
  app.add_option("--seeds", seeds, "seeds per success-rate point (default 50 in 2D, 20 in 3D; 10 and 5 with --quick)")
      ->check(CLI::Range(1, 10000));
  if (const auto code = mc::bench::read_options(app, argc, argv, "aggregate_generation")) return *code;
  const int seeds2 = seeds > 0 ? seeds : (quick ? 10 : 50), seeds3 = seeds > 0 ? seeds : (quick ? 5 : 20);
  std::printf("## Mesostructure generation (Tang 2013 ch. 4)%s\n", quick ? " — quick" : "");
  specimens_table(quick ? 3 : 10);
  generator_table(quick);
  success_table(quick, seeds2, seeds3);
  cost_table(quick);
  return 0;
}
