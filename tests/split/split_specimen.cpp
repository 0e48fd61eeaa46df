// One specimen split across the ranks of an MPI launch (World::split): tests/split/split_world_check.cpp steps a
// bonded block whole and split on every rank and compares the bits; here it runs on 1, 2 and 4 ranks (two cores:
// --oversubscribe). Built when the build has MPI and an mpirun.
#include "tests/common/cli_harness.hpp"

#ifdef MESOCRACK_MPIEXEC

// Each contact is computed on every rank that holds one of its particles and each particle sums its contacts in
// the whole world's order, so a split run must equal the whole run to the last bit: particles, timestep, walls,
// energy and crack log, through bond breaks, migration between ranks at every rebuild, new regions when the load
// is out of balance, an adaptive skin, walls under velocity, stress and opening control, gravity and energy.
TEST_CASE("split_specimen_on_1_2_and_4_ranks_gives_the_whole_world_bits") {
  const TempDir d;
  for (int n : {1, 2, 4}) {
    const Result r =
        Child({}, d.dir, {"OMPI_ALLOW_RUN_AS_ROOT=1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1", "OMP_NUM_THREADS=1"},
              {MESOCRACK_MPIEXEC, "-np", std::to_string(n), "--oversubscribe"}, SPLIT_WORLD_CHECK)
            .wait();
    MESSAGE(n, " ranks: ", r.out);
    REQUIRE_MESSAGE(r.code == 0, n, " ranks: ", r.describe());
    // Every rank reported each scene; particles changed hands, and the drifting block's regions were drawn anew
    // (one rank: neither can happen).
    int reports = 0;
    long arrived = 0, rebalances = 0;
    auto number_before = [&](std::size_t at, const char* word) {
      const std::size_t end = r.out.find(word, at);
      return std::stol(r.out.substr(r.out.rfind(' ', end - 1) + 1));
    };
    for (std::size_t at = 0; (at = r.out.find("same bits", at)) != std::string::npos; ++at) {
      ++reports;
      arrived += number_before(at, " arrived");
      rebalances += number_before(at, " rebalances");
    }
    CHECK(reports == 4 * n);  // four scenes
    int stops = 0;
    for (std::size_t at = 0; (at = r.out.find("same stop: ", at)) != std::string::npos; ++at) ++stops;
    CHECK(stops == 3 * n);  // three failures found alike on every rank
    if (n > 1) CHECK(arrived > 0);
    if (n > 1) CHECK(rebalances > 0);
  }
}

#endif
