// The processes of one MPI launch (mpirun -np N mesocrack ...): this one's rank and their count, for the
// commands that spread independent runs over them (run --realizations). A build without MPI (MESOCRACK_MPI off),
// or a command started without a launcher, is one rank and never touches MPI.
#pragma once
#include <cstdint>
#include <functional>
#include <type_traits>
#include <vector>

#include "engine/exchange.hpp"

namespace mc {

class Ranks {
 public:
  // Joins the launch when the process was started by mpirun (MPI_Init); otherwise one rank. Call once, first.
  static void start(int* argc, char*** argv);
  static const Ranks& world();
  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }
  // Job k of n belongs to rank k mod size: neighbouring seeds go to different ranks.
  bool owns(int k) const { return k % size_ == rank_; }
  // Runs job(k) for each k < n that this rank owns, and gives every rank every job's bytes, in k order: the ranks
  // go on from the same numbers (one rank: the jobs in turn).
  using Job = std::function<std::vector<std::uint8_t>(int k)>;
  std::vector<std::vector<std::uint8_t>> share(int n, const Job& job) const;
  // Ends the whole launch with this exit code (a rank that failed: the others would wait for it forever).
  [[noreturn]] void abort(int code) const;

 private:
  int rank_ = 0, size_ = 1;
  bool joined_ = false;
};

// The launch's processes as the engine's Exchange: one specimen split across them (World::split).
class RanksExchange final : public Exchange {
 public:
  explicit RanksExchange(const Ranks& ranks) : ranks_(ranks) {}
  int rank() const override { return ranks_.rank(); }
  int size() const override { return ranks_.size(); }
  std::vector<Bytes> all_to_all(const std::vector<Bytes>& out) const override;
  std::vector<Bytes> swap(const std::vector<Bytes>& out, const std::vector<std::size_t>& in_sizes) const override;
  std::vector<Bytes> all_gather(const Bytes& mine) const override;
  void max(std::vector<double>& values) const override;
  void sum(std::vector<std::int64_t>& values) const override;

 private:
  const Ranks& ranks_;
};

// Ranks::share for jobs whose result is one plain value (numbers, flags): job(k) returns a T.
template <class T, class F>
std::vector<T> share_values(const Ranks& ranks, int n, F&& job) {
  static_assert(std::is_trivially_copyable_v<T>);
  const auto bytes = ranks.share(n, [&](int k) {
    Bytes b;
    put_bytes(b, static_cast<T>(job(k)));
    return b;
  });
  std::vector<T> out;
  for (const Bytes& b : bytes) {
    std::size_t at = 0;
    out.push_back(take_bytes<T>(b, at));
  }
  return out;
}

}  // namespace mc
