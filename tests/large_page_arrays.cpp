// The engine's arrays of 2 MiB and more start on a 2 MiB boundary and carry the kernel's advice to back them
// with 2 MiB pages (engine/large_pages.cpp). Not physics, but a part of the speed beyond the caches that no other
// test would miss: if the linker stopped taking the engine's operator new, every number would stay the same.
#include <doctest/doctest.h>

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "engine/dim.hpp"

namespace {

constexpr std::uintptr_t kLargePage = std::uintptr_t(2) << 20;

// The "THPeligible" line of the mapping that holds address a in /proc/self/smaps: 1 when the kernel may back it
// with huge pages (advised, and huge pages not switched off); -1 when the kernel does not report it.
int huge_page_eligible(const void* a) {
  const auto at = reinterpret_cast<std::uintptr_t>(a);
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    std::uintptr_t lo = 0, hi = 0;
    char dash = 0;
    std::istringstream range(line);
    if (range >> std::hex >> lo >> dash >> hi && dash == '-') {
      inside = lo <= at && at < hi;
      continue;
    }
    if (inside && line.rfind("THPeligible:", 0) == 0) return std::stoi(line.substr(12));
  }
  return -1;
}

std::string huge_page_setting() {
  std::ifstream f("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string s;
  std::getline(f, s);
  return s;
}

}  // namespace

TEST_CASE("particle_array_of_four_mebibytes_starts_on_a_large_page_advised_for_huge_pages") {
  const std::vector<mc::Vec<3>> x(4 * (std::size_t(1) << 20) / sizeof(mc::Vec<3>));
  CHECK(reinterpret_cast<std::uintptr_t>(x.data()) % kLargePage == 0);
  // Eligible when the kernel lets a program ask ("[always]" or "[madvise]"); no assertion where it reports nothing.
  const std::string setting = huge_page_setting();
  const int eligible = huge_page_eligible(x.data());
  if (eligible >= 0 && setting.find("[never]") == std::string::npos) CHECK(eligible == 1);
}

TEST_CASE("small_arrays_stay_with_malloc_off_the_large_page_boundaries") {
  // 1000 blocks of 1 KiB: were they all put on 2 MiB boundaries, the process would reserve 2 GiB.
  std::vector<std::vector<double>> small(1000, std::vector<double>(128, 1.0));
  int on_boundary = 0;
  for (const auto& s : small) on_boundary += reinterpret_cast<std::uintptr_t>(s.data()) % kLargePage == 0;
  // One may land there by chance (malloc's blocks sit at any 16-byte step, 1 in 131 072 of them on a 2 MiB
  // boundary); two or more would mean the small ones are aligned too.
  CHECK(on_boundary <= 1);
}
