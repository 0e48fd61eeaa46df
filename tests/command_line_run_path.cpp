// The run path through the real `mesocrack` command (MESOCRACK_CLI; bad input: command_line_bad_input.cpp): a
// killed run leaves a file that `summary` reads and `run --resume` finishes bit for bit like an uninterrupted run;
// `summary` reports what the histories hold; every shipped scene runs; `report` writes the PNGs it names; a finished
// run resumed with a later end continues like one long run, and with the same end adds nothing. Each test works in its
// own fresh temp folder; the command runs as a child process (fork/execve) with its stdout and stderr captured to
// files.
#include "tests/common/cli_harness.hpp"
#include "tests/common/relative.hpp"

// ================================================================ 1. kill and resume

TEST_CASE("killed_run_leaves_readable_file_and_resume_matches_uninterrupted_run") {
  const TempDir d;
  // 1500 discs falling into a box: contacts (with their tangential springs) form from ~0.045 s on. Frames every
  // 1000 steps and checkpoints every 3000, so the killed file nearly always holds frames and history rows written
  // after its last checkpoint, which the resume must drop and write again.
  const std::string scene = (kScenes / "deposition_2d.toml").string();
  const std::vector<std::string> sets{"--set", "run.duration=0.12 s",    "--set", "output.checkpoint_every=3000",
                                      "--set", "output.frame_every=1000"};
  auto args = [&](std::vector<std::string> a) {
    a.insert(a.end(), sets.begin(), sets.end());
    return a;
  };
  constexpr double kill_after_step = 20000;  // of ~32600; contacts exist by then

  // A: uninterrupted, two threads.
  const Result a = mesocrack(args({"run", scene, "-o", "a.h5", "--threads", "2"}), d.dir);
  REQUIRE_MESSAGE(a.code == 0, a.describe());
  MESSAGE("uninterrupted run: ", a.seconds, " s");

  // B: one thread, killed once the histories show step >= kill_after_step (so the checkpoints up to there are
  // complete: history rows past a checkpoint's step are flushed only after that checkpoint was written). The
  // polling `summary` reads without HDF5's file lock, which the running writer holds; a read that catches the
  // file mid-write may fail and is retried.
  Child b(args({"run", scene, "-o", "b.h5", "--threads", "1"}), d.dir);
  double seen_step = 0;
  const auto poll_start = Clock::now();
  while (!b.ended() && Clock::now() - poll_start < std::chrono::seconds(150)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(150));
    if (!fs::exists(d / "b.h5")) continue;
    const Result s = Child({"summary", "b.h5"}, d.dir, {"HDF5_USE_FILE_LOCKING=FALSE"}).wait(std::chrono::seconds(30));
    if (s.code != 0) continue;
    try {
      const Json j = parse_json(s.out);
      if (j["status"].text != "running") break;
      seen_step = j["steps"].number;
    } catch (const std::exception&) {
      continue;
    }
    if (seen_step >= kill_after_step) {
      b.kill_now();
      break;
    }
  }
  const Result killed = b.wait();
  REQUIRE_MESSAGE(killed.code == -SIGKILL, "run B was not killed mid-run (last step seen ", seen_step,
                  "): ", killed.describe());
  MESSAGE("run B killed after ", killed.seconds, " s at step >= ", seen_step);

  // The killed file is readable: summary exits 0 with valid JSON and status "running".
  const Json sb = summary_of("b.h5", d.dir);
  CHECK(sb["status"].text == "running");
  CHECK(sb["history_rows"].number > 0);
  CHECK(sb["steps"].number >= kill_after_step);
  const Json sa = summary_of("a.h5", d.dir);
  CHECK(sa["status"].text == "finished");
  CHECK(sb["steps"].number < sa["steps"].number);
  {
    const mc::H5File f((d / "b.h5").string(), mc::H5File::Mode::ReadOnly);
    CHECK(f.attr_string("/", "status") == "running");
    CHECK(f.rows("/frames/x") >= 1);
    CHECK(f.rows("/frames/x") == f.rows("/frames/time"));
  }

  // Resume B with the same scene and overrides, on two threads.
  const Result resumed = mesocrack(args({"run", scene, "--resume", "b.h5", "--threads", "2"}), d.dir);
  REQUIRE_MESSAGE(resumed.code == 0, resumed.describe());
  CHECK(contains(resumed.err, "finished"));
  MESSAGE("resumed run: ", resumed.seconds, " s");

  // B now equals A bit for bit: every history series, every frame, the status.
  check_same_run(d / "a.h5", d / "b.h5");
  {
    const mc::H5File fa((d / "a.h5").string(), mc::H5File::Mode::ReadOnly);
    CHECK(fa.read_doubles("/history/contacts").back() > 100);  // the resume carried real contacts across
  }
  // The CSV written at the end holds the same histories, so it is the same text.
  CHECK(slurp(d / "a_history.csv") == slurp(d / "b_history.csv"));
}

// ================================================================ 2. summary

TEST_CASE("summary_json_matches_histories") {
  const TempDir d;
  const Result r = mesocrack({"run", (kScenes / "collision_3d.toml").string(), "-o", "c.h5"}, d.dir);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  const Json j = summary_of("c.h5", d.dir);

  const mc::H5File f((d / "c.h5").string(), mc::H5File::Mode::ReadOnly);
  const auto names = history_names(f);
  auto series = [&](const std::string& n) { return f.read_doubles("/history/" + n); };
  const auto t = series("time"), overlap = series("overlap"), speed = series("approach_speed");
  REQUIRE(t.size() > 100);

  CHECK(j["file"].text == "c.h5");
  CHECK(j["title"].text == "Two-sphere collision, linear contact");
  CHECK(j["dimension"].text == "3");
  CHECK(j["status"].text == "finished");
  CHECK(j["particles"].text == "2");
  CHECK(j["history_rows"].number == static_cast<double>(t.size()));
  CHECK(j["time"].text == json_number(t.back()));
  CHECK(j["steps"].text == json_number(series("step").back()));

  // final.*: exactly the recorded series, each its last row (to the 10 digits printed).
  const Json& fin = j["final"];
  std::vector<std::string> keys;
  for (const auto& [k, v] : fin.members) keys.push_back(k);
  CHECK(keys == names);
  for (const auto& n : names) CHECK_MESSAGE(fin[n].text == json_number(series(n).back()), "final.", n);

  // results.*: the scene's reductions of the histories.
  const Json& res = j["results"];
  CHECK(res.members.size() == 3);
  const double max_overlap = *std::max_element(overlap.begin(), overlap.end());
  CHECK(res["max_overlap_m"].text == json_number(max_overlap));
  CHECK(max_overlap > 0);
  // Contact duration: the time the overlap is positive, crossings interpolated linearly between rows.
  double duration = 0;
  for (std::size_t k = 1; k < overlap.size(); ++k) {
    const double a = overlap[k - 1], b = overlap[k], dt = t[k] - t[k - 1];
    if (a > 0 && b > 0)
      duration += dt;
    else if (a > 0 || b > 0)
      duration += dt * std::max(a, b) / std::abs(b - a);
  }
  CHECK(res["contact_duration_s"].number == mc::test::relative(duration, 1e-9));
  CHECK(res["restitution"].number == mc::test::relative(std::abs(speed.back()) / std::abs(speed.front()), 1e-9));

  // Closed forms (the scene's comment): m = ρ (4/3)π R³, m* = m/2, k_n = 4 R E_c / 2; T = π sqrt(m*/k_n) = 23.2 µs.
  const double R = 1e-3, rho = 2600, E_c = 50e6;
  const double m = rho * 4.0 / 3.0 * std::numbers::pi * R * R * R, kn = 4 * R * E_c / 2;
  const double T = std::numbers::pi * std::sqrt(m / 2 / kn);
  CHECK(T == mc::test::relative(23.2e-6, 0.002));
  CHECK(res["contact_duration_s"].number == mc::test::relative(T, 0.015));
  CHECK(res["restitution"].number == mc::test::relative(1.0, 0.01));
  // The approach speed: −0.1 m/s before (closing), +0.1 m/s after (no damping).
  CHECK(speed.front() == mc::test::relative(-0.1, 1e-12));
  CHECK(speed.back() == mc::test::relative(0.1, 0.01));
}

// ================================================================ 3. every scene

// A genesis packing is built before the first step and costs minutes at the reference scenes' resolution
// (8 000 spheres in uniaxial_3d), and a 3D rigid-cell specimen of 10^4 cells a few seconds a factorisation: tests of
// the run path over every scene make grains four times and cells under 5 mm twice as coarse, which they, about the run
// path and not the specimen, do not notice. Returns the --set arguments.
static std::vector<std::string> coarse_specimen(const fs::path& scene) {
  const std::string text = slurp(scene);
  const auto millimetres = [&](const std::string& key) {
    const auto at = text.find(key + " = \"");
    REQUIRE(at != std::string::npos);
    return std::stod(text.substr(at + key.size() + 4));
  };
  if (contains(text, "kind = \"packing\""))
    return {"--set", "specimen.radius_min=" + std::to_string(4e-3 * millimetres("radius_min"))};
  // A dynamic rigid-cell scene factorises once and then reuses the factor (the cantilever's 32 000 DOFs: 3 s in
  // all for its first steps), and its plates hold one layer of nodes, which a coarser l_min would leave empty.
  if (contains(text, "[rigid_cell.dynamics]")) return {};
  if (!contains(text, "kind = \"voronoi_cells\"")) return {};
  const bool three_d = contains(text, "\ndimension = 3");
  // 2D cells finer than 1.5 mm (a beam's 2 000-5 000 cells, tens of secant iterations a step once its facets
  // soften) run twice as coarse too; coarsening away from a fine box becomes uniform at the doubled l_min.
  if (millimetres("l_min") >= (three_d ? 5 : 1.5)) return {};
  const std::string l_min = std::to_string(2e-3 * millimetres("l_min"));
  if (!contains(text, "\nl_max = ")) return {"--set", "specimen.l_min=" + l_min};
  return {"--set", "specimen.l_min=" + l_min, "--set", "specimen.l_max=" + l_min};
}

// The steps a loop over every scene gives `scene` for `steps` of the others: a tenth for a 2D rigid-cell scene and a
// fiftieth for a 3D one or a 2D one whose cells coarsen away from a crack (l_max: a beam of 2 000-5 000 cells whose
// load steps reach its peak within 20-40), whose damaged steps take tens of milliseconds to seconds each (a static
// solve of 10^3-10^4 cells with tens of secant iterations where damage spreads; the compact-tension specimen's
// facets soften from its tenth load step on); their first steps still build the specimen, solve, write and resume.
// Their damage is tested by their own tests.
static int loop_steps(const fs::path& scene, int steps) {
  const std::string text = slurp(scene);
  if (!contains(text, "\n[rigid_cell]")) return steps;
  return contains(text, "\ndimension = 3") || contains(text, "\nl_max = ") ? steps / 50 : steps / 10;
}

// The shipped Hertz–Mindlin collision (scenes/collision_hertz_3d.toml) against Hertz's closed forms (Johnson 1985,
// §11.4) for its G = 50 MPa, ν = 0.2, R = 1 mm, ρ = 2600 kg/m³, v = 0.1 m/s: E* = G/(1 − ν), R* = R/2, m* = m/2.
// Its step varies with the stiffness (safety 0.05), about 100 steps per contact: within 1 % (the constant-step
// check of the law, tests/two_particle_impact.cpp, is the tighter one).
TEST_CASE("shipped_hertz_collision_lasts_as_long_and_overlaps_as_deep_as_hertz_says") {
  const TempDir d;
  const Result r = mesocrack({"run", (kScenes / "collision_hertz_3d.toml").string(), "-o", "h.h5"}, d.dir);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  const Json summary = summary_of("h.h5", d.dir);
  const Json& res = summary["results"];
  const double m = 2600 * 4.0 / 3.0 * M_PI * 1e-9, m_eff = 0.5 * m, e_eff = 50e6 / 0.8, r_eff = 0.5e-3, v = 0.1;
  const double duration = 2.868 * std::pow(m_eff * m_eff / (r_eff * e_eff * e_eff * v), 0.2);
  const double overlap = std::pow(15 * m_eff * v * v / (16 * e_eff * std::sqrt(r_eff)), 0.4);
  CHECK(res["contact_duration_s"].number == mc::test::relative(duration, 0.01));
  CHECK(res["max_overlap_m"].number == mc::test::relative(overlap, 0.01));
  CHECK(res["restitution"].number == mc::test::relative(1.0, 1e-3));
}

// The shipped rolling-resistance slope (scenes/rolling_slope_3d.toml): a sphere rolling against its rolling moment
// μ_r R F_n reaches a t after t = 0.1 s, a = g (sin θ − μ_r cos θ)/(1 + 2/5) (tests/rolling_resistance_slope.cpp);
// its start from touching, not from rest at the equilibrium overlap, costs a transient of a few steps in 77 000:
// within 1e-4. With μ_r above tan θ it stays: its speed is round-off, far below 1e-9 m/s.
TEST_CASE("shipped_rolling_slope_rolls_at_g_sin_minus_mu_r_cos_and_stays_where_mu_r_is_above_tan") {
  const TempDir d;
  const double theta = 20 * M_PI / 180;
  const double a = 9.81 * (std::sin(theta) - 0.1 * std::cos(theta)) / 1.4;
  const std::string scene = (kScenes / "rolling_slope_3d.toml").string();
  const Result r = mesocrack({"run", scene, "-o", "r.h5"}, d.dir);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  const Json rolled = summary_of("r.h5", d.dir);
  CHECK(rolled["results"]["speed_final_m_per_s"].number == mc::test::relative(a * 0.1, 1e-4));
  const Result held = mesocrack({"run", scene, "-o", "h.h5", "--set", "contacts[0].rolling_friction=0.4"}, d.dir);
  REQUIRE_MESSAGE(held.code == 0, held.describe());
  const Json stayed = summary_of("h.h5", d.dir);
  CHECK(stayed["results"]["speed_final_m_per_s"].number < 1e-9);
}

TEST_CASE("every_scene_in_scenes_folder_runs" * doctest::test_suite("build_options")) {
  const std::vector<fs::path> scenes = runnable_scenes();
  REQUIRE(!scenes.empty());
  const auto t0 = Clock::now();
  for (const auto& s : scenes) {
    CAPTURE(s.string());
    const TempDir d;
    // 200 steps whatever the scene says (loop_steps): a duration is lifted (0: no limit), the step count ends the
    // run; a scene's own stop condition may end it sooner.
    const int steps = loop_steps(s, 200);
    std::vector<std::string> args{
        "run",   s.string(),      "-o", "out.h5", "--threads", "2", "--set", "run.steps=" + std::to_string(steps),
        "--set", "run.duration=0"};
    const auto coarse = coarse_specimen(s);
    args.insert(args.end(), coarse.begin(), coarse.end());
    const Result r = mesocrack(args, d.dir);
    CHECK_MESSAGE(r.code == 0, r.describe());
    if (r.code != 0) continue;
    const Json j = summary_of("out.h5", d.dir);
    CHECK(j["history_rows"].number >= 2);
    CHECK(j["particles"].number >= 1);
    if (j["status"].text == "finished") {
      CHECK(j["steps"].text == std::to_string(steps));
    } else {
      CHECK_MESSAGE(j["status"].text == "stopped", j["status"].text);
      CHECK(j["steps"].number <= steps);
    }
    CHECK(fs::exists(d / "out.xdmf"));
    CHECK(fs::exists(d / "out_history.csv"));
    check_no_repeated_rows(d / "out.h5");
    MESSAGE(s.filename().string(), ": ", r.seconds, " s");
  }
  CHECK(std::chrono::duration<double>(Clock::now() - t0).count() < 60);
}

// ================================================================ 4. report

TEST_CASE("report_writes_pngs") {
  const TempDir d;
  struct Case {
    std::string scene, output;
    std::vector<std::string> sets, expected;  // expected: PNG name suffixes that must be among those printed
  };
  const std::vector<Case> cases{
      {"deposition_2d.toml",
       "dep2.h5",
       {"--set", "run.steps=400", "--set", "output.frame_every=200"},
       {"_history.png", "_energy.png", "_specimen.png"}},
      {"collision_3d.toml", "col3.h5", {}, {"_history.png", "_slice.png"}},
  };
  for (const auto& c : cases) {
    CAPTURE(c.scene);
    std::vector<std::string> args{"run", (kScenes / c.scene).string(), "-o", c.output, "--threads", "2"};
    args.insert(args.end(), c.sets.begin(), c.sets.end());
    const Result r = mesocrack(args, d.dir);
    REQUIRE_MESSAGE(r.code == 0, r.describe());
    const Result rep = mesocrack({"report", c.output}, d.dir);
    CHECK_MESSAGE(rep.code == 0, rep.describe());
    std::vector<std::string> printed;
    std::istringstream lines(rep.out);
    for (std::string line; std::getline(lines, line);)
      if (!line.empty()) printed.push_back(line);
    CHECK(!printed.empty());
    for (const auto& p : printed) {
      CAPTURE(p);
      CHECK(p.ends_with(".png"));
      CHECK(fs::path(p).parent_path() == fs::canonical(d.dir));  // next to the output file
      REQUIRE(fs::exists(p));
      CHECK(fs::file_size(p) > 1000);
      CHECK(slurp(p).substr(0, 8) == std::string("\x89PNG\r\n\x1a\n", 8));
    }
    const std::string stem = fs::path(c.output).stem().string();
    for (const auto& suffix : c.expected)
      CHECK_MESSAGE(
          std::any_of(printed.begin(), printed.end(), [&](const std::string& p) { return p.ends_with(stem + suffix); }),
          (stem + suffix), " not printed");
  }
}

// ================================================================ 5. resume of a finished run

// A finished run resumed with a later end continues from its final checkpoint exactly as one long run would; a
// finished run resumed with the same end writes nothing new (no repeated final row or frame). One scene of each
// kind of state (state_signature): the scenes that differ only in their numbers (the same test on mortar and on
// concrete) checkpoint the same state.
TEST_CASE("resume_extends_a_finished_run_like_one_long_run") {
  const std::vector<fs::path> scenes = scenes_one_per_kind_of_state();
  MESSAGE(scenes.size(), " of ", runnable_scenes().size(), " scenes");
  CHECK(scenes.size() * 4 > runnable_scenes().size() * 3);  // the signature tells most scenes apart
  REQUIRE(!scenes.empty());
  // Rows every 50 steps and frames every 100 (loop_steps), so the step where the short run ends has both, like the
  // long run.
  for (const auto& s : scenes) {
    CAPTURE(s.string());
    const auto coarse = coarse_specimen(s);
    const std::vector<std::string> common{"--threads", "2",
                                          "--set",     "run.duration=0",
                                          "--set",     "output.history_every=" + std::to_string(loop_steps(s, 50)),
                                          "--set",     "output.frame_every=" + std::to_string(loop_steps(s, 100))};
    auto args = [&](std::vector<std::string> a, int steps) {
      a.insert(a.end(), common.begin(), common.end());
      a.insert(a.end(), coarse.begin(), coarse.end());
      a.insert(a.end(), {"--set", "run.steps=" + std::to_string(loop_steps(s, steps))});
      return a;
    };
    const TempDir d;
    const Result whole = mesocrack(args({"run", s.string(), "-o", "whole.h5"}, 600), d.dir);
    REQUIRE_MESSAGE(whole.code == 0, whole.describe());
    const Result half = mesocrack(args({"run", s.string(), "-o", "halves.h5"}, 300), d.dir);
    REQUIRE_MESSAGE(half.code == 0, half.describe());
    const Result rest = mesocrack(args({"run", s.string(), "--resume", "halves.h5"}, 600), d.dir);
    REQUIRE_MESSAGE(rest.code == 0, rest.describe());
    check_same_run(d / "whole.h5", d / "halves.h5");
    check_no_repeated_rows(d / "halves.h5");
    // Resuming the finished run with the same end: nothing to do, nothing added.
    fs::copy_file(d / "whole.h5", d / "before.h5");
    const Result again = mesocrack(args({"run", s.string(), "--resume", "whole.h5"}, 600), d.dir);
    REQUIRE_MESSAGE(again.code == 0, again.describe());
    check_same_run(d / "before.h5", d / "whole.h5");
    check_no_repeated_rows(d / "whole.h5");
    MESSAGE(s.filename().string(), ": runs of ", whole.seconds, ", ", half.seconds, ", ", rest.seconds, " and ",
            again.seconds, " s");
  }
}

// ================================================================ 6. resume with servo walls

// Four servo walls squeezing a small box of discs, in contact with the discs from a few hundred steps on.
// A checkpoint must carry the contact forces of the last step (World::save, "contact_f"): a run resumed at a step where
// the timestep is refreshed (step % timestep.every == 0; every checkpoint at a multiple of 10 steps with the
// default every = 10) recomputes each wall's contact_kn from those forces, and without them would find no touching
// contact and drive the walls at max_speed for up to `every` steps, departing from the uninterrupted run.
TEST_CASE("resume_with_servo_walls_in_contact_matches_uninterrupted_run") {
  const TempDir d;
  std::string walls;
  const char* w[4][4] = {{"bottom", "[0, 0]", "[\"20 mm\", 0]", ""},
                         {"top", "[0, \"20 mm\"]", "[\"20 mm\", \"20 mm\"]", ""},
                         {"left", "[0, 0]", "[0, \"20 mm\"]", ""},
                         {"right", "[\"20 mm\", 0]", "[\"20 mm\", \"20 mm\"]", ""}};
  for (const auto& x : w)
    walls += std::string("[[walls]]\nname = \"") + x[0] + "\"\nshape = \"segment\"\na = " + x[1] + "\nb = " + x[2] +
             "\ninside = [\"10 mm\", \"10 mm\"]\nkn = \"2e8 N/m\"\nmotion = \"servo\"\nstress = \"100 kPa\"\n"
             "max_speed = \"1 m/s\"\ngain = 0.2\n";
  write_file(
      d / "servo.toml",
      "title = \"servo box\"\ndimension = 2\nseed = 5\n[[phases]]\nname = \"grain\"\ndensity = \"2600 kg/m3\"\n"
      "[[contacts]]\nphase_a = \"grain\"\nmodel = \"linear\"\nmodulus = \"100 MPa\"\nkn_ks_ratio = 2.0\nfriction = "
      "0.3\n"
      "[specimen]\nkind = \"random_box\"\nlo = [0, 0]\nhi = [\"20 mm\", \"20 mm\"]\ncount = 180\n"
      "radius_min = \"0.4 mm\"\nradius_max = \"0.6 mm\"\n" +
          walls +
          "[physics]\nlocal_damping = 0.7\n[run]\nsteps = 2000\n[output]\nhistory_every = 50\nframe_every = 500\n");
  const Result whole = mesocrack({"run", "servo.toml", "-o", "whole.h5"}, d.dir);
  REQUIRE_MESSAGE(whole.code == 0, whole.describe());
  const Result half = mesocrack({"run", "servo.toml", "-o", "halves.h5", "--set", "run.steps=1000"}, d.dir);
  REQUIRE_MESSAGE(half.code == 0, half.describe());
  {  // the walls press on the discs when the first half ends, so the servo gain matters at the resume
    const mc::H5File f((d / "halves.h5").string(), mc::H5File::Mode::ReadOnly);
    const auto top = f.read_doubles("/history/wall.top.stress"), left = f.read_doubles("/history/wall.left.stress");
    REQUIRE(top.size() == 21);
    CHECK(std::abs(top[19]) + std::abs(top[20]) + std::abs(left[19]) + std::abs(left[20]) > 0);
  }
  const Result rest = mesocrack({"run", "servo.toml", "--resume", "halves.h5"}, d.dir);
  REQUIRE_MESSAGE(rest.code == 0, rest.describe());
  check_same_run(d / "whole.h5", d / "halves.h5");
}

// A run that ended on its stop condition keeps that end: resuming it (its final checkpoint holds the reason)
// must not carry it on past the condition.
TEST_CASE("resumed_stopped_run_stays_stopped") {
  const TempDir d;
  write_file(d / "stop.toml", R"(dimension = 2
[[phases]]
name = "g"
density = 2600
[[contacts]]
phase_a = "g"
model = "linear"
modulus = 5e7
[specimen]
kind = "particles"
[[specimen.particles]]
x = [0, 0]
radius = 0.001
velocity = [0.05, 0]
[[specimen.particles]]
x = [0.00201, 0]
radius = 0.001
velocity = [-0.05, 0]
[[probes]]
name = "overlap"
kind = "overlap"
particles = [0, 1]
[run]
steps = 100000
[[run.stop]]
quantity = "overlap"
above = 5e-7
[output]
history_every = 1
)");
  const Result first = mesocrack({"run", "stop.toml", "-o", "stop.h5"}, d.dir);
  REQUIRE_MESSAGE(first.code == 0, first.describe());
  const Json a = summary_of("stop.h5", d.dir);
  CHECK(a["status"].text == "stopped");
  // The overlap of two discs approaching at 0.1 m/s passes 5e-7 m long before the 100000 steps.
  CHECK(a["steps"].number < 1000);
  const Result again = mesocrack({"run", "stop.toml", "--resume", "stop.h5"}, d.dir);
  REQUIRE_MESSAGE(again.code == 0, again.describe());
  const Json b = summary_of("stop.h5", d.dir);
  CHECK(b["status"].text == "stopped");
  CHECK(b["steps"].number == a["steps"].number);
  CHECK(b["history_rows"].number == a["history_rows"].number);
}
