// The physical units of scene-file numbers: the conversion of a number written with a unit ("30 GPa") to SI, and the
// words that describe a unit kind (Unit) and an interval (Range) in messages.
#pragma once
#include <cstddef>
#include <limits>
#include <string>

#include "engine/keys.hpp"

namespace mc {

// Unit and Range are declared with the keys (engine/keys.hpp): the models' key tables state them.

// A range in words, e.g. "0 <= value < 1", "value > 0 Pa".
std::string describe(const Range& r, const std::string& unit = "");

namespace detail {

// A number-with-unit string converted to SI, or the reason it is not one (error is empty on success).
struct Quantity {
  double si = 0.0;
  std::string error;
};

// "30 GPa" -> 3e10 for Unit::Pressure; a number without a unit is taken as SI. A number out of double range
// converts to infinity, for the caller to reject as non-finite.
Quantity quantity(const std::string& text, Unit u);

// What a warning says of the number x of kind u written without a unit, when it lies more than 100 times outside the
// usual values of its key (Range::usually) or of its kind (a bare angle: beyond a turn); "" when it does not.
std::string unusual_bare_number(double x, Unit u, const Range& r);

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
