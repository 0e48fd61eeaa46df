// What memory the machine has and the process holds, for the estimates that refuse a specimen too large before it
// is built (particles, rigid cells, the rigid-cell stiffness's factor).
#pragma once
#include <unistd.h>

#include <cstdio>

namespace mc {

// The machine's physical memory [bytes].
inline double physical_memory() {
  return static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGE_SIZE));
}

// What this process holds resident now [bytes] (Linux's /proc/self/statm; 0 where it cannot be read).
inline double resident_memory() {
  double size = 0, resident = 0;
  if (std::FILE* f = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(f, "%lf %lf", &size, &resident) != 2) resident = 0;
    std::fclose(f);
  }
  return resident * static_cast<double>(sysconf(_SC_PAGE_SIZE));
}

}  // namespace mc
