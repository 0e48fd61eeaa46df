// The particle-list reader: the shared benchmark specimen reads back as described in its README, and every
// bad line fails with one message naming the file, the line, the offending text and what is allowed.
#include <doctest/doctest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "engine/errors.hpp"
#include "io/sphere_list.hpp"
#include "tests/common/errors.hpp"

namespace {

// A private folder under the system temp directory, removed with everything in it.
struct ListDir {
  std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("mesocrack_sphere_list_test_" + std::to_string(getpid()));
  ListDir() { std::filesystem::create_directories(dir); }
  ~ListDir() { std::filesystem::remove_all(dir); }
  std::string write(const std::string& name, const std::string& text) const {
    const std::string path = (dir / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
};

template <int D>
std::string input_error(const ListDir& d, const std::string& text) {
  const std::string path = d.write("bad.spheres", text);
  return mc::test::error_of<mc::InputError>([&] { mc::read_sphere_list<D>(path); });
}

}  // namespace

TEST_CASE("sphere list: the shared specimen n10k reads as its README describes") {
  const auto s = mc::read_sphere_list<3>(MESOCRACK_SOURCE_DIR "/scenes/specimens/n10k.spheres");
  REQUIRE(s.size() == 10098);
  CHECK(s.radius.size() == 10098);
  CHECK(s.tag.size() == 10098);
  CHECK(s.id.size() == 10098);
  CHECK(std::all_of(s.radius.begin(), s.radius.end(), [](double r) { return r == 2.95e-3; }));
  const std::set<int> tags(s.tag.begin(), s.tag.end());
  CHECK(tags == std::set<int>{0, 1, 2});
  CHECK(s.id.front() == 0);
  CHECK(s.id.back() == 10097);
  // Box 0.1 × 0.1 × 0.2 m: every sphere inside it, and the packing reaching within a radius of each face.
  const double box[3] = {0.1, 0.1, 0.2};
  for (int k = 0; k < 3; ++k) {
    double lo = 1e9, hi = -1e9;
    for (int i = 0; i < s.size(); ++i) {
      lo = std::min(lo, s.x[i][k] - s.radius[i]);
      hi = std::max(hi, s.x[i][k] + s.radius[i]);
    }
    CHECK(lo >= -1e-9);
    CHECK(hi <= box[k] + 1e-9);
    CHECK(lo < 2.95e-3);
    CHECK(hi > box[k] - 2.95e-3);
  }
  // The held layer (tag 1) is at the bottom, the moved layer (tag 2) at the top.
  double z1 = -1, z2 = 1;
  for (int i = 0; i < s.size(); ++i) {
    if (s.tag[i] == 1) z1 = std::max(z1, s.x[i][2]);
    if (s.tag[i] == 2) z2 = std::min(z2, s.x[i][2]);
  }
  CHECK(z1 < 0.02);
  CHECK(z2 > 0.18);
}

TEST_CASE("sphere list: comments, blank lines, CRLF, '+' signs and the 2D forms") {
  const ListDir d;
  const auto s3 = mc::read_sphere_list<3>(d.write("ok3.spheres",
                                                  "# id x y z r tag\n\n"
                                                  "7 0.1 0.2 0.3 1e-3 2   # trailing comment\r\n"
                                                  "  \t\n"
                                                  "3\t-1.5e-2 +0 4 0.5 -1"));  // no final newline
  REQUIRE(s3.size() == 2);
  CHECK(s3.id[0] == 7);
  CHECK(s3.x[0] == mc::Vec<3>(0.1, 0.2, 0.3));
  CHECK(s3.radius[0] == 1e-3);
  CHECK(s3.tag[0] == 2);
  CHECK(s3.x[1] == mc::Vec<3>(-1.5e-2, 0, 4));
  CHECK(s3.tag[1] == -1);

  const auto s2 = mc::read_sphere_list<2>(d.write("ok2.spheres", "0 1 2 0.5 0\n1 3 4 0 0.25 1\n"));
  REQUIRE(s2.size() == 2);
  CHECK(s2.x[0] == mc::Vec<2>(1, 2));
  CHECK(s2.radius[0] == 0.5);
  CHECK(s2.x[1] == mc::Vec<2>(3, 4));
  CHECK(s2.radius[1] == 0.25);
  CHECK(s2.tag[1] == 1);
}

TEST_CASE("sphere list: each bad line names the file, the line, the text and what is allowed") {
  const ListDir d;
  const std::string f = (d.dir / "bad.spheres").string();
  const std::string ok = "# header\n0 0 0 0 0.001 0\n";
  CHECK(input_error<3>(d, ok + "1 0 0 0.002 0\n") == f + ":3: expected 6 fields 'id x y z r tag', found 5");
  CHECK(input_error<3>(d, ok + "1 0 0 0 0.001 0 7\n") == f + ":3: expected 6 fields 'id x y z r tag', found 7");
  CHECK(input_error<3>(d, ok + "\n1 0 0 0.004 -1 0\n") == f + ":4: radius '-1' must be > 0");
  CHECK(input_error<3>(d, ok + "1 0 0 0.004 0 0\n") == f + ":3: radius '0' must be > 0");
  CHECK(input_error<3>(d, ok + "1 0 0 0.004 nan 0\n") == f + ":3: radius 'nan' must be a finite number");
  CHECK(input_error<3>(d, ok + "1 0 0.0o1 0 0.001 0\n") == f + ":3: y '0.0o1' is not a number");
  CHECK(input_error<3>(d, ok + "1 inf 0 0 0.001 0\n") == f + ":3: x 'inf' must be a finite number");
  CHECK(input_error<3>(d, ok + "1 0 0 1e999 0.001 0\n") == f + ":3: z '1e999' is out of the range of a double");
  CHECK(input_error<3>(d, ok + "1 0 0 0 0.001 top\n") == f + ":3: tag 'top' must be an integer");
  CHECK(input_error<3>(d, ok + "1 0 0 0 0.001 1.0\n") == f + ":3: tag '1.0' must be an integer");
  CHECK(input_error<3>(d, ok + "-4 0 0 0 0.001 0\n") == f + ":3: id '-4' must be an integer >= 0");
  CHECK(input_error<3>(d, ok + "0 0 0 0 0.001 0\n") == f + ":3: id '0' is already used on line 2; ids must be unique");
  CHECK(input_error<3>(d, "# nothing\n\n") ==
        f + ": no particles (every line is blank or a comment); expected lines 'id x y z r tag'");
  CHECK(input_error<2>(d, "0 0 0 0.001\n") ==
        f + ":1: expected 5 fields 'id x y r tag' or 6 fields 'id x y z r tag' with z = 0 (2D list), found 4");
  CHECK(input_error<2>(d, "0 0 0 0.5 0.001 0\n") ==
        f + ":1: z '0.5' must be 0 in a 2D list (the discs lie in the plane z = 0)");
}

TEST_CASE("sphere list: a file that cannot be read names the path and the reason") {
  const ListDir d;
  const std::string missing = (d.dir / "missing.spheres").string();
  CHECK(mc::test::error_of<mc::IoError>([&] { mc::read_sphere_list<3>(missing); }) ==
        "cannot read particle list '" + missing + "': No such file or directory");
  CHECK(mc::test::error_of<mc::IoError>([&] { mc::read_sphere_list<3>(d.dir.string()); }) ==
        "cannot read particle list '" + d.dir.string() + "': Is a directory");
}
