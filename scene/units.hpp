// The physical units of scene-file numbers: the kind a key has (Unit), the interval it allows (Range), the
// conversion of a number written with a unit ("30 GPa") to SI, and the words that describe a kind in messages.
#pragma once
#include <cstddef>
#include <limits>
#include <string>

namespace mc {

// The physical kind of a number. A plain TOML number is taken as SI; a string such as "30 GPa" or "5 mm/s" is
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
  Angle,          // rad
  Rate,           // 1/s
  Frequency,      // Hz
  EnergyPerArea,  // J/m2 = N/m: fracture energies
};

// The allowed interval of a number, in SI. Bounds are inclusive unless marked open.
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  bool hi_open = false;

  static Range any() { return {}; }
  static Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }  // 0 < v
  static Range non_negative() { return at_least(0.0); }                                            // 0 <= v
  static Range at_least(double lo) { return {lo, std::numeric_limits<double>::infinity(), false, false}; }
  static Range closed(double lo, double hi) { return {lo, hi, false, false}; }  // lo <= v <= hi
  static Range open_fraction() { return {0.0, 1.0, false, true}; }              // 0 <= v < 1

  bool contains(double v) const;
  std::string describe(const std::string& unit = "") const;  // e.g. "0 <= value < 1", "value > 0 Pa"
};

namespace detail {

// A number-with-unit string converted to SI, or the reason it is not one (error is empty on success).
struct Quantity {
  double si = 0.0;
  std::string error;
};

// "30 GPa" -> 3e10 for Unit::Pressure; a number without a unit is taken as SI. A number out of double range
// converts to infinity, for the caller to reject as non-finite.
Quantity quantity(const std::string& text, Unit u);

// The shortest text that reads back as x: 0.1, 3e+10.
std::string format_number(double x);

// The SI unit values of kind u are compared and reported in: "Pa", "m/s"; "" for Unit::None.
std::string si_unit(Unit u);

// The phrases of messages about a number of kind u:
std::string number_hint(Unit u);                // a missing key: a number in kg/m3, e.g. 2600 or "2.6 g/cm3"
std::string array_hint(Unit u, std::size_t n);  // an array of 3 numbers in m (n = 0: of any length)
std::string expected_number(Unit u);            // a value that is no number: expected a number in Pa (or ...)
std::string expected_finite_number(Unit u);     // inf, nan, or a quantity beyond double range

}  // namespace detail
}  // namespace mc
