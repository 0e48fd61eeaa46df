// Rigid-cell scenes through the real `mesocrack` command: the family runs as a System under the same runner as the
// explicit engine (histories, summary, crack log, --resume), and its bad input is refused with exit 2 or 4.
#include "engine/crack.hpp"
#include "tests/common/cli_harness.hpp"
#include "tests/common/relative.hpp"

namespace {

double final_value(const mc::H5File& f, const std::string& series) {
  return f.read_doubles("/history/" + series).back();
}

}  // namespace

TEST_CASE("rigid_cell_box_between_plates_answers_with_the_facet_modulus_when_alpha_is_one") {
  const TempDir d;
  const Result r = mesocrack({"run", (kScenes / "rigid_cell_tension_2d.toml").string(), "-o", "box.h5"}, d.dir);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  const mc::H5File f((d / "box.h5").string(), mc::H5File::Mode::ReadOnly);
  const double force = final_value(f, "group.top.reaction_y"), travel = final_value(f, "group.top.disp_y");
  const double width = 0.04, height = 0.2, E0 = 30e9;
  const double E = force / width / (travel / height);  // 2D: unit thickness
  // With α = 1 a uniform strain is in equilibrium on any tessellation, so E = E₀ (Květoň (3.8), 2D: 2E₀(1 + α)/
  // (3 + α)). The rigid plates hold the cells whose nodes lie 1–2 mm inside each end, and those cells reach about
  // l_min/2 further in: the gauge length is 2-3 % shorter than the box, and the measured modulus as much higher.
  CHECK(E / E0 > 1.0);
  CHECK(E / E0 < 1.035);
  // Elastic: the plates' work is the energy the facets store, to round-off.
  CHECK(final_value(f, "energy.boundary_work") == mc::test::relative(final_value(f, "energy.strain"), 1e-9));
  CHECK(final_value(f, "energy.boundary_work") == mc::test::relative(0.5 * force * travel, 1e-9));
}

// The mean strain over a box ([rigid_cell.strain], the least-squares gradient of its nodes' displacements) read
// as an extensometer: with α = 1 the cells between the plates take a uniform strain (E = E₀, ν = 0), so over the
// middle half the axial stress across a section over the axial strain is E₀, and the lateral and shear strains
// vanish. Not to round-off: the plates move their cells rigidly, which perturbs the uniform field near them. Measured
// 50 mm away: σ/ε within 1.7e-5 of E₀ (bound 1e-4); lateral and shear strains 1.8e-4 to 8.6e-4 of the axial one
// (2D and 3D; bound 2e-3), where a wrong gradient (a transposed or halved weight) would be off by order one.
TEST_CASE("rigid_cell_mean_strain_over_a_box_reads_the_uniform_strain_of_a_box_pulled_with_alpha_one") {
  const TempDir d;
  for (const int dim : {2, 3}) {
    CAPTURE(dim);
    std::string scene = slurp(kScenes / "rigid_cell_tension_2d.toml");
    const std::string name = "box" + std::to_string(dim);
    if (dim == 3)
      for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
               {"dimension = 2", "dimension = 3"},
               {"size = [\"40 mm\", \"200 mm\"]", "size = [\"40 mm\", \"200 mm\", \"20 mm\"]"},
               {"l_min = \"2 mm\"", "l_min = \"4 mm\""},
               {"box_lo = [0, 0]", "box_lo = [0, 0, 0]"},
               {"box_hi = [\"40 mm\", \"2 mm\"]", "box_hi = [\"40 mm\", \"4 mm\", \"20 mm\"]"},
               {"box_lo = [0, \"198 mm\"]", "box_lo = [0, \"196 mm\", 0]"},
               {"box_hi = [\"40 mm\", \"200 mm\"]", "box_hi = [\"40 mm\", \"200 mm\", \"20 mm\"]"},
               {"velocity = [0, \"1 mm/s\"]", "velocity = [0, \"1 mm/s\", 0]"}}) {
        REQUIRE_MESSAGE(scene.find(from) != std::string::npos, from);
        scene.replace(scene.find(from), from.size(), to);
      }
    scene += dim == 2 ? "[rigid_cell.strain]\nbox_lo = [0, \"50 mm\"]\nbox_hi = [\"40 mm\", \"150 mm\"]\n"
                      : "[rigid_cell.strain]\nbox_lo = [0, \"50 mm\", 0]\n"
                        "box_hi = [\"40 mm\", \"150 mm\", \"20 mm\"]\n";
    scene += "[rigid_cell.sections]\naxis = \"y\"\nat = [\"100 mm\"]\n";
    write_file(d / (name + ".toml"), scene);
    const Result r = mesocrack({"run", name + ".toml", "-o", name + ".h5"}, d.dir);
    REQUIRE_MESSAGE(r.code == 0, r.describe());
    const mc::H5File f((d / (name + ".h5")).string(), mc::H5File::Mode::ReadOnly);
    const double eyy = final_value(f, "strain.yy"), E0 = 30e9;
    CHECK(eyy > 0);
    CHECK(final_value(f, "section.y_100mm") / eyy == mc::test::relative(E0, 1e-4));
    CHECK(std::abs(final_value(f, "strain.xx") / eyy) < 2e-3);
    CHECK(std::abs(final_value(f, "strain.xy") / eyy) < 2e-3);
    if (dim == 3) {
      CHECK(std::abs(final_value(f, "strain.zz") / eyy) < 2e-3);
      CHECK(std::abs(final_value(f, "strain.yz") / eyy) < 2e-3);
    }
  }
  // A box that holds too few nodes is refused naming the table.
  std::string scene = slurp(kScenes / "rigid_cell_tension_2d.toml") +
                      "[rigid_cell.strain]\nbox_lo = [0, \"50 mm\"]\nbox_hi = [\"0.1 mm\", \"50.1 mm\"]\n";
  write_file(d / "tiny.toml", scene);
  const Result bad = mesocrack({"run", "tiny.toml", "-o", "tiny.h5"}, d.dir);
  CHECK_MESSAGE(bad.code == 2, bad.describe());
  CHECK_MESSAGE(contains(bad.err, "[rigid_cell.strain]"), bad.err);
}

TEST_CASE("rigid_cell_brazilian_disc_resumed_halfway_gives_the_same_bits") {
  const TempDir d;
  const std::string scene = (kScenes / "brazilian_2d.toml").string();
  // 160 load steps: the facets under the plates and at the centre have begun to damage (from step ~110).
  const Result whole = mesocrack({"run", scene, "-o", "whole.h5", "--set", "run.steps=160"}, d.dir);
  REQUIRE_MESSAGE(whole.code == 0, whole.describe());
  const Result first = mesocrack(
      {"run", scene, "-o", "parts.h5", "--set", "run.steps=120", "--set", "output.checkpoint_every=120"}, d.dir);
  REQUIRE_MESSAGE(first.code == 0, first.describe());
  const Result rest = mesocrack(
      {"run", scene, "--resume", "parts.h5", "--set", "run.steps=160", "--set", "output.checkpoint_every=120"}, d.dir);
  REQUIRE_MESSAGE(rest.code == 0, rest.describe());
  const mc::H5File f((d / "whole.h5").string(), mc::H5File::Mode::ReadOnly);
  REQUIRE(final_value(f, "facets.damaged") > 0);
  REQUIRE(f.exists("/cracks"));
  check_same_run(d / "whole.h5", d / "parts.h5");
}

TEST_CASE("rigid_cell_3d_brazilian_disc_splits_along_its_loaded_diameter_at_the_tensile_strength") {
  const TempDir d;
  // Květoň's thin concrete disc (Tab. 9.1: D 70, T 30 mm, f_t 2.64 MPa, l_min 7.5 mm), run to 70 % past its peak.
  const Result r = mesocrack({"run", (kScenes / "brazilian_concrete_thin.toml").string(), "-o", "disc.h5"}, d.dir);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  const mc::H5File f((d / "disc.h5").string(), mc::H5File::Mode::ReadOnly);
  const auto load = f.read_doubles("/history/group.bottom.reaction_y");
  const double peak = *std::max_element(load.begin(), load.end());
  const double D = 0.07, T = 0.03, ft = 2.64e6, pi = std::numbers::pi;
  // (9.2) with P₁ = P₂ = P: the splitting strength 2P/(πTD) is the facets' f_t, as in Květoň's fit (Tab. 9.2:
  // 8.71 kN, 2.64 MPa). This seed's peak is 8.77 kN; six seeds gave 8.39-11.32 kN (a 130-cell disc touches each
  // plate through one to three cells): 15 % is about the scatter of one realisation.
  CHECK(2 * peak / (pi * T * D) == mc::test::relative(ft, 0.15));
  // The split: in the middle of the disc (within 20 mm of its centre along the load), most facets that broke in
  // tension lie within one l_min of the loaded diameter; spread evenly, 15 mm of the 70 mm width would hold ~21 %
  // (six seeds: 41-74 %; this one 56 %).
  std::vector<hsize_t> dims;
  const auto kind = f.read_ints("/cracks/kind"), mode = f.read_ints("/cracks/mode");
  const auto position = f.read_doubles("/cracks/position", &dims);
  REQUIRE(dims.size() == 2);
  REQUIRE(dims[1] == 3);
  int central = 0, on_diameter = 0;
  for (std::size_t i = 0; i < kind.size(); ++i) {
    const double x = position[3 * i], y = position[3 * i + 1];
    if (kind[i] != static_cast<int>(mc::CrackKind::Break) || mode[i] != static_cast<int>(mc::CrackMode::Tensile) ||
        std::abs(y - D / 2) > 0.02)
      continue;
    ++central;
    on_diameter += std::abs(x - D / 2) < 0.0075;
  }
  CHECK(central > 50);
  CHECK(on_diameter > 0.45 * central);
}

TEST_CASE("rigid_cell_bad_input_names_the_plate_cell_or_step") {
  const TempDir d;
  const std::string base = slurp(kScenes / "brazilian_2d.toml");
  REQUIRE(!base.empty());
  check_edits_refused(
      d.dir, base,
      {{"box_lo = [\"31 mm\", 0]\nbox_hi = [\"39 mm\", \"4 mm\"]",
        "box_lo = [\"31 mm\", 0]\nbox_hi = [\"39 mm\", \"1 mm\"]",
        {"plate 'bottom'", "no cell's node lies in its box", "widen the box"}},
       {"fix = \"all\"\n\n[[groups]]\nname = \"top\"\nbox_lo = [\"31 mm\", \"66 mm\"]\nbox_hi = [\"39 mm\", "
        "\"70 mm\"]\nfix = \"all\"\nvelocity = [0, \"-1 mm/s\"]",
        "\n[[groups]]\nname = \"top\"\nbox_lo = [\"31 mm\", \"66 mm\"]\nbox_hi = [\"39 mm\", \"70 mm\"]",
        {"cell 0", "not held", "unsupported"}},
       {"box_lo = [\"31 mm\", \"66 mm\"]", "box_lo = [\"31 mm\", \"2 mm\"]", {"plates 'bottom' and 'top'", "cell"}},
       {"shape = \"disc\"",
        "shape = \"polygon\"\nvertices_x = [0, 0, \"70 mm\"]\nvertices_y = [0, \"70 mm\", 0]",
        {"vertices_y", "counter-clockwise"}},
       // A corner given twice (refused as "cell 0 is unbounded"), and an outline through itself (it ran, its cells
       // covering an area the outline does not have).
       {"shape = \"disc\"",
        "shape = \"polygon\"\nvertices_x = [0, \"70 mm\", \"70 mm\", \"70 mm\", 0]\n"
        "vertices_y = [0, 0, \"70 mm\", \"70 mm\", \"70 mm\"]",
        {"specimen.vertices_x", "vertices 2 and 3", "same point"}},
       {"shape = \"disc\"",
        "shape = \"polygon\"\nvertices_x = [0, \"70 mm\", \"70 mm\", \"40 mm\", \"40 mm\", 0]\n"
        "vertices_y = [0, 0, \"70 mm\", \"70 mm\", \"-10 mm\", \"70 mm\"]",
        {"specimen.vertices_x", "edge 0-1 meets edge 3-4", "crosses itself"}},
       {"[timestep]",
        "[[walls]]\nshape = \"plane\"\npoint = [0, 0]\nnormal = [0, 1]\nkn = 1e9\n\n[timestep]",
        {"'walls'", "rigid-cell scene"}},
       {"E0 = \"40 GPa\"\nalpha = 0.237",
        "modulus = \"30 GPa\"\npoisson_ratio = 0.4",
        {"modulus and poisson_ratio", "0.4"}},
       {"fracture_energy = \"40.66 N/m\"", "fracture_energy = \"0.1 N/m\"", {"facet", "snap"}},
       // A slit 1 mm wide among cells 2.5 mm apart: the cells on its two sides would join across it.
       {"shape = \"disc\"\ncentre = [\"35 mm\", \"35 mm\"]\nradius = \"35 mm\"",
        "shape = \"polygon\"\nvertices_x = [0, \"34.5 mm\", \"34.5 mm\", \"35.5 mm\", \"35.5 mm\", \"70 mm\", "
        "\"70 mm\", 0]\nvertices_y = [0, 0, \"40 mm\", \"40 mm\", 0, 0, \"70 mm\", \"70 mm\"]",
        {"across a gap of the outline", "notch or slit", "at least 2 l wide"}},
       // Coarsening: its box without l_max, an l_max finer than l_min, a box inside out, nodes given.
       {"l_min = \"2.5 mm\"", "l_min = \"2.5 mm\"\nfine_lo = [0, 0]",
        {"specimen.fine_lo", "needs l_max"}},
       {"l_min = \"2.5 mm\"", "l_min = \"2.5 mm\"\nl_max = \"2 mm\"\nfine_lo = [0, 0]\nfine_hi = [1, 1]",
        {"specimen.l_max", "at least l_min"}},
       {"l_min = \"2.5 mm\"",
        "l_min = \"2.5 mm\"\nl_max = \"5 mm\"\nfine_lo = [\"30 mm\", 0]\nfine_hi = [\"40 mm\", 0]",
        {"specimen.fine_hi", "component 1"}},
       {"l_min = \"2.5 mm\"",
        "l_min = \"2.5 mm\"\nl_max = \"5 mm\"\nfine_lo = [0, 0]\nfine_hi = [1, 1]\nnodes = [0, 0, 1, 1]",
        {"specimen.l_max", "nodes are given"}}});
}

TEST_CASE("rigid_cell_secant_iteration_that_cannot_converge_stops_with_exit_4_naming_the_step") {
  const TempDir d;
  // An out-of-balance tolerance of 1e-300 that round-off never meets: the first step cannot converge, however often
  // it is cut.
  const Result r = mesocrack({"run", (kScenes / "brazilian_2d.toml").string(), "-o", "out.h5", "--set",
                              "rigid_cell.force_tolerance=1e-300", "--set", "rigid_cell.max_iterations=2"},
                             d.dir);
  CHECK_MESSAGE(r.code == 4, r.describe());
  CHECK_MESSAGE(contains(r.err, "step 1 "), r.err);
  CHECK_MESSAGE(contains(r.err, "did not converge"), r.err);
  CHECK_MESSAGE(contains(r.err, "out-of-balance ratio"), r.err);
  // The run up to the failing step is kept, finite, with its status.
  const mc::H5File f((d / "out.h5").string(), mc::H5File::Mode::ReadOnly);
  CHECK(f.attr_string("/", "status") == "unstable");
  for (const double v : f.read_doubles("/history/group.bottom.reaction_y")) CHECK(std::isfinite(v));
}

TEST_CASE("rigid_cell_specimen_free_to_slide_stops_with_exit_4_at_a_singular_stiffness") {
  const TempDir d;
  // Both plates held along y only: the disc may slide along x, its stiffness is singular.
  const std::string base = slurp(kScenes / "brazilian_2d.toml");
  write_file(d / "scene.toml", edit(edit(base, "box_hi = [\"39 mm\", \"4 mm\"]\nfix = \"all\"",
                                         "box_hi = [\"39 mm\", \"4 mm\"]\nfix = \"y\""),
                                    "\"70 mm\"]\nfix = \"all\"", "\"70 mm\"]\nfix = \"y\""));
  const Result r = mesocrack({"run", "scene.toml", "-o", "out.h5"}, d.dir);
  CHECK_MESSAGE(r.code == 4, r.describe());
  CHECK_MESSAGE(contains(r.err, "step 1 "), r.err);
  CHECK_MESSAGE(contains(r.err, "singular"), r.err);
}

TEST_CASE("rigid_cell_misspelt_required_key_is_named_as_the_misspelling_not_as_the_key_missing") {
  // Each misspelling was reported as "missing key 'correlation_length'", the key the user had written.
  const TempDir d;
  check_edits_refused(d.dir, slurp(kScenes / "rigid_cell_tension_field_2d.toml"),
                      {{"correlation_length = ", "corelation_length = ",
                        {"rigid_cell.random_field.corelation_length", "misspelling of 'correlation_length'"}},
                       {"l_min = ", "l_mn = ", {"specimen.l_mn", "misspelling of 'l_min'"}}});
  check_edits_refused(d.dir, slurp(kScenes / "stress_wave_bar_2d.toml"),
                      {{"pressure = ", "presure = ", {"rigid_cell.stress_wave.presure", "misspelling of 'pressure'"}}});
}
