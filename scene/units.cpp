#include "scene/units.hpp"

#include <charconv>
#include <numbers>
#include <optional>
#include <string_view>
#include <system_error>
#include <tuple>
#include <vector>

#include "engine/dim.hpp"  // kInf
#include "scene/text.hpp"

namespace mc {

namespace detail {
namespace {

struct UnitDef {
  std::string_view name;
  Unit kind;
  int pow10;  // decimal prefix, applied to the exponent so that "5 mm/s" gives exactly 0.005
  double mul = 1.0;
  double div = 1.0;
};

constexpr UnitDef kUnits[] = {
    {"m", Unit::Length, 0},
    {"cm", Unit::Length, -2},
    {"mm", Unit::Length, -3},
    {"um", Unit::Length, -6},
    {"s", Unit::Time, 0},
    {"ms", Unit::Time, -3},
    {"us", Unit::Time, -6},
    {"min", Unit::Time, 0, 60.0},
    {"h", Unit::Time, 0, 3600.0},
    {"kg", Unit::Mass, 0},
    {"g", Unit::Mass, -3},
    {"t", Unit::Mass, 3},
    {"N", Unit::Force, 0},
    {"kN", Unit::Force, 3},
    {"MN", Unit::Force, 6},
    {"N*m", Unit::Moment, 0},
    {"N m", Unit::Moment, 0},
    {"kN*m", Unit::Moment, 3},
    {"kN m", Unit::Moment, 3},
    {"Pa", Unit::Pressure, 0},
    {"kPa", Unit::Pressure, 3},
    {"MPa", Unit::Pressure, 6},
    {"GPa", Unit::Pressure, 9},
    {"kg/m3", Unit::Density, 0},
    {"g/cm3", Unit::Density, 3},
    {"t/m3", Unit::Density, 3},
    {"m/s", Unit::Velocity, 0},
    {"mm/s", Unit::Velocity, -3},
    {"mm/min", Unit::Velocity, -3, 1.0, 60.0},
    {"um/s", Unit::Velocity, -6},
    {"m/s2", Unit::Acceleration, 0},
    {"N/m", Unit::Stiffness, 0},
    {"kN/m", Unit::Stiffness, 3},
    {"MN/m", Unit::Stiffness, 6},
    {"GN/m", Unit::Stiffness, 9},
    {"N/mm", Unit::Stiffness, 3},
    {"J", Unit::Energy, 0},
    {"N*m", Unit::Energy, 0},
    {"mJ", Unit::Energy, -3},
    {"rad", Unit::Angle, 0},
    {"deg", Unit::Angle, 0, std::numbers::pi, 180.0},
    {"1/s", Unit::Rate, 0},
    {"/s", Unit::Rate, 0},
    {"Hz", Unit::Frequency, 0},
    {"kHz", Unit::Frequency, 3},
    {"%", Unit::None, -2},
    {"Pa/m", Unit::StiffnessPerArea, 0},
    {"N/m3", Unit::StiffnessPerArea, 0},
    {"MPa/m", Unit::StiffnessPerArea, 6},
    {"GPa/m", Unit::StiffnessPerArea, 9},
    {"MPa/mm", Unit::StiffnessPerArea, 9},
    {"N/mm3", Unit::StiffnessPerArea, 9},
    // Last: a unit of two kinds ("N/m") is named in messages by its first, the stiffness.
    {"J/m2", Unit::EnergyPerArea, 0},
    {"N/m", Unit::EnergyPerArea, 0},
};

struct KindDef {
  std::string_view noun;  // with its article, for "is a length, not an acceleration"
  std::string_view si;
  std::string_view number_example;
  std::string_view string_example;
};

const KindDef& kind_def(Unit u) {
  static constexpr KindDef defs[] = {
      {"a dimensionless number", "", "0.5", "50 %"},
      {"a length", "m", "0.002", "2 mm"},
      {"a time", "s", "1e-6", "1 us"},
      {"a mass", "kg", "0.5", "500 g"},
      {"a force", "N", "1000", "1 kN"},
      {"a moment", "N m", "10", "10 N*m"},
      {"a pressure", "Pa", "3e10", "30 GPa"},
      {"a density", "kg/m3", "2600", "2.6 g/cm3"},
      {"a velocity", "m/s", "0.005", "5 mm/s"},
      {"an acceleration", "m/s2", "9.81", "9.81 m/s2"},
      {"a stiffness", "N/m", "1e6", "1 MN/m"},
      {"an energy", "J", "0.001", "1 mJ"},
      {"an angle", "rad", "0.785", "45 deg"},
      {"a rate", "1/s", "0.1", "0.1 /s"},
      {"a frequency", "Hz", "1000", "1 kHz"},
      {"an energy per area", "J/m2", "100", "100 N/m"},
      {"a stiffness per area", "Pa/m", "2e11", "200 MPa/mm"},
  };
  return defs[static_cast<int>(u)];
}

// " in Pa" after "a number" for a quantity; nothing for a plain number.
std::string in_si(Unit u) { return u == Unit::None ? "" : " in " + si_unit(u); }

std::string allowed_units(Unit u) {
  if (u == Unit::None) return "a plain number or %";
  std::vector<std::string> names;
  for (const auto& d : kUnits)
    if (d.kind == u) names.emplace_back(d.name);
  return join_list(names, " or ");
}

const UnitDef* find_unit(std::string_view name, std::optional<Unit> kind) {
  for (const auto& d : kUnits)
    if (d.name == name && (!kind || d.kind == *kind)) return &d;
  return nullptr;
}

std::string unit_mismatch(const std::string& unit, Unit u) {
  const UnitDef* other = find_unit(unit, std::nullopt);
  const std::string noun(kind_def(u).noun);
  const std::string is = other ? "is " + std::string(kind_def(other->kind).noun) + ", not " + noun : "is not " + noun;
  return "unit '" + shorten(printable(unit)) + "' " + is + "; use " + allowed_units(u);
}

// The decimal exponent is shifted rather than the value multiplied, so a quantity converts exactly as if
// the user had written it in SI ("0.01 mm/s" == 1e-5, "30 GPa" == 3e10).
double scaled(std::string num, const UnitDef& d) {
  int exponent = 0;
  if (const auto e = num.find_first_of("eE"); e != std::string::npos) {
    const char* first = num.data() + e + 1 + (num[e + 1] == '+');
    if (std::from_chars(first, num.data() + num.size(), exponent).ec != std::errc{}) return kInf;
    num.resize(e);
  }
  num += 'e';  // two appends: GCC 12 warns falsely (-Wrestrict) on "e" + std::to_string(...) here
  num += std::to_string(exponent + d.pow10);
  double x = 0.0;
  // Out of double range: report as non-finite rather than keep from_chars' untouched 0.
  if (std::from_chars(num.data(), num.data() + num.size(), x).ec != std::errc{}) return kInf;
  return x * d.mul / d.div;
}

}  // namespace

Quantity quantity(const std::string& text, Unit u) {
  const std::string s = trim(text);
  if (s.empty()) return {0.0, expected_number(u)};
  const char* first = s.data() + (s[0] == '+');  // from_chars refuses a leading '+'
  const char* last = s.data() + s.size();
  double ignored = 0.0;
  const auto [end, ec] = std::from_chars(first, last, ignored);
  if (ec == std::errc::invalid_argument) return {0.0, expected_number(u)};
  const std::string unit = trim(std::string(end, last));
  static constexpr UnitDef si{"", Unit::None, 0};
  const UnitDef* def = unit.empty() ? &si : find_unit(unit, u);
  if (!def) return {0.0, unit_mismatch(unit, u)};
  return {scaled(std::string(first, end), *def), ""};
}

std::string format_number(double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

std::string si_unit(Unit u) { return std::string(kind_def(u).si); }

std::string number_hint(Unit u) {
  const auto& k = kind_def(u);
  return "a number" + in_si(u) + ", e.g. " + std::string(k.number_example) + " or \"" + std::string(k.string_example) +
         "\"";
}

std::string array_hint(Unit u, std::size_t n) {
  const std::string count = n > 0 ? std::to_string(n) + " " : "";
  return "an array of " + count + "numbers" + in_si(u);
}

std::string expected_number(Unit u) {
  if (u == Unit::None) return "expected a number (or a percentage such as \"50 %\")";
  return "expected a number in " + si_unit(u) + " (or a string with a unit such as \"" +
         std::string(kind_def(u).string_example) + "\")";
}

std::string expected_finite_number(Unit u) { return "expected a finite number" + in_si(u); }

}  // namespace detail

namespace detail {
namespace {

// The values numbers of a kind usually take in a meso-scale model of concrete (SI), and a unit a user who meant
// other than SI would likely have written.
struct Usual {
  Unit kind;
  double lo, hi;
  std::string_view instead;
};
constexpr Usual kUsual[] = {
    {Unit::Length, 1e-6, 1.0, "mm"},          // a particle of microns to a specimen of a metre
    {Unit::Time, 1e-9, 1e3, "ms"},            // a timestep to a long creep of loading
    {Unit::Mass, 1e-12, 1e3, "g"},            //
    {Unit::Force, 1e-3, 1e7, "kN"},           //
    {Unit::Moment, 1e-6, 1e5, "kN m"},        //
    {Unit::Pressure, 1e4, 1e11, "MPa"},       // a confinement of kPa to an aggregate's modulus
    {Unit::Density, 300.0, 2e4, "g/cm3"},     // foamed concrete to steel fibres
    {Unit::Velocity, 1e-8, 100.0, "mm/s"},    // a creeping platen to an impact
    {Unit::Acceleration, 0.1, 1e3, "m/s2"},   //
    {Unit::Stiffness, 1.0, 1e13, "kN/m"},     //
    {Unit::Energy, 1e-9, 1e4, "mJ"},          //
    {Unit::Angle, 0.0, 2 * std::numbers::pi, "deg"},  // any bare angle beyond a turn: degrees meant
    {Unit::Rate, 1e-6, 1e4, "1/s"},           //
    {Unit::Frequency, 1e-3, 1e9, "kHz"},      //
    {Unit::EnergyPerArea, 1.0, 1e4, "J/m2"},  // a mortar's fracture energy to an FRP bond's
    {Unit::StiffnessPerArea, 1e6, 1e14, "MPa/mm"},  // a soft adhesive's shear stiffness to a steel bar's rib
};

}  // namespace

std::string unusual_bare_number(double x, Unit u, const Range& r) {
  const Usual* usual = nullptr;
  for (const Usual& k : kUsual)
    if (k.kind == u) usual = &k;
  if (!usual || x == 0) return "";
  const bool declared = r.usual_lo != 0 || r.usual_hi != 0;
  const double lo = declared ? r.usual_lo : usual->lo, hi = declared ? r.usual_hi : usual->hi;
  const double factor = u == Unit::Angle ? 1.0 : 100.0;  // Angle: a turn is the bound itself
  const double m = std::abs(x);
  if (m >= lo / factor && m <= hi * factor) return "";
  const std::string why = u == Unit::Angle ? "more than a turn"
                          : m > hi         ? "more than 100 times the usual"
                                           : "less than 1/100 of the usual";
  return "has no unit, so it is read as " + format_number(x) + " " + si_unit(u) + " (SI), " + why +
         (u == Unit::Angle ? "" : " values " + format_number(lo) + " to " + format_number(hi) + " " + si_unit(u)) +
         "; if another unit was meant, write it (e.g. \"" + format_number(x) + " " + std::string(usual->instead) +
         "\")";
}

}  // namespace detail

std::string describe(const Range& r, const std::string& unit) {
  const auto [lo, hi, lo_open, hi_open] = std::tuple{r.lo, r.hi, r.lo_open, r.hi_open};
  const auto bound = [&](double x) { return detail::format_number(x) + (unit.empty() ? "" : " " + unit); };
  const bool has_lo = lo > -kInf;
  const bool has_hi = hi < kInf;
  if (has_lo && has_hi)
    return bound(lo) + (lo_open ? " < " : " <= ") + "value" + (hi_open ? " < " : " <= ") + bound(hi);
  if (has_lo) return std::string("value ") + (lo_open ? "> " : ">= ") + bound(lo);
  if (has_hi) return std::string("value ") + (hi_open ? "< " : "<= ") + bound(hi);
  return "any value";
}

}  // namespace mc
