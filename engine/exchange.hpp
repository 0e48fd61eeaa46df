// What a world split across processes (World::split) needs of the others: the engine states it, and the MPI
// launch (studies/ranks.hpp) provides it, so the engine itself never includes MPI.
#pragma once
#include <cstdint>
#include <cstring>
#include <vector>

namespace mc {

using Bytes = std::vector<std::uint8_t>;

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

// Plain numbers in and out of a byte buffer.
template <class T>
void put_bytes(Bytes& out, const T& value) {
  const std::size_t at = out.size();
  out.resize(at + sizeof(T));
  std::memcpy(out.data() + at, static_cast<const void*>(&value), sizeof(T));
}
template <class T>
T take_bytes(const Bytes& in, std::size_t& at) {
  T value;
  std::memcpy(static_cast<void*>(&value), in.data() + at, sizeof(T));
  at += sizeof(T);
  return value;
}

}  // namespace mc
