// A resume continues the checkpoint under the scene it was written with: the command refuses (exit 2, naming
// the key, the file byte for byte untouched) any change but the run's end, its stop conditions, the output
// cadences and the summaries, and accepts those, leaving every history as long as `time`.
#include "scene/resume_check.hpp"
#include "tests/common/cli_harness.hpp"

namespace {

const std::string kCollision = (kScenes / "collision_2d.toml").string();

// The collision scene run to 0.1 ms (222 steps) with a checkpoint every 50 steps.
const std::vector<std::string> kShort = {"--set", "run.duration=0.1 ms", "--set", "output.checkpoint_every=50"};

std::vector<std::string> with(std::vector<std::string> a, const std::vector<std::string>& more) {
  a.insert(a.end(), more.begin(), more.end());
  return a;
}

// The collision scene without its second probe and the summary that reads it.
std::string without_second_probe() {
  std::string s = slurp(kCollision);
  s = edit(s, "[[probes]]\nname = \"approach_speed\"\nkind = \"relative_speed\"\nparticles = [0, 1]\n", "");
  return edit(s, "[[summary]]\nname = \"restitution\"\nof = \"approach_speed\"\nreduce = \"final_over_initial\"\n", "");
}

// Runs the short collision into dir/a.h5 and returns its bytes.
std::string short_run(const TempDir& d) {
  const Result r = mesocrack(with({"run", kCollision, "-o", "a.h5"}, kShort), d.dir);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  return slurp(d / "a.h5");
}

void check_refused(const Result& r, const std::string& key, const std::string& before, const fs::path& file) {
  CHECK_MESSAGE(r.code == 2, r.describe());
  CHECK_MESSAGE(contains(r.err, "cannot resume"), r.err);
  CHECK_MESSAGE(contains(r.err, "'" + key), r.err, " does not name ", key);
  CHECK_MESSAGE(slurp(file) == before, "the refused resume changed ", file.string());
}

}  // namespace

TEST_CASE("resume refuses a scene that lost a probe, naming it, and leaves the file untouched") {
  const TempDir d;
  const std::string before = short_run(d);
  write_file(d / "fewer.toml", without_second_probe());
  check_refused(mesocrack(with({"run", "fewer.toml", "--resume", "a.h5"}, kShort), d.dir), "probes[1]", before,
                d / "a.h5");
}

TEST_CASE("resume refuses a scene that gained a probe, naming it, and leaves the file untouched") {
  const TempDir d;
  write_file(d / "fewer.toml", without_second_probe());
  REQUIRE(mesocrack(with({"run", "fewer.toml", "-o", "a.h5"}, kShort), d.dir).code == 0);
  const std::string before = slurp(d / "a.h5");
  check_refused(mesocrack(with({"run", kCollision, "--resume", "a.h5"}, kShort), d.dir), "probes[1]", before,
                d / "a.h5");
}

TEST_CASE("resume refuses a changed material, contact law, specimen, wall or seed given by --set") {
  const TempDir d;
  const std::string before = short_run(d);
  for (const auto& [set, key] : std::vector<std::pair<std::string, std::string>>{
           {"contacts[0].modulus=60 MPa", "contacts[0].modulus"},
           {"contacts[0].friction=0.3", "contacts[0].friction"},
           {"phases[0].density=2700", "phases[0].density"},
           {"specimen.particles[1].radius=1.1 mm", "specimen.particles[1].radius"},
           {"timestep.safety=0.1", "timestep.safety"},
           {"seed=2", "seed"}}) {
    CAPTURE(set);
    check_refused(mesocrack(with({"run", kCollision, "--resume", "a.h5", "--set", set}, kShort), d.dir), key, before,
                  d / "a.h5");
  }
}

TEST_CASE(
    "resume accepts a later end, new cadences and a new stop condition, and every history stays as long as time") {
  const TempDir d;
  short_run(d);
  const Result r = mesocrack({"run", kCollision, "--resume", "a.h5", "--set", "run.duration=0.2 ms", "--set",
                              "output.checkpoint_every=70", "--set", "output.history_every=3", "--set",
                              "output.frame_every=50", "--set", "run.stop=[{quantity = \"overlap\", above = 1.0}]"},
                             d.dir);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  const mc::H5File f((d / "a.h5").string(), mc::H5File::Mode::ReadOnly);
  const auto time = f.read_doubles("/history/time");
  // 222 steps recorded every step (the scene's history_every = 1), then every 3rd step up to 0.2 ms (444 steps).
  CHECK(time.back() >= 0.2e-3);
  CHECK(time.size() > 222);
  CHECK(time.size() < 222 + 80);
  for (const auto& name : history_names(f)) {
    CAPTURE(name);
    CHECK(f.read_doubles("/history/" + name).size() == time.size());
  }
  check_no_repeated_rows(d / "a.h5");
}

TEST_CASE("the keys a resume may change are the run's end, stops, output cadences and summaries, nothing else") {
  const std::string base = "dimension = 2\nseed = 1\n[run]\nsteps = 10\n[output]\nhistory_every = 5\n";
  auto refused = [&](const std::string& now) { return mc::compare_for_resume(base, now).refused; };
  CHECK(refused(base).empty());
  CHECK(refused(edit(base, "steps = 10", "steps = 20\nduration = 1.0")).empty());
  CHECK(refused(edit(base, "history_every = 5", "history_every = 7\nframe_every = 3")).empty());
  CHECK(refused(base + "[[summary]]\nname = \"a\"\nof = \"time\"\nreduce = \"max\"\n").empty());
  CHECK(refused(edit(base, "seed = 1", "seed = 2")) == "key 'seed' was 1, now 2");
  CHECK(refused(edit(base, "seed = 1\n", "")) == "key 'seed' (1) is gone");
  CHECK(refused(base + "[physics]\nenergy = true\n") == "key 'physics.energy' = true is new");
  CHECK(mc::compare_for_resume(base, base + "[[run.stop]]\nquantity = \"time\"\nabove = 1.0\n").stops_changed);
  CHECK_FALSE(mc::compare_for_resume(base, edit(base, "steps = 10", "steps = 11")).stops_changed);
}
