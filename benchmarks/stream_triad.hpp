// The machine's memory bandwidth as STREAM measures it: the triad a = b + s·c over arrays far larger than the
// caches, best of several passes, on the threads asked for. STREAM's count: 24 bytes per element (two reads, one
// write; the write-allocate read is not counted).
#pragma once
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <vector>

namespace mc::bench {

inline double triad_bytes_per_second(int threads, std::size_t n = std::size_t(1) << 24) {
  std::vector<double> a(n), b(n), c(n);
  // Each thread first touches the pages it will stream (what STREAM does, for machines with several sockets).
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::size_t i = 0; i < n; ++i) a[i] = 0.0, b[i] = 1.0, c[i] = 2.0;
  double best = 1e300;
  for (int pass = 0; pass < 6; ++pass) {
    const double s = 3.0 + pass;
    const auto t0 = std::chrono::steady_clock::now();
#pragma omp parallel for schedule(static) num_threads(threads)
    for (std::size_t i = 0; i < n; ++i) a[i] = b[i] + s * c[i];
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  volatile double keep = a[n / 2];  // the result is used: the passes cannot be optimised away
  (void)keep;
  return 24.0 * static_cast<double>(n) / best;
}

}  // namespace mc::bench
