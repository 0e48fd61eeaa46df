// The scene reader under 10^4 mutated shipped scenes (tests/robustness/scene_mutations.hpp: the mutations and the
// rule each outcome is judged by), read in-process with a fixed seed: every input is accepted as a valid scene or
// refused with a one-line message that places the fault; none crashes, hangs or throws anything else.
// benchmarks/fuzz_scenes runs the same inputs by the million.
#include <doctest/doctest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "tests/robustness/scene_mutations.hpp"

namespace {

constexpr std::uint64_t kSeed = 20240614;
constexpr std::uint64_t kInputs = 10000;
constexpr unsigned kBudgetSeconds = 10;  // per input; the slowest takes milliseconds
constexpr std::size_t kReported = 20;    // wrong outcomes printed in full; the count covers all

}  // namespace

TEST_CASE("fuzzed_scenes_are_read_or_refused_with_a_placed_message_never_crash_hang_or_throw_else") {
  using namespace mc::fuzz;
  const auto seeds = shipped_scenes(MESOCRACK_SOURCE_DIR);
  REQUIRE(seeds.size() >= 14);  // scenes/, scenes/specimens/ and tests/scenes/
  std::size_t accepted = 0, refused = 0, wrong = 0;
  double slowest = 0;
  {
    Watchdog watchdog(kSeed, kBudgetSeconds);
    for (std::uint64_t k = 0; k < kInputs; ++k) {
      const Mutant m = Mutator(kSeed, k).mutate(seeds);
      watchdog.start(k);
      const Judgement j = judge(m, seeds[m.seed_index].name);
      watchdog.stop();
      slowest = std::max(slowest, j.seconds);
      if (j.outcome == Outcome::Accepted) ++accepted;
      if (j.outcome == Outcome::Refused) ++refused;
      if (j.outcome != Outcome::Wrong) continue;
      if (++wrong <= kReported)
        FAIL_CHECK("input ", k, " (", seeds[m.seed_index].name, ", ", m.mutations.size(),
                   " mutations; fuzz_scenes --seed ", kSeed, " --only ", k, "): ", j.detail);
    }
  }
  MESSAGE(accepted, " accepted, ", refused, " refused, ", wrong, " wrong; slowest input ", slowest, " s");
  CHECK(wrong == 0);
  // Both outcomes occur: a fuzzer whose every input is refused (or accepted) tests one path only.
  CHECK(accepted > kInputs / 100);
  CHECK(refused > kInputs / 2);
}
