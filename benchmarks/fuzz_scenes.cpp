// The scene reader under mutated shipped scenes, by the million (tests/robustness/scene_fuzzer.cpp runs 10^4 of
// the same inputs in the test suite; the mutations and the judgement are in tests/robustness/scene_mutations.hpp).
// Prints the count of each outcome, per mutation kind, the slowest input and every wrong outcome (up to --show);
// exits 1 when any outcome is wrong. A crash or a hang stops the run naming the input.
//
//   fuzz_scenes [--seed S] [--count N] [--show M]   (defaults: the test's seed, 10^6 inputs, 20 shown)
//   fuzz_scenes --seed S --only K                    (input K alone: its text, overrides and outcome)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>

#include "benchmarks/options.hpp"
#include "tests/robustness/scene_mutations.hpp"

namespace {

using namespace mc::fuzz;

struct Options {
  std::uint64_t seed = 20240614, count = 1000000, show = 20;
  long long only = -1;
};

const char* outcome_name(Outcome o) {
  return o == Outcome::Accepted ? "accepted" : o == Outcome::Refused ? "refused" : "WRONG";
}

int show_one(const std::vector<SeedScene>& seeds, const Options& o) {
  const Mutant m = Mutator(o.seed, static_cast<std::uint64_t>(o.only)).mutate(seeds);
  std::printf("# input %lld of seed %llu: %s", o.only, static_cast<unsigned long long>(o.seed),
              seeds[m.seed_index].name.c_str());
  for (const auto& x : m.mutations) std::printf(" %s", x.c_str());
  std::printf("\n");
  for (const auto& x : m.overrides) std::printf("# --set %s\n", x.c_str());
  std::fwrite(m.text.data(), 1, m.text.size(), stdout);
  std::fflush(stdout);  // before reading it, which may hang or crash
  const Judgement j = judge(m, seeds[m.seed_index].name);
  std::fprintf(stderr, "%s: %s\n", outcome_name(j.outcome), j.detail.c_str());
  return j.outcome == Outcome::Wrong ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{"fuzz_scenes: the scene reader under mutated shipped scenes, by the million"};
  app.add_option("--seed", o.seed, "the mutations' seed (default: the test's)")->check(mc::bench::kWholeNumber);
  app.add_option("--count", o.count, "inputs")->check(mc::bench::kWholeNumber);
  app.add_option("--show", o.show, "wrong outcomes shown at most")->check(mc::bench::kWholeNumber);
  app.add_option("--only", o.only, "input K alone: its text, overrides and outcome")->check(mc::bench::kWholeNumber);
  if (const auto code = mc::bench::read_options(app, argc, argv, "fuzz_scenes")) return *code;
  const auto seeds = shipped_scenes(MESOCRACK_SOURCE_DIR);
  if (seeds.empty()) return std::fprintf(stderr, "no scenes under %s\n", MESOCRACK_SOURCE_DIR), 2;
  if (o.only >= 0) return show_one(seeds, o);

  std::map<std::string, std::array<std::uint64_t, 3>> per_kind;  // mutation -> accepted, refused, wrong
  std::array<std::uint64_t, 3> total{};
  double slowest = 0;
  std::uint64_t slowest_k = 0, shown = 0;
  const auto t0 = std::chrono::steady_clock::now();
  Watchdog watchdog(o.seed, 10);
  for (std::uint64_t k = 0; k < o.count; ++k) {
    const Mutant m = Mutator(o.seed, k).mutate(seeds);
    watchdog.start(k);
    const Judgement j = judge(m, seeds[m.seed_index].name);
    watchdog.stop();
    const auto at = static_cast<std::size_t>(j.outcome);
    ++total[at];
    for (const auto& x : m.mutations) ++per_kind[x][at];
    if (j.seconds > slowest) slowest = j.seconds, slowest_k = k;
    if (j.outcome == Outcome::Wrong && shown++ < o.show)
      std::printf("WRONG input %llu (%s): %s\n", static_cast<unsigned long long>(k), seeds[m.seed_index].name.c_str(),
                  j.detail.c_str());
    if ((k + 1) % 100000 == 0) std::fprintf(stderr, "%llu inputs\n", static_cast<unsigned long long>(k + 1));
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("\n%llu inputs of seed %llu from %zu scenes in %.1f s (%.0f per second); slowest: input %llu, %.3f s\n\n",
              static_cast<unsigned long long>(o.count), static_cast<unsigned long long>(o.seed), seeds.size(), wall,
              static_cast<double>(o.count) / wall, static_cast<unsigned long long>(slowest_k), slowest);
  std::printf("| mutation | accepted | refused | wrong |\n|---|---|---|---|\n");
  for (const auto& [kind, n] : per_kind)
    std::printf("| %s | %llu | %llu | %llu |\n", kind.c_str(), static_cast<unsigned long long>(n[0]),
                static_cast<unsigned long long>(n[1]), static_cast<unsigned long long>(n[2]));
  std::printf("| **all inputs** | %llu | %llu | %llu |\n", static_cast<unsigned long long>(total[0]),
              static_cast<unsigned long long>(total[1]), static_cast<unsigned long long>(total[2]));
  return total[2] > 0 ? 1 : 0;
}
