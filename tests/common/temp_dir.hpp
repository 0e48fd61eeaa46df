// A private folder under the system temp directory, made unique by mkdtemp and removed with everything in it, so
// tests that write files can run side by side.
#pragma once
#include <stdlib.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace mc::test {

struct TempDir {
  std::filesystem::path dir;
  TempDir() {
    std::string t = (std::filesystem::temp_directory_path() / "mesocrack_test_XXXXXX").string();
    if (!mkdtemp(t.data())) throw std::runtime_error("mkdtemp failed: " + std::string(std::strerror(errno)));
    dir = t;
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::filesystem::path operator/(const std::string& name) const { return dir / name; }
  std::string file(const std::string& name) const { return (dir / name).string(); }
};

}  // namespace mc::test
