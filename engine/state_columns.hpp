// A contact set's per-pair states. A model may split its State into a History, which a force pass rewrites every
// step, and Properties, drawn once when the pair bonds (strengths, stiffness factor) and only read by the force
// pass and the timestep estimate: State then derives from both, and the two parts live in two arrays. Beyond the
// caches a step's time goes with the bytes it moves, and a force pass that never writes the properties' array
// sends none of it back to memory; the timestep estimate reads the properties alone.
// Whole or split, a state travels as the bytes of one State (checkpoints, a split world's messages).
#pragma once
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

#include "engine/bytes.hpp"

namespace mc {

template <class Model, int D>
concept HasStateParts = requires {
  typename Model::template History<D>;
  typename Model::template Properties<D>;
};
template <class Model, int D>
constexpr bool state_derives_from_parts() {
  using State = typename Model::template State<D>;
  return std::is_base_of_v<typename Model::template History<D>, State> &&
         std::is_base_of_v<typename Model::template Properties<D>, State>;
}
template <class Model, int D>
concept SplitState = HasStateParts<Model, D> && state_derives_from_parts<Model, D>();

struct NoProperties {};

template <class Model, int D, bool = SplitState<Model, D>>
struct StateParts {
  using History = typename Model::template State<D>;
  using Properties = NoProperties;
};
template <class Model, int D>
struct StateParts<Model, D, true> {
  using History = typename Model::template History<D>;
  using Properties = typename Model::template Properties<D>;
};

template <class Model, int D>
class StateColumns {
 public:
  using State = typename Model::template State<D>;
  using History = typename StateParts<Model, D>::History;
  using Properties = typename StateParts<Model, D>::Properties;
  static constexpr bool kSplit = SplitState<Model, D>;
  static_assert(!kSplit || sizeof(State) == sizeof(History) + sizeof(Properties),
                "a split State's bytes are its history's, then its properties'");

  std::size_t size() const { return history_.size(); }
  // Where contact c's parts start, for a model's lanes (engine/lanes.hpp); no properties unless split.
  History* history(std::size_t c) { return history_.data() + c; }
  const Properties* properties(std::size_t c) const {
    if constexpr (kSplit)
      return properties_.data() + c;
    else
      return nullptr;
  }

  State get(std::size_t c) const {
    if constexpr (kSplit) {
      State s;
      static_cast<History&>(s) = history_[c];
      static_cast<Properties&>(s) = properties_[c];
      return s;
    } else {
      return history_[c];
    }
  }
  // The properties' array is written only where they changed (a bond made or broken), so that their cache lines
  // stay clean.
  void set(std::size_t c, const State& s) {
    history_[c] = s;
    if constexpr (kSplit) {
      const Properties& p = s;
      if (std::memcmp(static_cast<const void*>(&p), static_cast<const void*>(&properties_[c]), sizeof p) != 0)
        properties_[c] = p;
    }
  }
  void push_back(const State& s) {
    history_.push_back(s);
    if constexpr (kSplit) properties_.push_back(s);
  }
  void copy(std::size_t from, std::size_t to) {
    history_[to] = history_[from];
    if constexpr (kSplit) properties_[to] = properties_[from];
  }
  void reserve(std::size_t n) {
    history_.reserve(n);
    if constexpr (kSplit) properties_.reserve(n);
  }
  void resize(std::size_t n) {
    history_.resize(n);
    if constexpr (kSplit) properties_.resize(n);
  }
  void swap(StateColumns& other) {
    history_.swap(other.history_);
    properties_.swap(other.properties_);
  }
  std::size_t history_bytes() const { return history_.capacity() * sizeof(History); }
  std::size_t capacity_bytes() const { return history_bytes() + properties_.capacity() * sizeof(Properties); }

  // The bytes of one State, appended; and a State from such bytes.
  void append_bytes(std::size_t c, Bytes& out) const {
    const State s = get(c);
    const auto* b = reinterpret_cast<const std::uint8_t*>(&s);
    out.insert(out.end(), b, b + sizeof(State));
  }
  static State from_bytes(const std::uint8_t* in) {
    State s;
    std::memcpy(static_cast<void*>(&s), in, sizeof(State));
    return s;
  }
  // As put_array and take_array (bytes.hpp) of a std::vector<State>: the same bytes, split or whole.
  void put(Bytes& out) const {
    if constexpr (kSplit) {
      put_bytes(out, static_cast<std::uint64_t>(size()));
      out.reserve(out.size() + size() * sizeof(State));
      for (std::size_t c = 0; c < size(); ++c) append_bytes(c, out);
    } else {
      put_array(out, history_);
    }
  }
  void take(const Bytes& in, std::size_t& at) {
    if constexpr (kSplit) {
      const auto n = take_bytes<std::uint64_t>(in, at);
      history_.clear(), properties_.clear();
      reserve(n);
      for (std::uint64_t c = 0; c < n; ++c, at += sizeof(State)) push_back(from_bytes(in.data() + at));
    } else {
      take_array(in, at, history_);
    }
  }

 private:
  std::vector<History> history_;
  std::vector<Properties> properties_;  // empty unless split
};

}  // namespace mc
