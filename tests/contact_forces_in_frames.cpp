// The contacts a frame records (/contacts) on the two discs of scenes/collision_2d.toml, a frame every step: each
// frame's normal force is the linear law's k_n δ at the overlap δ = r_a + r_b − |branch| of the branch vector it
// records (Tang (3.25), (3.38): k_n = 2 t E_c / 2 = 5e7 N/m), head-on without shear, no bond; frames without a
// touching pair record none.
#include <cmath>

#include "tests/common/cli_harness.hpp"
#include "tests/common/relative.hpp"

TEST_CASE("contact_forces_in_frames_are_the_linear_law_at_the_branch_vector_they_record") {
  const TempDir d;
  const Result r = mesocrack({"run", (kScenes / "collision_2d.toml").string(), "-o", "c.h5", "--threads", "1", "--set",
                              "output.frame_every=1"},
                             d.dir);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  const mc::H5File f((d / "c.h5").string(), mc::H5File::Mode::ReadOnly);
  const auto first = f.read_ints("/contacts/frame_first"), count = f.read_ints("/contacts/frame_count");
  const auto pair = f.read_ints("/contacts/pair"), bonded = f.read_ints("/contacts/bonded");
  const auto normal = f.read_doubles("/contacts/normal_force"), shear = f.read_doubles("/contacts/shear_force");
  const auto branch = f.read_doubles("/contacts/branch");
  REQUIRE(first.size() == f.rows("/frames/time"));
  constexpr double kn = 5e7, radius = 1e-3;
  int touching = 0;
  double largest = 0;
  for (std::size_t k = 0; k < first.size(); ++k) {
    CHECK(count[k] <= 1);
    if (count[k] == 0) continue;
    const auto c = static_cast<std::size_t>(first[k]);
    ++touching;
    CHECK(pair[2 * c] == 0);
    CHECK(pair[2 * c + 1] == 1);
    CHECK(bonded[c] == 0);
    const double length = std::hypot(branch[2 * c], branch[2 * c + 1]);
    // δ ≈ 1e-6 m out of |branch| ≈ 2e-3 m: its rounding is 1e-13 of the force, so 1e-9 leaves room and no more.
    CHECK(normal[c] == mc::test::relative(kn * (2 * radius - length), 1e-9));
    CHECK(shear[c] <= 1e-12 * normal[c]);  // head-on: the branch vector stays on x
    largest = std::max(largest, normal[c]);
  }
  // The contact lasts π √(m*/k_n) = 28.4 µs, some 70 steps at the scene's safety 0.05: each a frame with it.
  CHECK(touching > 50);
  // Energy: ½ m* v² = ½ k_n δ_max², m* = m/2, v = 0.1 m/s: the largest force √(k_n m*) v; sampled at ~70 steps a
  // contact the peak is missed by at most 1 − cos(π/140) < 0.03 %, so 1 % is the law, not the sampling.
  const double m_star = 0.5 * 2600 * M_PI * radius * radius;
  CHECK(largest == mc::test::relative(std::sqrt(kn * m_star) * 0.1, 0.01));
}
