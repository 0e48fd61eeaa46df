// Runs of bonded specimens through the real `mesocrack` command: the crack log end to end and across a
// resume, `generate` (genesis packing with aggregates) feeding an other scene, and the uniaxial compression
// analysis of Tang §5.2.
#include <cmath>
#include <string>

#include "tests/common/cli_harness.hpp"
#include "tests/common/relative.hpp"

// The bonded bar of scenes/lattice_tension_2d.toml pulled until it breaks: every broken bond is in /cracks (one
// row each, the counts equal to the histories', positions inside the bar, normals of unit length), and a run
// stopped while the crack runs and resumed writes the same crack log, bit for bit, as one never stopped.
TEST_CASE("crack_log_of_a_bonded_bar_pulled_apart_is_complete_and_survives_resume") {
  const TempDir d;
  const std::string scene = (kScenes / "lattice_tension_2d.toml").string();
  const Result whole = mesocrack({"run", scene, "-o", "whole.h5", "--threads", "2"}, d.dir);
  REQUIRE_MESSAGE(whole.code == 0, whole.describe());
  {
    const mc::H5File f((d / "whole.h5").string(), mc::H5File::Mode::ReadOnly);
    CHECK(f.attr_string("/", "status") == "stopped");  // by the post-peak condition: the bar broke
    const auto mode = f.read_ints("/cracks/mode"), kind = f.read_ints("/cracks/kind"),
               step = f.read_ints("/cracks/step");
    const auto tensile = f.read_doubles("/history/cracks.tensile").back(),
               shear = f.read_doubles("/history/cracks.shear").back();
    REQUIRE(mode.size() > 50);
    CHECK(static_cast<double>(std::count(mode.begin(), mode.end(), 1)) == tensile);
    CHECK(static_cast<double>(std::count(mode.begin(), mode.end(), 2)) == shear);
    CHECK(std::count(kind.begin(), kind.end(), 0) == static_cast<long>(mode.size()));  // parallel bonds only break
    CHECK(std::is_sorted(step.begin(), step.end()));
    const double bonds0 = f.read_doubles("/history/bonds.intact").front(),
                 bonds1 = f.read_doubles("/history/bonds.intact").back();
    CHECK(bonds0 - bonds1 == tensile + shear);
    std::vector<hsize_t> dims;
    const auto x = f.read_doubles("/cracks/position", &dims), n = f.read_doubles("/cracks/normal");
    REQUIRE(dims == std::vector<hsize_t>{mode.size(), 2});
    for (std::size_t k = 0; k < mode.size(); ++k) {
      CHECK(x[2 * k] > 0);
      CHECK(x[2 * k] < 20e-3);
      CHECK(std::hypot(n[2 * k], n[2 * k + 1]) == mc::test::relative(1.0, 1e-12));
    }
  }
  // Stopped at step 12000 (a history row and a frame fall there, so the first half adds no extra final row),
  // when the first bonds have broken and the crack is about to run; then resumed.
  const Result first = mesocrack({"run", scene, "-o", "halves.h5", "--set", "run.steps=12000"}, d.dir);
  REQUIRE_MESSAGE(first.code == 0, first.describe());
  {
    const mc::H5File f((d / "halves.h5").string(), mc::H5File::Mode::ReadOnly);
    const auto rows = f.rows("/cracks/mode");
    CHECK(rows > 0);
    CHECK(rows < mc::H5File((d / "whole.h5").string(), mc::H5File::Mode::ReadOnly).rows("/cracks/mode") / 2);
  }
  const Result rest = mesocrack({"run", scene, "--resume", "halves.h5"}, d.dir);
  REQUIRE_MESSAGE(rest.code == 0, rest.describe());
  check_same_run(d / "whole.h5", d / "halves.h5");
}

// `generate` builds a scene's specimen without running it: here a PFC genesis packing with aggregates laid over
// it. The file carries what the generation measured (porosity, stress, aggregate fractions) and the aggregate
// outlines, is drawn by report, and an other scene loads it (kind = "output") and runs on it.
TEST_CASE("generate_writes_a_mesostructure_packing_that_a_scene_loads") {
  const TempDir d;
  write_file(d / "gen.toml",
             "title = \"genesis\"\ndimension = 2\nseed = 3\n"
             "[[phases]]\nname = \"mortar\"\ndensity = \"2200 kg/m3\"\n"
             "[[phases]]\nname = \"aggregate\"\ndensity = \"2700 kg/m3\"\n"
             "[[contacts]]\nphase_a = \"mortar\"\nphase_b = \"mortar\"\nmodel = \"linear\"\nmodulus = \"20 GPa\"\n"
             "[[contacts]]\nphase_a = \"aggregate\"\nmodel = \"linear\"\nmodulus = \"20 GPa\"\n"
             "[[contacts]]\nphase_a = \"mortar\"\nphase_b = \"aggregate\"\nmodel = \"linear\"\nmodulus = \"20 GPa\"\n"
             "[specimen]\nkind = \"packing\"\nlo = [0, 0]\nhi = [\"20 mm\", \"20 mm\"]\nradius_min = \"0.3 mm\"\n"
             "modulus = \"20 GPa\"\nphase = \"mortar\"\n"
             "[mesostructure]\nfraction = 0.3\ngrading = \"ranges\"\nmortar_phase = \"mortar\"\naggregate_phase = "
             "\"aggregate\"\n"
             "[[mesostructure.ranges]]\nlo = \"3 mm\"\nhi = \"6 mm\"\nshare = 1\n"
             "[run]\nsteps = 1\n");
  const Result g = mesocrack({"generate", "gen.toml", "-o", "specimen.h5"}, d.dir);
  REQUIRE_MESSAGE(g.code == 0, g.describe());
  CHECK(contains(g.out, "specimen.png"));  // the picture, drawn by report
  CHECK(fs::exists(d / "specimen_specimen.png"));
  {
    const mc::H5File f((d / "specimen.h5").string(), mc::H5File::Mode::ReadOnly);
    CHECK(f.attr_string("/", "status") == "finished");
    CHECK(f.attr_double("/specimen", "packing_porosity_grown") == mc::test::relative(0.16, 1e-9));
    CHECK(f.attr_double("/specimen", "packing_stress_final") == mc::test::relative(1e5, 0.02));
    CHECK(f.attr_double("/specimen", "aggregate_fraction_achieved") == mc::test::relative(0.3, 1e-9));
    // Particles take the aggregate phase by their centres: their share tends to the aggregate fraction
    // (Tang Fig. 4.14); at L/R ≈ 50 it is within a few percent.
    CHECK(f.attr_double("/specimen", "aggregate_particle_fraction") == mc::test::relative(0.3, 0.15));
    CHECK(f.rows("/specimen/outline_start") > 3);
    const auto phase = f.read_ints("/specimen/phase");
    CHECK(std::count(phase.begin(), phase.end(), 1) > 0);
  }
  write_file(
      d / "use.toml",
      "title = \"use\"\ndimension = 2\n"
      "[[phases]]\nname = \"mortar\"\ndensity = \"2200 kg/m3\"\n"
      "[[phases]]\nname = \"aggregate\"\ndensity = \"2700 kg/m3\"\n"
      "[[contacts]]\nphase_a = \"mortar\"\nmodel = \"parallel_bond\"\nmodulus = \"20 GPa\"\nbond_modulus = \"20 GPa\"\n"
      "bond_tensile_strength = \"8 MPa\"\nbond_shear_strength = \"16 MPa\"\n"
      "[[contacts]]\nphase_a = \"aggregate\"\nmodel = \"parallel_bond\"\nmodulus = \"40 GPa\"\nbond_modulus = \"40 "
      "GPa\"\n"
      "bond_tensile_strength = \"30 MPa\"\nbond_shear_strength = \"60 MPa\"\n"
      "[[contacts]]\nphase_a = \"mortar\"\nphase_b = \"aggregate\"\nmodel = \"parallel_bond\"\nmodulus = \"15 GPa\"\n"
      "bond_modulus = \"15 GPa\"\nbond_tensile_strength = \"4 MPa\"\nbond_shear_strength = \"8 MPa\"\n"
      "[bonds]\ngap_tolerance = 0.01\n"
      "[specimen]\nkind = \"output\"\nfile = \"specimen.h5\"\n"
      "[run]\nsteps = 50\n");
  const Result r = mesocrack({"run", "use.toml", "-o", "run.h5"}, d.dir);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  const mc::H5File f((d / "run.h5").string(), mc::H5File::Mode::ReadOnly);
  // Bonds of all three phase pairs (mortar, aggregate, ITZ) are installed and counted.
  for (const char* pair : {"bonds_mortar-mortar", "bonds_aggregate-aggregate", "bonds_mortar-aggregate"})
    CHECK_MESSAGE(f.attr_double("/specimen", pair) > 0, pair);
}

// The uniaxial compression scene of Tang §5.2 (scenes/uniaxial_2d.toml) on a 25 mm × 50 mm specimen (about
// 900 discs, L/R ≈ 30): E scales linearly with the contact and bond modulus (Tang 6.1, E = E_c Φ_E(k_n/k_s, …)),
// and ν rises with k_n/k_s (6.2). Each run is a few seconds.
TEST_CASE("uniaxial_compression_E_scales_with_E_c_and_nu_rises_with_kn_over_ks") {
  const TempDir d;
  // One packing for all runs (a genesis is chaotic: two of them differ like two random specimens, by several %
  // in E at this size), generated once and loaded by a copy of the scene.
  const std::string scene = (kScenes / "uniaxial_2d.toml").string();
  const Result g =
      mesocrack({"generate", scene, "-o", "packing.h5", "--set", "specimen.hi=[\"25 mm\", \"50 mm\"]"}, d.dir);
  REQUIRE_MESSAGE(g.code == 0, g.describe());
  std::string text = slurp(scene);
  const auto from = text.find("[specimen]"), to = text.find("[bonds]");
  REQUIRE(from != std::string::npos);
  REQUIRE(to != std::string::npos);
  text.replace(from, to - from, "[specimen]\nkind = \"output\"\nfile = \"packing.h5\"\n\n");
  write_file(d / "uniaxial.toml", text);
  // A specimen of half the moduli is the same problem in other units when everything with the unit of stress
  // (platen stiffness 2tE_c, bond strengths) is halved too and time runs slower by √2 (the wave speed √(E/ρ)),
  // i.e. the platens move √2 slower (Tang 5.2–5.4: E = E_c Φ_E, σ_c = σ_b Φ_c(E_c/σ_b, …)).
  auto run = [&](const std::string& name, double scale, const std::string& ratio) {
    auto num = [](double x) { return std::to_string(x); };
    const std::string speed = num(10e-3 * std::sqrt(scale)), ramp = num(2e-3 / std::sqrt(scale));
    const Result r = mesocrack({"run",   "uniaxial.toml",
                                "-o",    name,
                                "--set", "contacts[0].modulus=" + num(20e9 * scale),
                                "--set", "contacts[0].bond_modulus=" + num(20e9 * scale),
                                "--set", "contacts[0].bond_tensile_strength=" + num(18e6 * scale),
                                "--set", "contacts[0].bond_tensile_strength_std=" + num(2e6 * scale),
                                "--set", "contacts[0].bond_shear_strength=" + num(36e6 * scale),
                                "--set", "contacts[0].bond_shear_strength_std=" + num(4e6 * scale),
                                "--set", "contacts[0].kn_ks_ratio=" + ratio,
                                "--set", "contacts[0].bond_kn_ks_ratio=" + ratio,
                                "--set", "walls[0].kn=" + num(4e10 * scale),
                                "--set", "walls[1].kn=" + num(4e10 * scale),
                                "--set", "walls[0].ramp_time=" + ramp,
                                "--set", "walls[1].ramp_time=" + ramp,
                                "--set", "run.stop[0].after_time=" + ramp,
                                "--set", "walls[0].b=[\"45 mm\", 0]",
                                "--set", "walls[0].inside=[\"12.5 mm\", \"25 mm\"]",
                                "--set", "walls[0].area=25 mm",
                                "--set", "walls[1].a=[\"-20 mm\", \"50 mm\"]",
                                "--set", "walls[1].b=[\"45 mm\", \"50 mm\"]",
                                "--set", "walls[1].inside=[\"12.5 mm\", \"25 mm\"]",
                                "--set", "walls[1].area=25 mm",
                                "--set", "measure[0].centre=[\"12.5 mm\", \"25 mm\"]",
                                "--set", "measure[0].radius=10 mm",
                                "--set", "walls[0].velocity=[0, " + speed + "]",
                                "--set", "walls[1].velocity=[0, -" + speed + "]"},
                               d.dir);
    REQUIRE_MESSAGE(r.code == 0, r.describe());
    const Json j = summary_of(name, d.dir);
    REQUIRE(j["uniaxial"].kind == Json::Kind::Object);
    MESSAGE(name, ": E = ", j["uniaxial"]["E"].number, " Pa, nu = ", j["uniaxial"]["nu"].number,
            ", UCS = ", j["uniaxial"]["ucs"].number,
            " Pa, crack initiation / UCS = ", j["uniaxial"]["crack_initiation_ratio"].number);
    CHECK(j["status"].text == "stopped");  // past the peak
    return j["uniaxial"];
  };
  const Json a = run("e20.h5", 1.0, "2"), b = run("e10.h5", 0.5, "2");
  // The same problem in other units, but for the locked-in genesis overlaps (σ0/E_c ≈ 5e-6 of strain against
  // the ≈ 1e-4 of the 25–50 % window): E halves to 1 %, ν stays to 1 %. UCS, past many breaks, to 5 %.
  CHECK(a["E"].number / b["E"].number == mc::test::relative(2.0, 0.01));
  CHECK(a["nu"].number == mc::test::relative(b["nu"].number, 0.01));
  CHECK(a["ucs"].number / b["ucs"].number == mc::test::relative(2.0, 0.05));
  const Json c = run("r1.h5", 1.0, "1"), e = run("r3.h5", 1.0, "3");
  CHECK(c["nu"].number < a["nu"].number);
  CHECK(a["nu"].number < e["nu"].number);
  CHECK(c["E"].number > e["E"].number);  // softer shear springs, softer specimen
}
