// Indirect displacement control of the rigid-cell static solver (CMOD control, rigid_cell/static_solver.hpp
// GaugeControl) on scenes/bending_notched_rigid_cell_2d.toml: a brittle notched beam whose load-point travel snaps
// back after its peak. Driven by the opening of its notch mouth it stays in equilibrium through the snap-back;
// driven by the load point it cannot, and its steps end in snap-throughs.
#include <algorithm>

#include "tests/common/cli_harness.hpp"
#include "tests/common/relative.hpp"

namespace {

const fs::path kBeam = kScenes / "bending_notched_rigid_cell_2d.toml";

// The same beam pushed down at the load plate's own speed (displacement control): the opening control left out.
std::string displacement_controlled(const std::string& scene) {
  const auto from = scene.find("\n[rigid_cell.opening_control]"), to = scene.find("\n[[phases]]");
  REQUIRE(from != std::string::npos);
  REQUIRE(to != std::string::npos);
  const std::string without = scene.substr(0, from) + scene.substr(to);
  return edit(without, "box_hi = [\"154 mm\", \"50 mm\"]\nfix = \"y\"",
              "box_hi = [\"154 mm\", \"50 mm\"]\nfix = \"y\"\nvelocity = [0, \"-3 mm/s\"]");
}

// The largest return of a travel that went out: max over steps of (the farthest reached so far − the travel now).
double largest_return(const std::vector<double>& travel) {
  double farthest = 0, back = 0;
  for (double t : travel) {
    farthest = std::max(farthest, t);
    back = std::max(back, farthest - t);
  }
  return back;
}

std::vector<double> negated(std::vector<double> v) {
  for (double& x : v) x = -x;
  return v;
}

}  // namespace

TEST_CASE("rigid_cell_notched_beam_under_cmod_control_follows_its_snap_back_without_snap_throughs") {
  const TempDir d;
  const Result cmod = mesocrack({"run", kBeam.string(), "-o", "cmod.h5"}, d.dir);
  REQUIRE_MESSAGE(cmod.code == 0, cmod.describe());
  write_file(d / "pushed.toml", displacement_controlled(slurp(kBeam)));
  const Result pushed = mesocrack({"run", "pushed.toml", "-o", "pushed.h5"}, d.dir);
  REQUIRE_MESSAGE(pushed.code == 0, pushed.describe());

  const mc::H5File c((d / "cmod.h5").string(), mc::H5File::Mode::ReadOnly);
  const mc::H5File p((d / "pushed.h5").string(), mc::H5File::Mode::ReadOnly);
  // Both ran past the peak to the stop at a tenth of it: the beam broke through.
  REQUIRE(c.read_doubles("/history/facets.cracked").back() > 5);

  // The gauge opens as declared: 2 mm/s × t at every step, to round-off (λ is solved for exactly in each secant
  // iteration, and the last iteration's state is the step's).
  const auto time = c.read_doubles("/history/time"), opening = c.read_doubles("/history/cmod");
  for (std::size_t i = 0; i < time.size(); ++i) REQUIRE(opening[i] == mc::test::relative(2e-3 * time[i], 1e-9));

  // Equilibrium through the whole path: no part of a step was solved as a snap-through under CMOD control, while the
  // load-point control needed some (3 measured).
  CHECK(c.read_doubles("/history/snap_throughs").back() == 0);
  CHECK(p.read_doubles("/history/snap_throughs").back() > 0);

  // The snap-back itself: with the mouth opening steadily, the load point comes back up while the crack runs (by
  // 9 µm of its 93 µm travel measured); a path that only softened would never return. 1 µm is far above round-off
  // and below the measured return.
  const auto travel = negated(c.read_doubles("/history/group.load.disp_y"));
  CHECK(largest_return(travel) > 1e-6);
  // Displacement control never returns, by definition: its load point only goes out.
  CHECK(largest_return(negated(p.read_doubles("/history/group.load.disp_y"))) == 0);

  // Before the peak both follow one equilibrium path, so the peaks agree (7.77 and 7.80 kN measured: the steps
  // reach the peak at different points, 0.2 µm of travel against 0.3 µm apart); 2 % holds that with room.
  const auto load_c = c.read_doubles("/history/group.left.reaction_y");
  const auto load_p = p.read_doubles("/history/group.left.reaction_y");
  CHECK(*std::max_element(load_c.begin(), load_c.end()) ==
        mc::test::relative(*std::max_element(load_p.begin(), load_p.end()), 0.02));
}

TEST_CASE("rigid_cell_cmod_controlled_beam_resumed_halfway_gives_the_same_bits") {
  const TempDir d;
  // 160 steps: past the peak (step ~40) and two of the crack's jumps; both parts end on a frame (every 20).
  const Result whole = mesocrack({"run", kBeam.string(), "-o", "whole.h5", "--set", "run.steps=160"}, d.dir);
  REQUIRE_MESSAGE(whole.code == 0, whole.describe());
  const Result first = mesocrack(
      {"run", kBeam.string(), "-o", "parts.h5", "--set", "run.steps=80", "--set", "output.checkpoint_every=80"}, d.dir);
  REQUIRE_MESSAGE(first.code == 0, first.describe());
  const Result rest = mesocrack(
      {"run", kBeam.string(), "--resume", "parts.h5", "--set", "run.steps=160", "--set", "output.checkpoint_every=80"},
      d.dir);
  REQUIRE_MESSAGE(rest.code == 0, rest.describe());
  check_same_run(d / "whole.h5", d / "parts.h5");
}

TEST_CASE("rigid_cell_opening_control_bad_input_names_the_key") {
  const TempDir d;
  const std::string beam = slurp(kBeam);
  struct Case {
    std::string what, with, key, says;
  };
  const std::vector<Case> cases = {
      {"probe = \"cmod\"\nplate", "probe = \"mouth\"\nplate", "rigid_cell.opening_control.probe",
       "is not the name of an opening probe"},
      {"plate = \"load\"", "plate = \"loading\"", "rigid_cell.opening_control.plate", "is not the name of a plate"},
      // The load plate does not hold x: it cannot be driven along it.
      {"direction = [0, -1]", "direction = [1, -1]", "rigid_cell.opening_control.direction", "add x to its 'fix'"},
      {"rate = \"2 mm/s\"", "rate = \"-2 mm/s\"", "rigid_cell.opening_control.rate", "-0.002"},
      {"kind = \"opening\"", "kind = \"gap\"", "probes[0].kind", "opening"},
  };
  for (const Case& k : cases) {
    CAPTURE(k.with);
    write_file(d / "bad.toml", edit(beam, k.what, k.with));
    const Result r = mesocrack({"run", "bad.toml", "-o", "bad.h5"}, d.dir);
    CHECK(r.code == 2);
    CHECK_MESSAGE(contains(r.err, k.key), r.err);
    CHECK_MESSAGE(contains(r.err, k.says), r.err);
    CHECK_FALSE(fs::exists(d / "bad.h5"));
  }
  // Pushing the load plate up closes the notch: refused before anything runs, naming the plate and the gauge.
  write_file(d / "up.toml", edit(beam, "direction = [0, -1]", "direction = [0, 1]"));
  const Result up = mesocrack({"run", "up.toml", "-o", "up.h5"}, d.dir);
  CHECK(up.code == 2);
  CHECK_MESSAGE(contains(up.err, "plate 'load'"), up.err);
  CHECK_MESSAGE(contains(up.err, "does not open gauge 'cmod'"), up.err);
  CHECK_FALSE(fs::exists(d / "up.h5"));
}
