#include "studies/ranks.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <utility>

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
// Posts every send and receive of one exchange and waits for them all. MPI counts are int: a message goes in
// pieces of at most 1 GiB (a checkpoint gathered from a few million particles is larger than 2 GiB), which
// arrive in the order they were sent. A receive's buffer has its size already; a rank's message to itself is
// copied.
void send_and_receive(const std::vector<std::pair<int, const Bytes*>>& sends,
                      const std::vector<std::pair<int, Bytes*>>& receives) {
  constexpr std::size_t kPiece = std::size_t(1) << 30;
  int me = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &me);
  std::vector<MPI_Request> requests;
  for (const auto& [r, b] : receives)
    for (std::size_t at = 0; r != me && at < b->size(); at += kPiece) {
      requests.emplace_back();
      MPI_Irecv(b->data() + at, static_cast<int>(std::min(kPiece, b->size() - at)), MPI_BYTE, r, 0, MPI_COMM_WORLD,
                &requests.back());
    }
  for (const auto& [r, b] : sends) {
    if (r == me) {
      for (const auto& [from, into] : receives)
        if (from == me) std::memcpy(into->data(), b->data(), b->size());
      continue;
    }
    for (std::size_t at = 0; at < b->size(); at += kPiece) {
      requests.emplace_back();
      MPI_Isend(b->data() + at, static_cast<int>(std::min(kPiece, b->size() - at)), MPI_BYTE, r, 0, MPI_COMM_WORLD,
                &requests.back());
    }
  }
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
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
  std::vector<std::uint64_t> send_count(n), receive_count(n);
  for (int r = 0; r < n; ++r) send_count[r] = out[r].size();
  MPI_Alltoall(send_count.data(), 1, MPI_UINT64_T, receive_count.data(), 1, MPI_UINT64_T, MPI_COMM_WORLD);
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
  std::vector<std::pair<int, const Bytes*>> sends;
  std::vector<std::pair<int, Bytes*>> receives;
  for (int r = 0; r < n; ++r) {
    if (in_sizes[r] > 0) in[r].resize(in_sizes[r]), receives.push_back({r, &in[r]});
    if (!out[r].empty()) sends.push_back({r, &out[r]});
  }
  send_and_receive(sends, receives);
#else
  (void)in_sizes;
#endif
  return in;
}

// MPI_Allgatherv while the total fits its int counts; else (a checkpoint of millions of particles, shared for a
// resume) every rank's bytes to every other, in pieces.
std::vector<Bytes> RanksExchange::all_gather(const Bytes& mine) const {
  const int n = size();
  if (n == 1) return {mine};
  std::vector<Bytes> all(n);
#ifdef MESOCRACK_MPI
  const std::uint64_t count = mine.size();
  std::vector<std::uint64_t> counts(n);
  MPI_Allgather(&count, 1, MPI_UINT64_T, counts.data(), 1, MPI_UINT64_T, MPI_COMM_WORLD);
  std::uint64_t total = 0;
  for (std::uint64_t c : counts) total += c;
  if (total < (std::uint64_t(1) << 31)) {
    std::vector<int> sizes(n), at(n);
    int sum = 0;
    for (int r = 0; r < n; ++r) sizes[r] = static_cast<int>(counts[r]), at[r] = sum, sum += sizes[r];
    Bytes joined(total);
    MPI_Allgatherv(mine.data(), static_cast<int>(count), MPI_BYTE, joined.data(), sizes.data(), at.data(), MPI_BYTE,
                   MPI_COMM_WORLD);
    for (int r = 0; r < n; ++r) all[r].assign(joined.begin() + at[r], joined.begin() + at[r] + sizes[r]);
    return all;
  }
  std::vector<std::pair<int, const Bytes*>> sends;
  std::vector<std::pair<int, Bytes*>> receives;
  for (int r = 0; r < n; ++r) {
    all[r].resize(counts[r]);
    if (counts[r] > 0) receives.push_back({r, &all[r]});
    if (count > 0) sends.push_back({r, &mine});
  }
  send_and_receive(sends, receives);
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
