#include "studies/ranks.hpp"

#include <cstdlib>
#include <cstring>

#ifdef MESOCRACK_MPI
#include <mpi.h>
#endif

namespace mc {

namespace {
Ranks& the_ranks() {
  static Ranks r;
  return r;
}
#ifdef MESOCRACK_MPI
// Open MPI's launcher and the PMI/PMIx ones of Slurm set these in every process they start.
bool launched_by_mpirun() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE"})
    if (std::getenv(v)) return true;
  return false;
}
void finalize() {
  int done = 0;
  MPI_Finalized(&done);
  if (!done) MPI_Finalize();
}
// Element-wise over the ranks, in place.
template <class T>
void reduce_in_place(std::vector<T>& values, int ranks, MPI_Datatype type, MPI_Op op) {
  if (ranks > 1) MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), type, op, MPI_COMM_WORLD);
}
#endif
}  // namespace

void Ranks::start(int* argc, char*** argv) {
#ifdef MESOCRACK_MPI
  Ranks& r = the_ranks();
  if (r.joined_ || !launched_by_mpirun()) return;
  int provided = 0;
  MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);  // MPI calls from the main thread only
  MPI_Comm_rank(MPI_COMM_WORLD, &r.rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &r.size_);
  r.joined_ = true;
  std::atexit(finalize);
#else
  (void)argc, (void)argv;
#endif
}

const Ranks& Ranks::world() { return the_ranks(); }

std::vector<std::vector<std::uint8_t>> Ranks::share(int n, const Job& job) const {
  std::vector<std::vector<std::uint8_t>> out(n);
  // This rank's jobs as (k, byte count, bytes) records.
  std::vector<std::uint8_t> mine;
  for (int k = 0; k < n; ++k) {
    if (!owns(k)) continue;
    out[k] = job(k);
    const std::uint64_t head[2] = {static_cast<std::uint64_t>(k), out[k].size()};
    const auto* h = reinterpret_cast<const std::uint8_t*>(head);
    mine.insert(mine.end(), h, h + sizeof head);
    mine.insert(mine.end(), out[k].begin(), out[k].end());
  }
  if (!joined_ || size_ == 1) return out;
  for (const Bytes& theirs : RanksExchange(*this).all_gather(mine))
    for (std::size_t at = 0; at < theirs.size();) {
      std::uint64_t head[2];
      std::memcpy(head, theirs.data() + at, sizeof head);
      at += sizeof head;
      out[head[0]].assign(theirs.begin() + at, theirs.begin() + at + head[1]);
      at += head[1];
    }
  return out;
}

std::vector<Bytes> RanksExchange::all_to_all(const std::vector<Bytes>& out) const {
  const int n = size();
  if (n == 1) return {out[0]};
  std::vector<std::size_t> in_sizes(n);
#ifdef MESOCRACK_MPI
  std::vector<int> send_count(n), receive_count(n);
  for (int r = 0; r < n; ++r) send_count[r] = static_cast<int>(out[r].size());
  MPI_Alltoall(send_count.data(), 1, MPI_INT, receive_count.data(), 1, MPI_INT, MPI_COMM_WORLD);
  for (int r = 0; r < n; ++r) in_sizes[r] = static_cast<std::size_t>(receive_count[r]);
#endif
  return swap(out, in_sizes);
}

// Point to point, with only the ranks there is something to send to or receive from (a split specimen's
// neighbours): the cost does not grow with the number of ranks. Messages between two ranks arrive in the order
// they were sent, so consecutive exchanges never mix.
std::vector<Bytes> RanksExchange::swap(const std::vector<Bytes>& out, const std::vector<std::size_t>& in_sizes) const {
  const int n = size();
  if (n == 1) return {out[0]};
  std::vector<Bytes> in(n);
#ifdef MESOCRACK_MPI
  std::vector<MPI_Request> requests;
  for (int r = 0; r < n; ++r) {
    if (in_sizes[r] == 0) continue;
    in[r].resize(in_sizes[r]);
    requests.emplace_back();
    MPI_Irecv(in[r].data(), static_cast<int>(in_sizes[r]), MPI_BYTE, r, 0, MPI_COMM_WORLD, &requests.back());
  }
  for (int r = 0; r < n; ++r) {
    if (out[r].empty()) continue;
    requests.emplace_back();
    MPI_Isend(out[r].data(), static_cast<int>(out[r].size()), MPI_BYTE, r, 0, MPI_COMM_WORLD, &requests.back());
  }
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
#endif
  return in;
}

std::vector<Bytes> RanksExchange::all_gather(const Bytes& mine) const {
  const int n = size();
  if (n == 1) return {mine};
  std::vector<Bytes> all(n);
#ifdef MESOCRACK_MPI
  const int count = static_cast<int>(mine.size());
  std::vector<int> counts(n), at(n);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  int total = 0;
  for (int r = 0; r < n; ++r) at[r] = total, total += counts[r];
  Bytes joined(total);
  MPI_Allgatherv(mine.data(), count, MPI_BYTE, joined.data(), counts.data(), at.data(), MPI_BYTE, MPI_COMM_WORLD);
  for (int r = 0; r < n; ++r) all[r].assign(joined.begin() + at[r], joined.begin() + at[r] + counts[r]);
#endif
  return all;
}

void RanksExchange::max(std::vector<double>& values) const {
#ifdef MESOCRACK_MPI
  reduce_in_place(values, size(), MPI_DOUBLE, MPI_MAX);
#else
  (void)values;
#endif
}

void RanksExchange::sum(std::vector<std::int64_t>& values) const {
#ifdef MESOCRACK_MPI
  reduce_in_place(values, size(), MPI_INT64_T, MPI_SUM);
#else
  (void)values;
#endif
}

void Ranks::abort(int code) const {
#ifdef MESOCRACK_MPI
  if (joined_ && size_ > 1) MPI_Abort(MPI_COMM_WORLD, code);
#endif
  std::exit(code);
}

}  // namespace mc
