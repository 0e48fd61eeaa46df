#include "engine/archive_bytes.hpp"

#include <cstdint>
#include <string>

namespace mc {

Bytes archive_bytes(const Archive& a) {
  Bytes out;
  auto put_string = [&](const std::string& s) {
    put_bytes(out, static_cast<std::uint64_t>(s.size()));
    out.insert(out.end(), s.begin(), s.end());
  };
  put_bytes(out, static_cast<std::uint64_t>(a.reals.size()));
  for (const auto& [key, values] : a.reals) {
    put_string(key);
    put_bytes(out, static_cast<std::uint64_t>(values.size()));
    for (double v : values) put_bytes(out, v);
  }
  put_bytes(out, static_cast<std::uint64_t>(a.bytes.size()));
  for (const auto& [key, values] : a.bytes) {
    put_string(key);
    put_bytes(out, static_cast<std::uint64_t>(values.size()));
    out.insert(out.end(), values.begin(), values.end());
  }
  return out;
}

Archive archive_of(const Bytes& in) {
  Archive a;
  std::size_t at = 0;
  auto take_string = [&] {
    const auto n = take_bytes<std::uint64_t>(in, at);
    std::string s(in.begin() + static_cast<std::ptrdiff_t>(at), in.begin() + static_cast<std::ptrdiff_t>(at + n));
    at += n;
    return s;
  };
  for (auto n = take_bytes<std::uint64_t>(in, at); n > 0; --n) {
    const std::string key = take_string();
    auto& values = a.reals[key];
    values.resize(take_bytes<std::uint64_t>(in, at));
    for (double& v : values) v = take_bytes<double>(in, at);
  }
  for (auto n = take_bytes<std::uint64_t>(in, at); n > 0; --n) {
    const std::string key = take_string();
    const auto size = take_bytes<std::uint64_t>(in, at);
    a.bytes[key].assign(in.begin() + static_cast<std::ptrdiff_t>(at),
                        in.begin() + static_cast<std::ptrdiff_t>(at + size));
    at += size;
  }
  return a;
}

}  // namespace mc
