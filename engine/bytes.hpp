// Plain numbers, and arrays of them, in and out of a byte buffer: checkpoints' contact lists, messages between
// the processes of a split world. Their bytes are their value (fixed-size Eigen vectors, doubles, flags).
#pragma once
#include <cstdint>
#include <cstring>
#include <vector>

namespace mc {

using Bytes = std::vector<std::uint8_t>;

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

// An array: its length, then its elements.
template <class T>
void put_array(Bytes& out, const std::vector<T>& v) {
  put_bytes(out, static_cast<std::uint64_t>(v.size()));
  const std::size_t at = out.size(), bytes = v.size() * sizeof(T);
  out.resize(at + bytes);
  if (bytes > 0) std::memcpy(out.data() + at, static_cast<const void*>(v.data()), bytes);
}
template <class T>
void take_array(const Bytes& in, std::size_t& at, std::vector<T>& v) {
  v.resize(take_bytes<std::uint64_t>(in, at));
  if (!v.empty()) std::memcpy(static_cast<void*>(v.data()), in.data() + at, v.size() * sizeof(T));
  at += v.size() * sizeof(T);
}

}  // namespace mc
