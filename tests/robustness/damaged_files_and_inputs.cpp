// Output files that lack what `summary` reads, or are no HDF5 at all, end `summary` and `report` with exit 3 naming
// the file and the missing entry (never a crash); and an output that is an input of the run (the scene file, the
// specimen file it loads, also through --set, or a file a sidecar would replace) is refused with exit 2 naming both,
// leaving the input as it was; an output that exists and is not a regular file (a device, a fifo, a socket, a folder,
// or a link to one), or lies in a folder that does not exist, is refused with exit 3 and left as it was.
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstring>

#include "tests/common/cli_harness.hpp"

namespace {

// A finished run of the two-disc collision, copied to `name` and changed by `damage`.
template <class F>
void damaged_copy(const TempDir& d, const std::string& name, F&& damage) {
  if (!fs::exists(d / "good.h5")) {
    const Result r = mesocrack({"run", (kScenes / "collision_2d.toml").string(), "-o", "good.h5"}, d.dir);
    REQUIRE_MESSAGE(r.code == 0, r.describe());
  }
  fs::copy_file(d / "good.h5", d / name);
  mc::H5File f((d / name).string(), mc::H5File::Mode::ReadWrite);
  damage(f);
}

void check_file_error(const Result& r, const std::vector<std::string>& parts) {
  CHECK_MESSAGE(r.code == 3, r.describe());
  CHECK_MESSAGE(std::count(r.err.begin(), r.err.end(), '\n') == 1, r.err);
  for (const auto& p : parts) CHECK_MESSAGE(contains(r.err, p), "stderr '", r.err, "' lacks '", p, "'");
}

}  // namespace

TEST_CASE("summary_of_a_file_lacking_what_it_reads_exits_3_naming_the_file_and_the_entry") {
  const TempDir d;
  damaged_copy(d, "no_time.h5", [](mc::H5File& f) { f.remove("/history/time"); });
  check_file_error(mesocrack({"summary", "no_time.h5"}, d.dir), {"no_time.h5", "/history/time"});
  damaged_copy(d, "no_history.h5", [](mc::H5File& f) { f.remove("/history"); });
  check_file_error(mesocrack({"summary", "no_history.h5"}, d.dir), {"no_history.h5", "/history"});
  damaged_copy(d, "short.h5", [](mc::H5File& f) { f.truncate_rows("/history/overlap", 3); });
  check_file_error(mesocrack({"summary", "short.h5"}, d.dir), {"short.h5", "/history/overlap", "3 rows"});
  damaged_copy(d, "no_scene.h5", [](mc::H5File& f) { f.remove("/scene"); });
  check_file_error(mesocrack({"summary", "no_scene.h5"}, d.dir), {"no_scene.h5", "/scene"});
  damaged_copy(d, "no_radius.h5", [](mc::H5File& f) { f.remove("/specimen/radius"); });
  check_file_error(mesocrack({"summary", "no_radius.h5"}, d.dir), {"no_radius.h5", "/specimen/radius"});
  damaged_copy(d, "bad_scene.h5", [](mc::H5File& f) { f.write_string("/scene", "dimension = 7\n"); });
  check_file_error(mesocrack({"summary", "bad_scene.h5"}, d.dir), {"bad_scene.h5", "/scene", "dimension"});
  write_file(d / "text.h5", "not HDF5\n");
  check_file_error(mesocrack({"summary", "text.h5"}, d.dir), {"text.h5"});
  check_file_error(mesocrack({"summary", "absent.h5"}, d.dir), {"absent.h5", "no such file"});
}

TEST_CASE("report_of_a_missing_or_non_hdf5_file_exits_3") {
  const TempDir d;
  write_file(d / "text.h5", "not HDF5\n");
  for (const std::string name : {"text.h5", "absent.h5"}) {
    const Result r = mesocrack({"report", name}, d.dir);
    CHECK_MESSAGE(r.code == 3, r.describe());
    CHECK_MESSAGE(contains(r.err, name), r.err);
  }
}

TEST_CASE("output_naming_an_input_of_the_run_is_refused_naming_both") {
  const TempDir d;
  const std::string scene = slurp(kScenes / "collision_2d.toml");
  write_file(d / "scene.toml", scene);
  // A specimen file the scene loads (kind = "output"): the collision's finished run.
  REQUIRE(mesocrack({"run", "scene.toml", "-o", "spec.h5"}, d.dir).code == 0);
  fs::copy_file(d / "spec.h5", d / "other.h5");
  const std::string from_file = edit(scene, "kind = \"particles\"", "kind = \"output\"\nfile = \"spec.h5\"");
  write_file(d / "loads.toml", from_file.substr(0, from_file.find("[[specimen.particles]]")) +
                                   from_file.substr(from_file.find("[[probes]]")));
  fs::create_directories(d / "sub");
  struct Case {
    std::vector<std::string> args;
    std::string input;  // the input the output would overwrite
  };
  const std::vector<Case> cases{
      {{"run", "scene.toml", "-o", "scene.toml"}, "scene.toml"},
      {{"run", "scene.toml", "-o", "sub/../scene.toml"}, "scene.toml"},  // another spelling of the same file
      {{"run", "loads.toml", "-o", "spec.h5"}, "spec.h5"},
      {{"run", "loads.toml", "-o", "./spec.h5"}, "spec.h5"},
      {{"run", "loads.toml", "--set", "specimen.file=other.h5", "-o", "other.h5"}, "other.h5"},
      {{"run", "loads.toml", "--resume", "spec.h5"}, "spec.h5"},
      {{"generate", "loads.toml", "-o", "spec.h5"}, "spec.h5"},
  };
  for (const auto& c : cases) {
    CAPTURE(c.args);
    const std::string before = slurp(d / c.input);
    const Result r = mesocrack(c.args, d.dir);
    CHECK_MESSAGE(r.code == 2, r.describe());
    CHECK_MESSAGE(contains(r.err, c.input), r.err);
    CHECK_MESSAGE(contains(r.err, "overwrite its own input"), r.err);
    CHECK(slurp(d / c.input) == before);
  }
  // A sidecar the run would replace that is an input: a scene named like the run's CSV.
  fs::copy_file(d / "scene.toml", d / "run_history.csv");
  const Result sidecar = mesocrack({"run", "run_history.csv", "-o", "run.h5"}, d.dir);
  CHECK_MESSAGE(sidecar.code == 2, sidecar.describe());
  CHECK_MESSAGE(contains(sidecar.err, "run_history.csv"), sidecar.err);
  CHECK(!fs::exists(d / "run.h5"));
}

TEST_CASE("output_onto_a_device_fifo_socket_or_folder_is_refused_and_left_as_it_was") {
  const TempDir d;
  const std::string scene = (kScenes / "collision_2d.toml").string();
  REQUIRE(mkfifo((d / "pipe").c_str(), 0600) == 0);
  const int sock = socket(AF_UNIX, SOCK_STREAM, 0);
  REQUIRE(sock >= 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  const std::string sock_path = (d / "sock").string();
  REQUIRE(sock_path.size() < sizeof(addr.sun_path));
  std::strcpy(addr.sun_path, sock_path.c_str());
  REQUIRE(bind(sock, reinterpret_cast<const sockaddr*>(&addr), sizeof(addr)) == 0);
  fs::create_directories(d / "folder");
  // A link to /dev/null is the device as the run would see it; the rename of a partial file over the link replaces
  // the link, not /dev/null, so the case can be tried as root without a private /dev.
  fs::create_symlink("/dev/null", d / "null_link");
  fs::create_symlink(d / "pipe", d / "pipe_link");
  struct Case {
    std::string output, kind;
    fs::file_type type;  // what it must still be
  };
  const std::vector<Case> cases{{"pipe", "a fifo", fs::file_type::fifo},
                                {"sock", "a socket", fs::file_type::socket},
                                {"folder", "a folder", fs::file_type::directory},
                                {"null_link", "a character device", fs::file_type::symlink},
                                {"pipe_link", "a fifo", fs::file_type::symlink}};
  for (const auto& c : cases) {
    CAPTURE(c.output);
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"run", scene, "-o", c.output}, std::vector<std::string>{"generate", scene, "-o", c.output}}) {
      const Result r = mesocrack(args, d.dir);
      CHECK_MESSAGE(r.code == 3, r.describe());
      CHECK_MESSAGE(contains(r.err, c.output), r.err);
      CHECK_MESSAGE(contains(r.err, c.kind), r.err);
      CHECK(fs::symlink_status(d / c.output).type() == c.type);
      CHECK(!fs::exists(d / (c.output + ".partial")));
      CHECK(!fs::exists(d / (c.output + ".xdmf")));
    }
  }
  close(sock);
  // A sidecar's name taken by a fifo: refused before the run, the fifo kept.
  REQUIRE(mkfifo((d / "run_history.csv").c_str(), 0600) == 0);
  const Result sidecar = mesocrack({"run", scene, "-o", "run.h5"}, d.dir);
  CHECK_MESSAGE(sidecar.code == 3, sidecar.describe());
  CHECK_MESSAGE(contains(sidecar.err, "run_history.csv"), sidecar.err);
  CHECK(fs::is_fifo(d / "run_history.csv"));
  CHECK(!fs::exists(d / "run.h5"));
  // An output in a folder that does not exist: refused before the run (calibrate: before its packing).
  const Result missing = mesocrack({"run", scene, "-o", "no/such/run.h5"}, d.dir);
  CHECK_MESSAGE(missing.code == 3, missing.describe());
  CHECK_MESSAGE(contains(missing.err, "no/such"), missing.err);
  CHECK_MESSAGE(contains(missing.err, "does not exist"), missing.err);
}

TEST_CASE("summary_of_a_run_still_writing_its_file_reads_it_as_running") {
  // A run of the 2D rigid-cell tension bar long enough to be caught mid-way; `summary` failed on HDF5's file lock
  // (exit 3) where `report` reads the same file.
  const TempDir d;
  Child run({"run", (kScenes / "brazilian_2d.toml").string(), "-o", "live.h5", "--set", "run.steps=100000"}, d.dir);
  const auto start = std::chrono::steady_clock::now();
  while (!fs::exists(d / "live.h5") && !run.ended() && std::chrono::steady_clock::now() - start < std::chrono::seconds(60))
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  REQUIRE_MESSAGE(fs::exists(d / "live.h5"), "the run never published its file");
  REQUIRE_FALSE(run.ended());
  const Result r = mesocrack({"summary", "live.h5"}, d.dir);
  run.kill_now();
  run.wait();
  CHECK_MESSAGE(r.code == 0, r.describe());
  CHECK_MESSAGE(contains(r.out, "\"status\": \"running\""), r.out);
}
