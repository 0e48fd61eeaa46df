// A named bag of arrays: what a checkpoint holds, independent of the file format that stores it.
#pragma once
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "engine/errors.hpp"

namespace mc {

struct Archive {
  std::map<std::string, std::vector<double>> reals;
  std::map<std::string, std::vector<std::uint8_t>> bytes;

  // Arrays of fixed-size Eigen vectors (or any plain numbers) stored as doubles.
  template <class T>
  void put(const std::string& key, const std::vector<T>& v) {
    static_assert(sizeof(T) % sizeof(double) == 0);
    std::vector<double> d(v.size() * (sizeof(T) / sizeof(double)));
    if (!v.empty()) std::memcpy(d.data(), v.data(), d.size() * sizeof(double));
    reals[key] = std::move(d);
  }
  template <class T>
  void get(const std::string& key, std::vector<T>& v) const {
    const auto& d = at(reals, key);
    v.resize(d.size() / (sizeof(T) / sizeof(double)));
    if (!d.empty()) std::memcpy(static_cast<void*>(v.data()), d.data(), d.size() * sizeof(double));
  }
  void put_scalar(const std::string& key, double x) { reals[key] = {x}; }
  double scalar(const std::string& key) const { return at(reals, key).at(0); }

 private:
  template <class M>
  static const typename M::mapped_type& at(const M& m, const std::string& key) {
    const auto it = m.find(key);
    if (it == m.end()) throw IoError("checkpoint is missing '" + key + "'");
    return it->second;
  }
};

}  // namespace mc
