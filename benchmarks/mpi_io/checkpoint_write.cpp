// How a split run's checkpoint reaches the file, measured alone: the whole world's state gathered on rank 0 and
// written there (what `mesocrack run` does under mpirun), against every rank writing its own part of the same
// dataset through parallel HDF5 (MPI-IO, collective). The payload is the checkpoint's size, each rank holding an
// equal share; the time runs from the ranks holding their shares to the file closed. Built when Debian's parallel
// HDF5 (libhdf5-openmpi-dev) is present:
//   mpirun -np 2 --bind-to core build/benchmarks/checkpoint_write --megabytes 789 --rounds 3 --dir /tmp
#include <hdf5.h>
#include <mpi.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "benchmarks/options.hpp"

namespace {

using Clock = std::chrono::steady_clock;

// Seconds from a barrier to the slowest rank's end of f().
template <class F>
double timed(F&& f) {
  MPI_Barrier(MPI_COMM_WORLD);
  const auto t0 = Clock::now();
  f();
  double s = std::chrono::duration<double>(Clock::now() - t0).count(), slowest = 0;
  MPI_Allreduce(&s, &slowest, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return slowest;
}

// One dataset of n doubles in a new file, written from `data` (offset `first`, `count` values) with the file
// access and transfer properties given.
void write_part(const std::string& file, hid_t fapl, hid_t dxpl, hsize_t n, hsize_t first, hsize_t count,
                const double* data) {
  const hid_t f = H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  const hid_t space = H5Screate_simple(1, &n, nullptr);
  const hid_t ds = H5Dcreate2(f, "x", H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t mem = H5Screate_simple(1, &count, nullptr);
  H5Sselect_hyperslab(space, H5S_SELECT_SET, &first, nullptr, &count, nullptr);
  if (H5Dwrite(ds, H5T_NATIVE_DOUBLE, mem, space, dxpl, data) < 0) std::abort();
  H5Sclose(mem), H5Sclose(space), H5Dclose(ds), H5Fclose(f);
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  double megabytes = 789;
  int rounds = 3;
  std::string dir = "/tmp";
  CLI::App app{"checkpoint_write: a split run's checkpoint gathered on rank 0 against parallel HDF5"};
  app.add_option("--megabytes", megabytes, "the checkpoint's size, MB")->check(CLI::Range(1.0, 1e6));
  app.add_option("--rounds", rounds, "rounds of both ways, in turns")->check(CLI::Range(1, 100));
  app.add_option("--dir", dir, "where the two files are written")->check(CLI::ExistingDirectory);
  if (const auto code = mc::bench::read_options(app, argc, argv, "checkpoint_write", rank == 0)) {
    MPI_Finalize();
    return *code;
  }
  const auto n = static_cast<hsize_t>(megabytes * 1e6 / sizeof(double));
  const hsize_t share = n / ranks, first = share * rank, count = rank == ranks - 1 ? n - first : share;
  std::vector<double> mine(count);
  for (hsize_t k = 0; k < count; ++k) mine[k] = static_cast<double>(first + k);
  const std::string gathered = dir + "/checkpoint_gathered.h5", parallel = dir + "/checkpoint_parallel.h5";
  for (int round = 0; round < rounds; ++round) {
    // Gathered: every share to rank 0 (in pieces of at most 1 GiB, MPI's counts being int), written there alone.
    const double t_gather = timed([&] {
      constexpr hsize_t kPiece = (hsize_t(1) << 30) / sizeof(double);
      if (rank != 0) {
        for (hsize_t at = 0; at < count; at += kPiece)
          MPI_Send(mine.data() + at, static_cast<int>(std::min(kPiece, count - at)), MPI_DOUBLE, 0, 0, MPI_COMM_WORLD);
        return;
      }
      std::vector<double> whole(n);
      std::memcpy(whole.data(), mine.data(), count * sizeof(double));
      for (int r = 1; r < ranks; ++r) {
        const hsize_t from = share * r, size = r == ranks - 1 ? n - from : share;
        for (hsize_t at = 0; at < size; at += kPiece)
          MPI_Recv(whole.data() + from + at, static_cast<int>(std::min(kPiece, size - at)), MPI_DOUBLE, r, 0,
                   MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      }
      write_part(gathered, H5P_DEFAULT, H5P_DEFAULT, n, 0, n, whole.data());
    });
    // Parallel: one file opened by all ranks through MPI-IO, each writing its hyperslab in one collective call.
    const double t_parallel = timed([&] {
      const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
      H5Pset_fapl_mpio(fapl, MPI_COMM_WORLD, MPI_INFO_NULL);
      const hid_t dxpl = H5Pcreate(H5P_DATASET_XFER);
      H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE);
      write_part(parallel, fapl, dxpl, n, first, count, mine.data());
      H5Pclose(dxpl), H5Pclose(fapl);
    });
    if (rank == 0) std::printf("| %d | %.0f | %.3f | %.3f |\n", ranks, n * sizeof(double) / 1e6, t_gather, t_parallel);
  }
  if (rank == 0) std::remove(gathered.c_str()), std::remove(parallel.c_str());
  MPI_Finalize();
  return 0;
}
