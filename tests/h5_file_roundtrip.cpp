// H5File: round trips of every type, replacement, tables, attributes, errors, id leaks, and a file that
// survives its writer being killed after a flush.
#include <doctest/doctest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/errors.hpp"
#include "io/h5_file.hpp"
#include "tests/common/errors.hpp"
#include "tests/common/temp_dir.hpp"

using mc::H5File;
using Dims = std::vector<hsize_t>;

namespace {

using mc::test::TempDir;

// Open files, groups, datasets, attributes and named types, in all files.
ssize_t open_ids() { return H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_ALL); }

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("datasets of every type round-trip with their shapes") {
  const TempDir tmp;
  const auto before = open_ids();
  const std::string path = tmp.file("types.h5");
  {
    H5File f(path, H5File::Mode::Create);
    f.write("/a/b/doubles", std::vector<double>{1.5, -2, 3, 4, 5, 6e300}, {2, 3});
    f.write("ints64", std::vector<std::int64_t>{-(std::int64_t{1} << 62), 0, 7, 8}, {4});
    f.write("/ints32", std::vector<std::int32_t>{1, -2, 3, -4, 5, -6, 7, -8}, {2, 2, 2});
    f.write("/bytes", std::vector<std::uint8_t>{0, 1, 255}, {3});
    f.write("/scalar", std::vector<double>{42.0}, {});
    f.write("/empty", std::vector<double>{}, {0, 3});
    CHECK_THROWS_AS(f.write("/bad", std::vector<double>{1, 2, 3}, {2, 2}), std::invalid_argument);
    CHECK(open_ids() == before + 1);  // the file alone
  }
  CHECK(open_ids() == before);

  const H5File f(path, H5File::Mode::ReadOnly);
  Dims dims;
  CHECK(f.read_doubles("/a/b/doubles", &dims) == std::vector<double>{1.5, -2, 3, 4, 5, 6e300});
  CHECK(dims == Dims{2, 3});
  CHECK(f.read_ints("/ints64", &dims) == std::vector<std::int64_t>{-(std::int64_t{1} << 62), 0, 7, 8});
  CHECK(dims == Dims{4});
  CHECK(f.read_ints("/ints32", &dims) == std::vector<std::int64_t>{1, -2, 3, -4, 5, -6, 7, -8});
  CHECK(dims == Dims{2, 2, 2});
  CHECK(f.read_doubles("/ints32") == std::vector<double>{1, -2, 3, -4, 5, -6, 7, -8});  // converted
  CHECK(f.read_bytes("/bytes") == std::vector<std::uint8_t>{0, 1, 255});
  CHECK(f.read_doubles("/bytes") == std::vector<double>{0, 1, 255});
  CHECK(f.read_doubles("/scalar", &dims) == std::vector<double>{42.0});
  CHECK(dims.empty());
  CHECK(f.read_doubles("/empty").empty());
  CHECK(f.shape("/empty") == Dims{0, 3});
  CHECK(f.shape("/a/b/doubles") == Dims{2, 3});
  CHECK_FALSE(f.exists("/bad"));

  // Reading as integers never truncates floats or clamps out-of-range values.
  CHECK(contains(mc::test::error_of<mc::IoError>([&] { f.read_ints("/a/b/doubles"); }), "stored as floating point"));
  CHECK(mc::test::error_of<mc::IoError>([&] { f.read_bytes("/ints32"); }) ==
        path + ": cannot read dataset '/ints32': a stored value is out of range for uint8");
}

TEST_CASE("groups: exists, list, create, remove; datasets are replaced, groups are not") {
  const TempDir tmp;
  const auto before = open_ids();
  {
    H5File f(tmp.file("groups.h5"), H5File::Mode::Create);
    CHECK(f.exists("/"));
    CHECK_FALSE(f.exists("/no/such/thing"));
    for (const char* name : {"/g/b", "/g/c10", "/g/a", "/g/c2"}) f.write(name, std::vector<double>{1}, {1});
    f.create_group("/g/sub/deeper");
    f.create_group("/g/sub");  // already there: nothing happens
    CHECK(f.list("/g") == std::vector<std::string>{"a", "b", "c10", "c2", "sub"});
    CHECK(f.list("/") == std::vector<std::string>{"g"});
    CHECK(f.exists("/g/sub/deeper"));
    CHECK_FALSE(f.exists("/g/a/below_a_dataset"));

    f.write("/g/a", std::vector<std::int32_t>{1, 2, 3, 4, 5, 6}, {3, 2});
    CHECK(f.shape("/g/a") == Dims{3, 2});
    CHECK(f.read_ints("/g/a") == std::vector<std::int64_t>{1, 2, 3, 4, 5, 6});
    CHECK(contains(mc::test::error_of<mc::IoError>([&] { f.write("/g/sub", std::vector<double>{1}, {1}); }),
                   "a group has that path"));
    CHECK(contains(mc::test::error_of<mc::IoError>([&] { f.create_group("/g/a"); }), "a dataset has that path"));
    CHECK(contains(mc::test::error_of<mc::IoError>([&] { f.list("/g/a"); }), "not a group"));

    f.remove("/g/b");
    f.remove("/g/sub");  // with everything below it
    f.remove("/g/never_was");
    CHECK(f.list("/g") == std::vector<std::string>{"a", "c10", "c2"});
  }
  CHECK(open_ids() == before);
}

TEST_CASE("tables grow in several appends, truncate, and grow again") {
  const TempDir tmp;
  const auto before = open_ids();
  const std::string path = tmp.file("tables.h5");
  // 3000 rows of width 3 span two 64 KiB chunks.
  std::vector<double> big(3000 * 3);
  for (std::size_t i = 0; i < big.size(); ++i) big[i] = static_cast<double>(i) * 0.5;
  {
    H5File f(path, H5File::Mode::Create);
    f.create_table("/history/forces", 3);
    f.create_table("/history/step", 0, true);
    CHECK(f.rows("/history/forces") == 0);
    CHECK(f.shape("/history/forces") == Dims{0, 3});

    const double first[] = {1, 2, 3};
    f.append_rows("/history/forces", first, 1);
    f.append_rows("/history/forces", first, 0);
    f.append_rows("/history/forces", big.data(), 3000);
    const std::int64_t steps[] = {10, 20, 30, 40};
    f.append_rows("/history/step", steps, 2);
    f.append_rows("/history/step", steps + 2, 2);
    CHECK(contains(mc::test::error_of<mc::IoError>([&] { f.append_rows("/history/step", first, 1); }),
                   "the table holds integers"));
    CHECK(contains(mc::test::error_of<mc::IoError>([&] { f.append_rows("/history/forces", steps, 1); }),
                   "the table holds doubles"));
    f.flush();

    std::vector<double> expected{1, 2, 3};
    expected.insert(expected.end(), big.begin(), big.end());
    Dims dims;
    CHECK(f.read_doubles("/history/forces", &dims) == expected);
    CHECK(dims == Dims{3001, 3});
    CHECK(f.read_ints("/history/step") == std::vector<std::int64_t>{10, 20, 30, 40});
  }
  CHECK(open_ids() == before);
  {
    H5File f(path, H5File::Mode::ReadWrite);  // as on resume
    f.truncate_rows("/history/forces", 2);
    f.truncate_rows("/history/step", 3);
    CHECK(contains(mc::test::error_of<mc::IoError>([&] { f.truncate_rows("/history/step", 5); }),
                   "it has 3 rows, fewer than 5"));
    const double more[] = {7, 8, 9, 10, 11, 12};
    f.append_rows("/history/forces", more, 2);
    const std::int64_t step = 99;
    f.append_rows("/history/step", &step, 1);
  }
  const H5File f(path, H5File::Mode::ReadOnly);
  CHECK(f.read_doubles("/history/forces") == std::vector<double>{1, 2, 3, 0, 0.5, 1, 7, 8, 9, 10, 11, 12});
  CHECK(f.rows("/history/forces") == 4);
  CHECK(f.read_ints("/history/step") == std::vector<std::int64_t>{10, 20, 30, 99});
}

TEST_CASE("attributes and strings") {
  const TempDir tmp;
  const auto before = open_ids();
  const std::string path = tmp.file("attrs.h5");
  const std::string scene = "# scene\n[particles]\nradius = 1e-3\nname = \"béton\"\n";
  std::string long_text;
  for (int i = 0; i < 20000; ++i) long_text += "line " + std::to_string(i) + "\n";
  {
    H5File f(path, H5File::Mode::Create);
    f.write_string("/scene", scene);
    f.write_string("/empty", "");
    f.write_string("/long", long_text);
    f.write("/frames/0000/x", std::vector<double>{1, 2}, {2});
    f.set_attr("/", "version", std::string("0.1"));
    f.set_attr("/frames/0000", "time", 1.25);
    f.set_attr("/frames/0000", "step", std::int64_t{1200});
    f.set_attr("/frames/0000/x", "unit", std::string("m"));
    f.set_attr("/frames/0000/x", "unit", std::string("metre"));  // overwritten, longer
    f.set_attr("/frames/0000", "step", 3.5);                     // overwritten, another type
    CHECK(contains(mc::test::error_of<mc::IoError>([&] { f.set_attr("/nowhere", "a", 1.0); }),
                   "no such group or dataset"));
  }
  CHECK(open_ids() == before);

  const H5File f(path, H5File::Mode::ReadOnly);
  CHECK(f.read_string("/scene") == scene);
  CHECK(f.read_string("/empty").empty());
  CHECK(f.read_string("/long") == long_text);
  CHECK(f.attr_string("/", "version") == "0.1");
  CHECK(f.attr_double("/frames/0000", "time") == 1.25);
  CHECK(f.attr_double("/frames/0000", "step") == 3.5);
  CHECK(f.attr_string("/frames/0000/x", "unit") == "metre");
  CHECK(f.has_attr("/frames/0000", "time"));
  CHECK_FALSE(f.has_attr("/frames/0000", "nope"));
  CHECK_FALSE(f.has_attr("/nowhere", "time"));
  CHECK(contains(mc::test::error_of<mc::IoError>([&] { f.attr_int("/frames/0000", "step"); }),
                 "stored as floating point"));
  CHECK(contains(mc::test::error_of<mc::IoError>([&] { f.read_doubles("/scene"); }), "stored as string"));
  CHECK(
      contains(mc::test::error_of<mc::IoError>([&] { f.read_string("/frames/0000/x"); }), "stored as floating point"));
  const std::string missing = mc::test::error_of<mc::IoError>([&] { f.attr_double("/frames/0000", "pressure"); });
  CHECK(missing == path + ": cannot read attribute 'pressure' of '/frames/0000': no such attribute");
}

TEST_CASE("variable-length strings, as h5py writes them, read too") {
  const TempDir tmp;
  const std::string path = tmp.file("vlen.h5");
  const char* text = "written by h5py: béton";
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t ds = H5Dcreate2(file, "/note", type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, &text);
  const hid_t attr = H5Acreate2(ds, "unit", type, space, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(attr, type, &text);
  H5Aclose(attr);
  H5Dclose(ds);
  H5Sclose(space);
  H5Tclose(type);
  H5Fclose(file);

  const H5File f(path, H5File::Mode::ReadOnly);
  CHECK(f.read_string("/note") == text);
  CHECK(f.attr_string("/note", "unit") == text);
}

TEST_CASE("errors name the file, the object and the reason") {
  const TempDir tmp;
  const auto before = open_ids();
  const std::string path = tmp.file("errors.h5");
  H5File(path, H5File::Mode::Create).write("/history/step", std::vector<std::int64_t>{1}, {1});
  {
    H5File f(path, H5File::Mode::ReadOnly);
    CHECK(mc::test::error_of<mc::IoError>([&] { f.read_doubles("/history/time"); }) ==
          path + ": cannot read dataset '/history/time': no such dataset");
    const std::string deep = mc::test::error_of<mc::IoError>([&] { f.shape("/no/group/here"); });
    CHECK(contains(deep, path));
    CHECK(contains(deep, "'/no/group/here'"));
    CHECK(contains(mc::test::error_of<mc::IoError>([&] { f.rows("/nothing"); }), "'/nothing': no such dataset"));
    const std::string readonly = mc::test::error_of<mc::IoError>([&] { f.write("/x", std::vector<double>{1}, {1}); });
    CHECK(contains(readonly, path + ": cannot write dataset '/x'"));
    CHECK(contains(readonly, "write intent"));

    H5File moved = std::move(f);
    CHECK(moved.read_ints("/history/step") == std::vector<std::int64_t>{1});
    CHECK(contains(mc::test::error_of<mc::IoError>([&] { f.exists("/history"); }),
                   "moved from"));  // NOLINT(bugprone-use-after-move)
  }
  CHECK(open_ids() == before);
  const std::string missing_file = tmp.file("absent.h5");
  CHECK(mc::test::error_of<mc::IoError>([&] { H5File absent(missing_file, H5File::Mode::ReadOnly); }) ==
        missing_file + ": cannot open file: no such file");
  const std::string not_hdf5 = tmp.file("plain.txt");
  std::FILE* plain = std::fopen(not_hdf5.c_str(), "w");
  std::fputs("not hdf5\n", plain);
  std::fclose(plain);
  CHECK(contains(mc::test::error_of<mc::IoError>([&] { H5File plain_file(not_hdf5, H5File::Mode::ReadWrite); }),
                 not_hdf5 + ": cannot open file"));
  const std::string in_missing_dir = tmp.file("no_dir/x.h5");
  CHECK(contains(mc::test::error_of<mc::IoError>([&] { H5File no_dir(in_missing_dir, H5File::Mode::Create); }),
                 in_missing_dir + ": cannot create file: no such directory"));
  CHECK(open_ids() == before);
}

// A child process creates the file, runs `write` on it, and dies by SIGKILL with the file still open.
template <class F>
void write_and_die(const std::string& path, F&& write) {
  const pid_t child = fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    try {
      H5File f(path, H5File::Mode::Create);
      write(f);
      raise(SIGKILL);
    } catch (...) {
    }
    _exit(1);
  }
  int status = 0;
  REQUIRE(waitpid(child, &status, 0) == child);
  REQUIRE(WIFSIGNALED(status));
  REQUIRE(WTERMSIG(status) == SIGKILL);
}

TEST_CASE("a writer killed after a flush leaves the flushed data readable") {
  const TempDir tmp;
  const std::string path = tmp.file("killed.h5");
  write_and_die(path, [](H5File& f) {
    f.write_string("/scene", "radius = 1");
    f.create_table("/history/time", 0);
    for (int i = 0; i < 100; ++i) {
      const double t = i * 0.01;
      f.append_rows("/history/time", &t, 1);
    }
    f.write("/frames/0000/x", std::vector<double>(3000, 2.5), {1000, 3});
    f.set_attr("/frames/0000", "step", std::int64_t{100});
    f.flush();
    // Work after the flush that never gets flushed: enough new objects to overflow HDF5's 2 MB metadata
    // cache, which, were it allowed to evict, would write half-updated groups and lose /frames/0000.
    for (int k = 1; k <= 2000; ++k) {
      const std::string frame = "/frames/" + std::to_string(1000 + k);
      f.write(frame + "/x", std::vector<double>(300, k), {100, 3});
      f.set_attr(frame, "step", std::int64_t{k});
      const double t = k;
      f.append_rows("/history/time", &t, 1);
    }
  });

  const H5File f(path, H5File::Mode::ReadOnly);
  CHECK(f.read_string("/scene") == "radius = 1");
  const std::vector<double> time = f.read_doubles("/history/time");
  REQUIRE(time.size() == 100);
  CHECK(time[99] == 99 * 0.01);
  CHECK(f.list("/frames") == std::vector<std::string>{"0000"});
  CHECK(f.read_doubles("/frames/0000/x") == std::vector<double>(3000, 2.5));
  CHECK(f.attr_int("/frames/0000", "step") == 100);
}

TEST_CASE("a writer killed before its first flush leaves an empty, readable file") {
  const TempDir tmp;
  const std::string path = tmp.file("early.h5");
  write_and_die(path, [](H5File& f) { f.write("/x", std::vector<double>(1000, 1.0), {1000}); });
  const H5File f(path, H5File::Mode::ReadOnly);
  CHECK(f.list("/").empty());
}
