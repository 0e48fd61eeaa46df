// Bad input through the real `mesocrack` command (MESOCRACK_CLI): refused with one line and exit 2 (3 for files
// that cannot be read or written) before any output exists, the message naming the file, the key, the value and
// what is allowed. Each test works in its own fresh temp folder; the command runs as a child process.
#include "tests/common/cli_harness.hpp"

// A scene to spoil: collision_3d.toml's text, written as scene.toml in a fresh folder by scene().
struct BadInput {
  const TempDir d;
  const std::string base = slurp(kScenes / "collision_3d.toml");
  const std::vector<std::string> run{"run", "scene.toml"};
  void scene(const std::string& text) const { write_file(d / "scene.toml", text); }
};

TEST_CASE_FIXTURE(BadInput, "bad_scene_keys_give_message_and_exit_2") {
  REQUIRE(!base.empty());

  SUBCASE("missing key") {
    scene(edit(base, "density = \"2600 kg/m3\"\n", ""));
    check_refused(d.dir, run, 2, {"scene.toml: ", "missing key 'phases[0].density'", "kg/m3"});
  }
  SUBCASE("a bond strength drawn from two distributions at once") {
    const std::string lattice = (kScenes / "lattice_tension_2d.toml").string();
    check_refused(d.dir, {"run", lattice, "--set", "contacts[0].bond_tensile_strength_weibull_shape=5"}, 2,
                  {"lattice_tension_2d.toml: ", "'contacts[0].bond_tensile_strength_weibull_shape' (from --set) = 5",
                   "bond_tensile_strength_std", "not both"});
  }
  SUBCASE("a 2D packing asked for a cylinder, a 3D one's shape") {
    const std::string disc = (kScenes / "brazilian_meso_explicit_2d.toml").string();
    check_refused(d.dir, {"run", disc, "--set", "specimen.shape=cylinder"}, 2,
                  {"brazilian_meso_explicit_2d.toml: ", "'specimen.shape' (from --set) = \"cylinder\"", "box, disc"});
  }
  SUBCASE("missing table") {
    scene(edit(base, "[run]\nduration = \"0.3 ms\"\n", ""));
    check_refused(d.dir, run, 2, {"scene.toml: ", "missing key 'run' (a table)"});
  }
  SUBCASE("unknown key") {
    scene(edit(base, "density = \"2600 kg/m3\"\n", "density = \"2600 kg/m3\"\ndesnity = 2600\n"));
    check_refused(d.dir, run, 2, {"scene.toml: ", "unknown key 'phases[0].desnity'", "allowed here: name, density"});
  }
  SUBCASE("unknown table") {
    scene(base + "\n[physcs]\ngravity = [0, 0, -9.81]\n");
    check_refused(d.dir, run, 2, {"scene.toml: ", "unknown key 'physcs'", "a misspelling of 'physics'"});
  }
  SUBCASE("wrong type") {
    scene(edit(base, "x = [\"2.01 mm\", 0, 0]\nradius = \"1 mm\"", "x = [\"2.01 mm\", 0, 0]\nradius = true"));
    check_refused(d.dir, run, 2,
                  {"scene.toml: ", "key 'specimen.particles[1].radius' = true", "expected a number in m"});
  }
  SUBCASE("wrong vector length") {
    scene(edit(base, "x = [\"2.01 mm\", 0, 0]", "x = [\"2.01 mm\", 0]"));
    check_refused(d.dir, run, 2,
                  {"scene.toml: ", "key 'specimen.particles[1].x' = [\"2.01 mm\", 0]", "3 numbers in m, got 2"});
  }
  SUBCASE("out-of-range value") {
    scene(edit(base, "safety = 0.05", "safety = 1.5"));
    check_refused(d.dir, run, 2, {"scene.toml: ", "key 'timestep.safety' = 1.5", "out of range", "0 < value <= 1"});
  }
  SUBCASE("out-of-range quantity with a unit") {
    scene(edit(base, "density = \"2600 kg/m3\"", "density = \"-2.6 g/cm3\""));
    check_refused(d.dir, run, 2,
                  {"scene.toml: ", "key 'phases[0].density' = \"-2.6 g/cm3\"", "out of range", "value > 0"});
  }
  SUBCASE("bad unit") {
    scene(edit(base, "x = [\"2.01 mm\", 0, 0]\nradius = \"1 mm\"", "x = [\"2.01 mm\", 0, 0]\nradius = \"1 kg\""));
    check_refused(d.dir, run, 2, {"scene.toml: ", "key 'specimen.particles[1].radius' = \"1 kg\"", "unit 'kg'", "mm"});
  }
  SUBCASE("unknown choice") {
    scene(edit(base, "model = \"linear\"", "model = \"lineer\""));
    check_refused(d.dir, run, 2, {"scene.toml: ", "key 'contacts[0].model' = \"lineer\"", "linear", "hertz_mindlin"});
  }
  SUBCASE("history named by a summary that the scene does not record") {
    scene(edit(base, "of = \"approach_speed\"", "of = \"approach_sped\""));
    check_refused(d.dir, run, 2, {"scene.toml: ", "key 'summary[2].of' = \"approach_sped\"", "overlap"});
  }
  SUBCASE("probe naming a particle that does not exist (checked when the world is built)") {
    scene(edit(base, "kind = \"overlap\"\nparticles = [0, 1]", "kind = \"overlap\"\nparticles = [0, 7]"));
    check_refused(d.dir, run, 2, {"scene.toml", "probe 'overlap'", "particle 7", "2 particles"});
  }
}

TEST_CASE_FIXTURE(BadInput, "unreadable_or_unwritable_files_give_message_and_exit_2_or_3") {
  SUBCASE("unreadable scene file") {
    // A file error (exit 3) for every command that reads a scene, naming the path and the system's reason.
    fs::create_directory(d / "folder.toml");
    for (const std::vector<std::string>& command :
         {std::vector<std::string>{"run"}, {"run", "--realizations", "2"}, {"generate"}}) {
      CAPTURE(command.front());
      auto absent = command, folder = command;
      absent.insert(absent.begin() + 1, "absent.toml");
      folder.insert(folder.begin() + 1, "folder.toml");
      check_refused(d.dir, absent, 3, {"cannot read scene file 'absent.toml'", "No such file or directory"});
      check_refused(d.dir, folder, 3, {"cannot read scene file 'folder.toml'", "Is a directory"});
    }
    check_refused(d.dir, {"calibrate", "absent.toml", "--target", "ucs=40MPa"}, 3,
                  {"cannot read scene file 'absent.toml'", "No such file or directory"}, "calibrated.toml");
    fs::remove(d / "folder.toml");
  }
  SUBCASE("unreadable sphere-list file named by the scene") {
    const std::string sl =
        "dimension = 3\n[[phases]]\nname = \"grain\"\ndensity = 2600\n[[contacts]]\nphase_a = \"grain\"\n"
        "model = \"linear\"\nmodulus = \"50 MPa\"\n[specimen]\nkind = \"sphere_list\"\nfile = \"grains.spheres\"\n"
        "[run]\nsteps = 10\n";
    scene(sl);
    // A file error (IoError): exit 3; the message names the scene, its key and the resolved path.
    check_refused(
        d.dir, run, 3,
        {"scene.toml: ", "'specimen.file'", "cannot read particle list 'grains.spheres'", "No such file or directory"});
    // A readable list with a bad line is bad input: exit 2, naming the list, the line and the value.
    write_file(d / "grains.spheres", "# id x y z r tag\n0 0 0 0 0.001 0\n1 0.003 0 0 -1 0\n");
    check_refused(d.dir, run, 2, {"grains.spheres:3", "'-1'"});
  }
  SUBCASE("TOML syntax error") {
    const std::string bad = edit(base, "dimension = 3", "dimension = = 3");
    scene(bad);
    check_refused(
        d.dir, run, 2,
        {"scene.toml:" + std::to_string(line_of(bad, "dimension = = 3")) + ": TOML syntax error", "'dimension = = 3'"});
  }
  SUBCASE("output file that cannot be created") {
    scene(base);
    check_refused(d.dir, run, 3, {"no_such_folder/out.h5", "does not exist"}, "no_such_folder/out.h5");
  }
  SUBCASE("resume of a file that is not a mesocrack output") {
    scene(base);
    write_file(d / "notes.h5", "not hdf5");
    const Result r = mesocrack({"run", "scene.toml", "--resume", "notes.h5"}, d.dir);
    CHECK_MESSAGE(r.code == 3, r.describe());
    CHECK(contains(r.err, "notes.h5"));
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(slurp(d / "notes.h5") == "not hdf5");  // left as it was
    CHECK(files_in(d.dir) == std::vector<std::string>{"notes.h5", "scene.toml"});
  }
}

TEST_CASE_FIXTURE(BadInput, "bad_set_overrides_give_message_and_exit_2") {
  scene(base);
  auto with = [&](const std::string& set) { return std::vector<std::string>{"run", "scene.toml", "--set", set}; };
  check_refused(d.dir, with("walls[0].kn=5"), 2, {"scene.toml: ", "--set 'walls[0].kn=5'", "'walls' is not an array"});
  check_refused(d.dir, with("run..duration=1"), 2, {"scene.toml: ", "--set 'run..duration=1'", "is not a key path"});
  check_refused(d.dir, with("specimen.particles[5].radius=1"), 2,
                {"scene.toml: ", "--set 'specimen.particles[5].radius=1'",
                 "index 5 is past the end of 'specimen.particles'", "2 entries"});
  check_refused(d.dir, with("run.duration"), 2, {"scene.toml: ", "--set 'run.duration'", "expected key=value"});
  check_refused(d.dir, with("run.duraton=1 ms"), 2,
                {"scene.toml: ", "unknown key 'run.duraton' (from --set)", "duration"});
  check_refused(d.dir, with("timestep.safety=2"), 2,
                {"scene.toml: ", "key 'timestep.safety' (from --set) = 2", "out of range"});
  check_refused(d.dir, with("contacts[0].model=lineer"), 2,
                {"scene.toml: ", "key 'contacts[0].model' (from --set) = \"lineer\"", "hertz_mindlin"});
  check_refused(d.dir, with("run.duration=0.3 parsecs"), 2,
                {"scene.toml: ", "key 'run.duration' (from --set) = \"0.3 parsecs\"", "parsecs"});
}

namespace {

// A command refused before it reads anything: exit `code`, one line "error: ..." naming `parts`, nothing on
// stdout and no file written.
void check_command_refused(const TempDir& d, const std::vector<std::string>& args, int code,
                           const std::vector<std::string>& parts) {
  CAPTURE(args);
  const Result r = mesocrack(args, d.dir);
  CHECK_MESSAGE(r.code == code, r.describe());
  CHECK_MESSAGE(r.err.rfind("error: ", 0) == 0, r.err);
  CHECK_MESSAGE(std::count(r.err.begin(), r.err.end(), '\n') == 1, r.err);
  for (const auto& part : parts) CHECK_MESSAGE(contains(r.err, part), "stderr '", r.err, "' lacks '", part, "'");
  CHECK_MESSAGE(r.out.empty(), r.out);
  CHECK(files_in(d.dir) == std::vector<std::string>{"scene.toml"});
}

}  // namespace

TEST_CASE_FIXTURE(BadInput, "command_line_errors_of_every_subcommand_give_one_line_and_exit_2") {
  scene(base);
  const std::vector<std::string> run_scene{"run", "scene.toml", "-o", "out.h5"};
  const auto with = [](std::vector<std::string> args, const std::vector<std::string>& more) {
    args.insert(args.end(), more.begin(), more.end());
    return args;
  };
  SUBCASE("bad option values name the option, the value and what is allowed") {
    for (const std::string value : {"0", "-1", "abc", "1e3", "99999999999"}) {
      check_command_refused(d, with(run_scene, {"--threads", value}), 2,
                            {"--threads: '" + value + "' is not allowed", "whole number >= 1", "mesocrack run --help"});
      check_command_refused(d, {"generate", "scene.toml", "-o", "g.h5", "--threads", value}, 2,
                            {"--threads: '" + value + "'", "whole number >= 1"});
      check_command_refused(d, {"calibrate", "scene.toml", "--target", "ucs=1MPa", "-o", "c.toml", "--threads", value},
                            2, {"--threads: '" + value + "'", "whole number >= 1"});
      check_command_refused(d, with(run_scene, {"--realizations", value}), 2,
                            {"--realizations: '" + value + "'", "whole number from 1 to 10000"});
    }
    // A count that fits an int but no study: it allocated about 350 B per realization before the first packing.
    check_command_refused(d, with(run_scene, {"--realizations", "2147483647"}), 2,
                          {"--realizations: '2147483647'", "whole number from 1 to 10000"});
    const std::vector<std::string> calibrate{"calibrate", "scene.toml", "--target", "ucs=1MPa", "-o", "c.toml"};
    for (const std::string value : {"nan", "inf", "0", "0.6", "x"})
      check_command_refused(
          d, with(calibrate, {"--tolerance", value}), 2,
          {"--tolerance: '" + value + "'", "number from 0.0001 to 0.5", "mesocrack calibrate --help"});
    for (const std::string value : {"0", "101", "2.5"})
      check_command_refused(d, with(calibrate, {"--max-iterations", value}), 2,
                            {"--max-iterations: '" + value + "'", "whole number from 1 to 100"});
  }
  SUBCASE("unknown options, missing arguments and excluded pairs give CLI11's message") {
    check_command_refused(d, with(run_scene, {"--bogus"}), 2, {"not expected: --bogus"});
    check_command_refused(d, {"run"}, 2, {"scene file is required", "--resume OUT.h5 alone", "mesocrack run --help"});
    check_command_refused(d, {"run", "scene.toml", "-o"}, 2, {"--output"});
    check_command_refused(d, with(run_scene, {"--realizations", "2", "--resume", "out.h5"}), 2, {"excludes"});
    check_command_refused(d, {"generate"}, 2, {"scene is required"});
    check_command_refused(d, {"generate", "scene.toml", "--bogus"}, 2, {"not expected: --bogus"});
    check_command_refused(d, {"calibrate", "scene.toml", "-o", "c.toml"}, 2, {"--target is required"});
    check_command_refused(d, {"calibrate", "scene.toml", "--target", "ucs=1MPa"}, 2, {"--output is required"});
    check_command_refused(d, {"summary"}, 2, {"output is required", "mesocrack summary --help"});
    check_command_refused(d, {"summary", "a.h5", "b.h5"}, 2, {"not expected: b.h5"});
    check_command_refused(d, {"report"}, 2, {"output is required"});
    check_command_refused(d, {"report", "a.h5", "-o", "x"}, 2, {"not expected"});
  }
  SUBCASE("no command or an unknown one lists the commands") {
    check_command_refused(d, {}, 2, {"subcommand is required", "run, generate, calibrate, summary, report"});
    check_command_refused(d, {"frobnicate", "scene.toml"}, 2,
                          {"unknown command 'frobnicate'", "run, generate, calibrate, summary, report"});
  }
  SUBCASE("summary and report of a missing file are file errors") {
    check_command_refused(d, {"summary", "absent.h5"}, 3, {"absent.h5"});
    check_command_refused(d, {"report", "absent.h5"}, 3, {"absent.h5", "no such file"});
  }
}

TEST_CASE_FIXTURE(BadInput, "help_of_every_subcommand_exits_0") {
  for (const std::vector<std::string>& args : {std::vector<std::string>{"--help"},
                                               {"run", "--help"},
                                               {"generate", "--help"},
                                               {"calibrate", "--help"},
                                               {"summary", "--help"},
                                               {"report", "--help"}}) {
    CAPTURE(args);
    const Result r = mesocrack(args, d.dir);
    CHECK_MESSAGE(r.code == 0, r.describe());
    CHECK(contains(r.out, "Usage:"));
    CHECK(r.err.empty());
  }
}

// A build without the rigid-cell family (-DMESOCRACK_RIGID_CELL=OFF) still reads a rigid-cell scene ([rigid_cell]),
// and refuses to run or generate it like any bad input, naming the scene and the option that builds the family.
#if !MESOCRACK_RIGID_CELL_BUILT
TEST_CASE_FIXTURE(BadInput, "rigid_cell_scene_in_a_build_without_the_family_gives_message_and_exit_2" *
                                doctest::test_suite("build_options")) {
  const std::string rigid = (kScenes / "rigid_cell_tension_2d.toml").string();
  for (const std::string command : {"run", "generate"}) {
    CAPTURE(command);
    check_refused(d.dir, {command, rigid}, 2,
                  {"rigid_cell_tension_2d.toml: [rigid_cell]: ", "built without the rigid-cell family",
                   "-DMESOCRACK_RIGID_CELL=ON"});
  }
}
#endif

// A misspelt table was reported through what it broke ("'load' is not the name of one of the [[walls]]"), and a
// misspelt optional key as unknown with the whole list: each is named as the misspelling, with the name meant.
TEST_CASE("misspelt_table_or_key_is_named_as_the_misspelling_of_the_name_meant") {
  const TempDir d;
  check_edits_refused(d.dir, slurp(kScenes / "bending_small_2d.toml"),
                      {{"[[probes]]", "[[probe]]", {"'probe'", "misspelling of 'probes'"}},
                       {"[physics]", "[phisics]", {"'phisics'", "misspelling of 'physics'"}},
                       {"duration = ", "duraton = ", {"'run.duraton'", "misspelling of 'duration'"}}});
  check_edits_refused(d.dir, slurp(kScenes / "uniaxial_2d.toml"),
                      {{"[[wall_strains]]", "[[wall_strain]]", {"'wall_strain'", "misspelling of 'wall_strains'"}}});
}
