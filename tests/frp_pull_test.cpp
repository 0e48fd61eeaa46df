// The FRP-to-concrete pull test through the real `mesocrack` command ([pullout], Tang §8.1): the strain profile
// of an elastic pull (scenes/pull_elastic_2d.toml) against the shear-lag solution, and bad [pullout] and driven-
// group keys refused naming them.
#include <cmath>
#include <string>
#include <vector>

#include "tests/common/cli_harness.hpp"
#include "tests/common/relative.hpp"

namespace {

const std::string kPull = (kScenes / "pull_elastic_2d.toml").string();

std::vector<double> history(const fs::path& file, const std::string& name) {
  const mc::H5File f(file.string(), mc::H5File::Mode::ReadOnly);
  return f.read_doubles("/history/" + name);
}

}  // namespace

// A sheet of axial stiffness EA on a rigid substrate through an interface of stiffness K per unit length, pulled
// by F at x = 0 and free at x = L: EA u'' = K u gives the sheet's force N(x) = F sinh(λ(L − x))/sinh(λL),
// λ = √(K/EA) (the linear bond-slip shear-lag solution). Gauge k reads the mean strain over [x_k, x_k+1]:
// ε₀ (cosh(λ(L − x_k)) − cosh(λ(L − x_k+1))) / (λ Δx sinh(λL)), ε₀ = F/EA (Tang 8.5). The scene's lattice gives
// EA = k_f 2r and K = (k_n + 3 k_s)/(4r) (two adhesive contacts per disc at ±60°; the sheet's own shear springs
// keep its discs from rolling, which would soften K by ~(√3/4) k_s/k_f ≈ 3e-4). What the solution leaves out:
// the lattice's discreteness (λ 2r = 0.03: ~1e-4), the half-disc of interface at the bond's loaded end (0.5 % of
// the length), and the inertia left after 90 wave transits under damping: each gauge within 5 % of ε₀.
TEST_CASE("frp_strain_profile_of_an_elastic_pull_follows_the_shear_lag_solution") {
  const TempDir d;
  const Result r = mesocrack({"run", kPull, "-o", "pull.h5"}, d.dir);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  const double radius = 0.2e-3, kf = 100e9, kn = 72e6, ks = kn / 2, length = 40e-3;
  const double ea = kf * 2 * radius, k = (kn + 3 * ks) / (4 * radius), lambda = std::sqrt(k / ea);
  const double force = history(d / "pull.h5", "pullout.load").back();
  const double eps0 = force / ea;
  REQUIRE(eps0 > 1e-5);
  const int gauges = 10;
  const double dx = length / gauges;
  for (int g = 0; g < gauges; ++g) {
    const double strain = history(d / "pull.h5", "pullout.strain_" + std::to_string(g)).back();
    const double x0 = g * dx, x1 = x0 + dx;
    const double expected = eps0 * (std::cosh(lambda * (length - x0)) - std::cosh(lambda * (length - x1))) /
                            (lambda * dx * std::sinh(lambda * length));
    MESSAGE("gauge ", g, " at ", (x0 + x1) / 2 * 1e3, " mm: strain / eps0 = ", strain / eps0, ", shear lag ",
            expected / eps0);
    CHECK(std::abs(strain - expected) < 0.05 * eps0);
  }
  const Json j = summary_of("pull.h5", d.dir);
  // The summary sets the final profile beside the same solution for the scene's interface_stiffness (= K).
  const Json& lag = j["pullout"]["shear_lag"];
  CHECK(lag["lambda"].number == mc::test::relative(lambda, 1e-9));
  CHECK(lag["max_deviation_over_epsilon_0"].number < 0.05);
  // The reported capacity is the load per metre times the sheet's width (b_f = 50 mm), and β_w of (8.1) for
  // b_f/b_c = 50/80 is √(1.375/1.625); the summary prints 10 significant digits.
  CHECK(j["pullout"]["capacity"].number == mc::test::relative(j["pullout"]["capacity_simulated"].number * 0.05, 1e-5));
  CHECK(j["pullout"]["beta_w"].number == mc::test::relative(std::sqrt(1.375 / 1.625), 1e-9));
}

// Bad [pullout] keys and a driven group that cannot be driven: exit 2, naming the file, the key, the value and
// what is allowed; nothing written.
TEST_CASE("bad_pullout_and_driven_group_keys_are_refused_naming_the_key") {
  const TempDir d;
  const std::vector<SceneEdit> edits = {
      {"pulled = \"grip\"", "pulled = \"prism\"", {"pullout.pulled", "not driven"}},
      {"pulled = \"grip\"", "pulled = \"hand\"", {"pullout.pulled", "'hand' is not the name"}},
      {"slip = \"slip\"\nfrp", "slip = \"prism\"\nfrp", {"pullout.slip", "opening probe"}},
      {"frp_phase = \"frp\"", "frp_phase = \"steel\"", {"pullout.frp_phase", "steel"}},
      {"bonded_to = \"40 mm\"", "bonded_to = 0", {"pullout.bonded_to", "bonded length must be positive"}},
      {"prism_width = \"80 mm\"", "prism_width = \"40 mm\"", {"pullout.width", "wider than the prism"}},
      {"gauges = 10", "gauges = 0", {"pullout.gauges"}},
      {"frp_thickness = \"0.4 mm\"", "frp_thickness = \"0.4 mm\"\nanchor = 1", {"pullout.anchor"}},
      {"fix = \"x y\"", "fix = \"y\"", {"groups[1].fix", "driven along x", "must be fixed"}},
      {"ramp_time = \"50 us\"", "ramp_time = \"-1 us\"", {"groups[1].ramp_time"}},
      {"bonded_to = \"40 mm\"", "bonded_to = \"60 mm\"", {"strain gauge", "sheet must cover"}},
      // Reversed against the pull: the loaded end was taken at the far end, and it ran.
      {"bonded_from = 0\nbonded_to = \"40 mm\"", "bonded_from = \"40 mm\"\nbonded_to = 0",
       {"pullout.bonded_to", "the loaded end", "swap"}},
  };
  check_edits_refused(d.dir, slurp(kPull), edits);
}
