// What a world split across processes (World::split) needs of the others: the engine states it, and the MPI
// launch (studies/ranks.hpp) provides it, so the engine itself never includes MPI.
#pragma once
#include <cstdint>
#include <vector>

#include "engine/bytes.hpp"

namespace mc {

class Exchange {
 public:
  virtual ~Exchange() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  // Sends out[r] to rank r (out has size() entries) and returns what each rank sent to this one, by rank.
  virtual std::vector<Bytes> all_to_all(const std::vector<Bytes>& out) const = 0;
  // The same when this rank knows how many bytes each rank sends it (in_sizes): one exchange instead of two.
  virtual std::vector<Bytes> swap(const std::vector<Bytes>& out, const std::vector<std::size_t>& in_sizes) const = 0;
  // Every rank's bytes, by rank, on every rank.
  virtual std::vector<Bytes> all_gather(const Bytes& mine) const = 0;
  // Element-wise maximum over the ranks, in place (the same array length on every rank). Exact: a maximum does
  // not depend on the order it is taken in.
  virtual void max(std::vector<double>& values) const = 0;
  // Element-wise sum over the ranks, in place: integers, so exact in any order.
  virtual void sum(std::vector<std::int64_t>& values) const = 0;
};

}  // namespace mc
