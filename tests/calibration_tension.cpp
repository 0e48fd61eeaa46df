// `mesocrack calibrate` on bonded specimens in uniaxial tension (Tang ch. 7: the phases' micro-parameters from
// "virtual tensile tests on each component phase"), through the real command line on a small specimen of the
// shipped phase scenes' grains (scenes/tension_*_2d.toml: R_min 1 mm, R_max/R_min 1.2, porosity 0.16): 20 × 40 mm,
// about 180 discs, strained at 0.5 /s by its end layers, a second or less per run. The calibrated scene, run again,
// must give the targets within the tolerance asked for: it is the same deterministic run as the last iteration,
// so a calibration that stopped short of the targets, or wrote other values than it ran, fails here.
#include <string>
#include <tuple>
#include <vector>

#include "tests/common/cli_harness.hpp"
#include "tests/common/relative.hpp"

namespace {

const char* kHead = R"(title = "small bonded specimen in uniaxial tension"
dimension = 2
seed = 2
[[phases]]
name = "mortar"
density = "2400 kg/m3"
)";

const char* kSoftening = R"([[contacts]]
phase_a = "mortar"
model = "softening_bond"
modulus = "40 GPa"
kn_ks_ratio = 1.8
friction = 0.5
bond_normal_strength = "5 kN"
bond_normal_strength_std = "0.55 kN"
bond_shear_strength = "10 kN"
bond_shear_strength_std = "1.1 kN"
bond_fracture_energy = "30 N/m"
)";

const char* kParallel = R"([[contacts]]
phase_a = "mortar"
model = "parallel_bond"
modulus = "40 GPa"
kn_ks_ratio = 1.8
friction = 0.5
bond_modulus = "40 GPa"
bond_kn_ks_ratio = 1.8
bond_tensile_strength = "5 MPa"
bond_tensile_strength_std = "0.55 MPa"
bond_shear_strength = "10 MPa"
bond_shear_strength_std = "1.1 MPa"
)";

// The genesis of the shipped scenes on a smaller box (seed 2: seed 1's genesis ends off the settling stress at
// this size, which the packing refuses); supports: the discs centred within 3 mm of each end, moving apart at
// 10 mm/s each (0.5 /s) and free across; stopped once the stress has fallen to 0.15 f_t, past the 0.2 f_t that
// G_f is read to.
const char* kTest = R"([specimen]
kind = "packing"
lo = [0, 0]
hi = ["20 mm", "40 mm"]
radius_min = "1 mm"
radius_ratio = 1.2
porosity = 0.16
stress = "0.1 MPa"
modulus = "35 GPa"
floater_contacts = 3
[bonds]
gap_tolerance = 0.01
[[groups]]
name = "bottom"
box_lo = ["-1 mm", "-1 mm"]
box_hi = ["21 mm", "3 mm"]
fix = "y"
velocity = [0, "-10 mm/s"]
[[groups]]
name = "top"
box_lo = ["-1 mm", "37 mm"]
box_hi = ["21 mm", "41 mm"]
fix = "y"
velocity = [0, "10 mm/s"]
[physics]
local_damping = 0.7
[uniaxial]
loading = "tension"
supports = "bottom top"
axis = "y"
[run]
duration = "20 ms"
[[run.stop]]
quantity = "uniaxial.stress"
post_peak_fraction = 0.15
)";

std::string scene(const char* contacts) { return std::string(kHead) + contacts + kTest; }

// Calibrates tension.toml in `d` to `targets` (5 %, Tang's tolerance) and returns the uniaxial summary of the
// calibrated scene run again.
Json calibrated_run(const TempDir& d, const std::string& targets, const std::string& changed_key) {
  const Result r = mesocrack(
      {"calibrate", "tension.toml", "--target", targets, "-o", "calibrated.toml", "--max-iterations", "8"}, d.dir);
  MESSAGE(r.err);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  CHECK(contains(r.err, "converged after"));
  CHECK(contains(r.out, "contacts[0]." + changed_key + "="));
  CHECK(fs::exists(d / "calibrated_it1.h5"));
  const Result run = mesocrack({"run", "calibrated.toml", "-o", "check.h5"}, d.dir);
  REQUIRE_MESSAGE(run.code == 0, run.describe());
  return summary_of("check.h5", d.dir)["uniaxial"];
}

}  // namespace

// From the scene's softening bonds (E ≈ 27 GPa, f_t ≈ 1.6 MPa, G_f ≈ 25 N/m on this packing) to targets that
// move E_c, the bond strengths and the bonds' ductility (G_f) all three; ν is no target, k_n/k_s stays.
TEST_CASE("calibrate_tension_softening_bond_converges_on_E_ft_and_Gf" * doctest::test_suite("build_options")) {
  const TempDir d;
  write_file(d / "tension.toml", scene(kSoftening));
  const Json u = calibrated_run(d, "E=30GPa,ft=2MPa,Gf=40N/m", "bond_fracture_energy");
  CHECK(u["E"].number == mc::test::relative(30e9, 0.05));
  CHECK(u["f_t"].number == mc::test::relative(2e6, 0.05));
  CHECK(u["G_f"].number == mc::test::relative(40, 0.05));
}

// From the scene's parallel bonds (E ≈ 31 GPa, ν ≈ 0.12, f_t ≈ 1.9 MPa) to targets that move the moduli, the
// stiffness ratios and the bond strengths.
TEST_CASE("calibrate_tension_parallel_bond_converges_on_E_nu_and_ft") {
  const TempDir d;
  write_file(d / "tension.toml", scene(kParallel));
  const Json u = calibrated_run(d, "E=25GPa,nu=0.18,ft=2.5MPa", "bond_kn_ks_ratio");
  CHECK(u["E"].number == mc::test::relative(25e9, 0.05));
  CHECK(u["nu"].number == mc::test::relative(0.18, 0.05));
  CHECK(u["f_t"].number == mc::test::relative(2.5e6, 0.05));
}

// Targets a bonded scene's model and loading cannot use, or that need another with them, are refused before
// anything runs (exit 2), naming the target; so is a softening bond in compression.
TEST_CASE("calibrate_tension_refuses_targets_the_bond_model_cannot_reach") {
  const TempDir d;
  write_file(d / "softening.toml", scene(kSoftening));
  write_file(d / "parallel.toml", scene(kParallel));
  write_file(d / "softening_compression.toml",
             edit(scene(kSoftening), "loading = \"tension\"", "loading = \"compression\""));
  const fs::path compression = fs::path(MESOCRACK_SOURCE_DIR) / "tests" / "scenes" / "uniaxial_2d_small.toml";
  const std::vector<std::tuple<std::string, std::string, std::string>> bad = {
      {"softening.toml", "ucs=5MPa", "--target ucs"},
      {"softening.toml", "E=30GPa,fc=40MPa", "--target fc"},
      {"softening.toml", "E=30GPa,Gf=40N/m", "ft with Gf"},
      {"softening.toml", "nu=0.2,ft=2MPa", "E with nu"},
      {"softening.toml", "Gf=-1N/m,ft=2MPa", "Gf"},
      {"parallel.toml", "ft=2MPa,Gf=40N/m", "--target Gf"},
      {"parallel.toml", "ucs=20MPa", "--target ucs"},
      {compression.string(), "E=25GPa,nu=0.2,Gf=40N/m", "--target Gf"},
      {compression.string(), "ft=2MPa", "--target ft"},
      {"softening_compression.toml", "ft=2MPa", "loading = \"tension\""}};
  for (const auto& [file, target, named] : bad) {
    const Result r = mesocrack({"calibrate", file, "--target", target, "-o", "c.toml"}, d.dir);
    CHECK_MESSAGE(r.code == 2, file, " ", target, ": ", r.describe());
    CHECK_MESSAGE(contains(r.err, named), file, " ", target, ": ", r.err);
    CHECK(!fs::exists(d / "c.toml"));
    CHECK(!fs::exists(d / "c_it1.h5"));
  }
}

// A target no bonded packing gives (E = 1e20 Pa, 3·10⁹ times the scene's moduli): its next run's steps would be
// √(3·10⁹) ≈ 5·10⁴ times as many (the critical step falls as 1/√k); it ran for hours, unbounded by --max-iterations.
// It stops after its first run, not converged (exit 5), saying what the next would cost; so does the CPM's.
TEST_CASE("calibrate_stops_with_exit_5_when_a_target_would_make_its_next_run_beyond_bound") {
  const TempDir d;
  write_file(d / "parallel.toml", scene(kParallel));
  const fs::path cpm = kScenes / "cpm_uniax_tension.toml";
  for (const std::string file : {std::string("parallel.toml"), cpm.string()}) {
    const Result r = mesocrack({"calibrate", file, "--target", "E=1e20Pa", "-o", "c.toml"}, d.dir);
    CHECK_MESSAGE(r.code == 5, file, ": ", r.describe());
    CHECK_MESSAGE(contains(r.err, "the next elastic run would take about"), file, ": ", r.err);
    CHECK_MESSAGE(contains(r.err, "NOT converged after 1 iterations"), file, ": ", r.err);
    CHECK_MESSAGE(r.seconds < 60, file, ": ", r.seconds, " s");
  }
}

// What the phase scenes' headers say their own calibrate command does on their values: at once (an elastic and a
// full run) for the softening mortar and the ITZ, in three runs for the brittle mortar and the aggregate (their
// headers say why), in its one elastic run for the FRP sheet (elastic only). A claim in a header is kept true by
// running it.
TEST_CASE("calibrate_on_the_phase_scenes_own_values_converges_in_the_runs_their_headers_say") {
  const TempDir d;
  struct Phase {
    std::string scene, targets;
    int iterations;
  };
  const std::vector<Phase> phases = {{"tension_itz_2d.toml", "E=25GPa,ft=1.1MPa,Gf=18N/m", 2},
                                     {"tension_mortar_softening_2d.toml", "E=35GPa,nu=0.16,ft=3.2MPa,Gf=170.4N/m", 2},
                                     {"tension_mortar_brittle_2d.toml", "E=35GPa,nu=0.16,ft=3.2MPa", 3},
                                     {"tension_aggregate_2d.toml", "E=70GPa,nu=0.22,ft=9.6MPa", 3},
                                     {"pull_frp_tension_2d.toml", "E=195.2GPa", 1}};
  for (const auto& [scene, targets, iterations] : phases) {
    const Result r =
        mesocrack({"calibrate", (kScenes / scene).string(), "--target", targets, "-o", "c.toml", "--threads", "1"},
                  d.dir);
    CHECK_MESSAGE(r.code == 0, scene, ": ", r.describe());
    CHECK_MESSAGE(contains(r.err, "converged after " + std::to_string(iterations) + " iterations"), scene, ": ", r.err);
  }
}
