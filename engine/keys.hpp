// The keys of a scene table as plain data, declared once beside what they fill: for each key its name, the member
// it fills, its unit kind, its range, whether it is required (else its default is the member's value in a
// default-made struct), and a line saying what it is and which equation it enters. A model declares its table beside
// its Params (contact_models/, rigid_cell/facet_law.hpp); scene/ walks the tables to read and check a scene, to
// write values back (calibration), and to print the key reference (`mesocrack keys`). Nothing here knows TOML.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace mc {

// The physical kind of a number. A plain number in a scene is taken as SI; a string such as "30 GPa" or "5 mm/s" is
// converted to SI, and its unit must belong to the key's kind.
enum class Unit {
  None,  // dimensionless: plain numbers, or a percentage "50 %"
  Length,
  Time,
  Mass,
  Force,
  Moment,  // N m
  Pressure,
  Density,
  Velocity,
  Acceleration,
  Stiffness,  // N/m
  Energy,
  Angle,             // rad
  Rate,              // 1/s
  Frequency,         // Hz
  EnergyPerArea,     // J/m2 = N/m: fracture energies
  StiffnessPerArea,  // Pa/m = N/m3: an interface's stress per slip
};

// The allowed interval of a number, in SI. Bounds are inclusive unless marked open. Beside it, the interval of the
// values a key usually takes (usual_lo = usual_hi = 0: the usual values of its unit kind, scene/units.cpp): a number
// written without a unit far outside it is more likely a unit left out than meant (scene/ warns about it).
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  bool hi_open = false;
  double usual_lo = 0, usual_hi = 0;

  // This range with the key's usual values [lo, hi].
  constexpr Range usually(double usual_low, double usual_high) const {
    Range r = *this;
    r.usual_lo = usual_low, r.usual_hi = usual_high;
    return r;
  }

  static constexpr Range any() { return {}; }
  static constexpr Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }  // 0 < v
  static constexpr Range non_negative() { return at_least(0.0); }                                            // 0 <= v
  static constexpr Range at_least(double lo) { return {lo, std::numeric_limits<double>::infinity(), false, false}; }
  static constexpr Range closed(double lo, double hi) { return {lo, hi, false, false}; }  // lo <= v <= hi
  static constexpr Range open_fraction() { return {0.0, 1.0, false, true}; }              // 0 <= v < 1

  bool contains(double v) const { return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi); }
};

// A number drawn per pair when it bonds (a bond's strength or modulus): from a normal distribution (mean, std)
// truncated to positive values, or, with a Weibull shape k > 0, from a Weibull distribution of scale λ = mean and
// shape k (Tang 8.4). In a scene: `key` (the mean or λ) with `key_std` or `key_weibull_shape`, not both.
struct Scatter {
  double mean = std::numeric_limits<double>::quiet_NaN();
  double std = 0.0;
  double weibull_shape = 0.0;
};

enum class Need { Optional, Required };

// What a key holds, as kept in its table's struct.
enum class KeyType {
  Real,     // double
  Integer,  // int or std::int64_t (int_bytes)
  Flag,     // bool
  Word,     // one of `words`, kept as the index of an enum (int-sized)
  Text,     // std::string
  Reals,    // std::vector<double>
  Scatter,  // Scatter: the keys `name`, `name_std`, `name_weibull_shape`
};

struct Key {
  static constexpr std::size_t kByHand = std::numeric_limits<std::size_t>::max();

  std::string_view name;
  KeyType type = KeyType::Real;  // of a key read by hand; bound() sets a bound key's from its member
  Unit unit = Unit::None;
  Range range = Range::any();
  Need need = Need::Optional;
  std::string_view when = {};  // where the key applies, when not everywhere: "motion = servo", "2D"
  std::string_view doc = {};      // one line: what it is, and the equation it enters
  std::string_view example = {};  // a value as a scene writes it ("30 GPa"); "" for none
  std::vector<std::string_view> words = {};  // Word: the allowed words, in the order of the enum's values
  bool tangent = false;                      // Real: the member holds tan(value), an angle whose law needs its tangent
  // A key read by hand (at = kByHand): the number its reader falls back to when it is absent (a flag: ≠ 0 is
  // true), and its default in words: the text or word it falls back to, or what the default depends on
  // ("kn", "0.1 R_min").
  std::optional<double> fallback = {};
  std::string_view shown_default = {};
  int count = 0;  // Reals bound to a member: how many (0: any number)

  // Set by bound(): the member filled, as a byte offset into the table's struct.
  std::size_t at = kByHand;
  int int_bytes = 0;

  bool by_hand() const { return at == kByHand; }
};

// The byte offset of member m in any P (P is default-made once to measure it).
template <class P, class T>
std::size_t offset_of(T P::*m) {
  static const P probe{};
  return static_cast<std::size_t>(reinterpret_cast<const char*>(&(probe.*m)) - reinterpret_cast<const char*>(&probe));
}

// k, filling member m of P: its type follows from the member's.
template <class P, class T>
Key bound(T P::*m, Key k) {
  k.at = offset_of(m);
  if constexpr (std::is_same_v<T, double>) {
    k.type = KeyType::Real;
  } else if constexpr (std::is_same_v<T, bool>) {
    k.type = KeyType::Flag;
  } else if constexpr (std::is_same_v<T, int> || std::is_same_v<T, std::int64_t>) {
    k.type = KeyType::Integer, k.int_bytes = sizeof(T);
  } else if constexpr (std::is_enum_v<T>) {
    static_assert(sizeof(T) == sizeof(int), "a Word key's enum is int-sized");
    k.type = KeyType::Word;
  } else if constexpr (std::is_same_v<T, std::string>) {
    k.type = KeyType::Text;
  } else if constexpr (std::is_same_v<T, std::vector<double>>) {
    k.type = KeyType::Reals;
  } else {
    static_assert(std::is_same_v<T, Scatter>, "a key fills a double, bool, int, int64, enum, string, vector or Scatter");
    k.type = KeyType::Scatter;
  }
  return k;
}

// A key that cannot stand with the others of its entry, and why: the table's check says so after reading.
struct KeyProblem {
  std::string key, what;
};

// Keys of which at most one may be given (exactly one when `one_required`), and the sentence that says why.
struct Alternatives {
  std::vector<std::string_view> keys = {};
  bool one_required = false;
  std::string_view why = {};
};

struct KeyTable {
  std::string_view name;   // what `mesocrack keys NAME` prints: "linear", "walls", "run.stop"
  std::string_view title;  // its heading in the reference: "[[contacts]] model = \"linear\"", "[[walls]]"
  std::string_view about;  // a paragraph: what the table declares, after which source
  std::vector<Key> keys;
  std::vector<Alternatives> alternatives = {};
  // After reading, the first key whose value cannot stand with the others (on the table's struct).
  std::function<std::optional<KeyProblem>(const void*)> check = {};
  const void* defaults = nullptr;  // a default-made struct of the table's type: the defaults of bound keys
  std::string_view location = {};  // its key in the table above it, when that is not `name` after its last dot

  // The key called `name` (that applies `when`, for a key declared once per case); std::logic_error when the table
  // declares none (a reader asked for an undeclared key).
  const Key& at(std::string_view name, std::string_view when = {}) const;
  const Key* find(std::string_view name, std::string_view when = {}) const;
  // The bound key that fills the member at byte offset `at` (offset_of), or null.
  const Key* filling(std::size_t at) const;
  // Its key in the table above it.
  std::string_view key() const;
};

// The table of struct P: its defaults are those of P{}, and `check` is given the P read.
template <class P>
KeyTable key_table(std::string_view name, std::string_view title, std::string_view about, std::vector<Key> keys,
                   std::vector<Alternatives> alternatives = {},
                   std::optional<KeyProblem> (*check)(const P&) = nullptr) {
  static const P defaults{};
  KeyTable t{name, title, about, std::move(keys), std::move(alternatives), {}, &defaults, {}};
  if (check) t.check = [check](const void* p) { return check(*static_cast<const P*>(p)); };
  return t;
}

// The keys of `sub`, a table of the member of P at `offset` (offset_of), as keys of P: a model that contains
// another's parameters (a parallel bond's grain contact) declares them once, in the other's table.
std::vector<Key> keys_at(const KeyTable& sub, std::size_t offset);
// a's keys, then b's.
std::vector<Key> joined(std::vector<Key> a, const std::vector<Key>& b);

// The member a bound key fills, in the struct at `obj`.
template <class T>
T& member(void* obj, const Key& k) {
  return *reinterpret_cast<T*>(static_cast<char*>(obj) + k.at);
}
template <class T>
const T& member(const void* obj, const Key& k) {
  return *reinterpret_cast<const T*>(static_cast<const char*>(obj) + k.at);
}

}  // namespace mc
