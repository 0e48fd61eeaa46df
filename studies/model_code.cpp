#include "studies/model_code.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "engine/errors.hpp"
#include "scene/json.hpp"

namespace mc {

namespace {

constexpr double kMPa = 1e6;
constexpr double kDeltaF = 8.0;    // MPa, (5.1-1)
constexpr double kEc0 = 21.5e3;    // MPa, (5.1-21)

// f_ck and f_ck,cube [MPa] of each strength class (§5.1.4).
const std::vector<std::pair<int, int>>& classes() {
  static const std::vector<std::pair<int, int>> c{{12, 15},  {16, 20},  {20, 25},  {25, 30},  {30, 37},  {35, 45},
                                                  {40, 50},  {45, 55},  {50, 60},  {55, 67},  {60, 75},  {70, 85},
                                                  {80, 95},  {90, 105}, {100, 115}, {110, 130}, {120, 140}};
  return c;
}

std::string class_name(const std::pair<int, int>& c) {
  return "C" + std::to_string(c.first) + "/" + std::to_string(c.second);
}

std::string listed(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

}  // namespace

std::vector<std::string> model_code_classes() {
  std::vector<std::string> names;
  for (const auto& c : classes()) names.push_back(class_name(c));
  return names;
}

std::vector<std::pair<std::string, double>> model_code_aggregates() {
  return {{"basalt", 1.2}, {"quartzite", 1.0}, {"limestone", 0.9}, {"sandstone", 0.7}};
}

ModelCodeConcrete model_code_concrete(const std::string& strength_class, const std::string& aggregate) {
  ModelCodeConcrete m;
  for (const auto& c : classes())
    if (class_name(c) == strength_class || "C" + std::to_string(c.first) == strength_class) {
      m.name = class_name(c);
      m.f_ck = c.first;
      m.f_ck_cube = c.second;
    }
  if (m.name.empty())
    throw InputError("concrete class '" + strength_class + "': not a class of the fib Model Code 2010; "
                     "allowed: " + listed(model_code_classes()) + " (or C12 … C120)");
  std::vector<std::string> aggregates;
  for (const auto& [name, alpha] : model_code_aggregates()) {
    aggregates.push_back(name);
    if (name == aggregate) m.alpha_e = alpha, m.aggregate = name;
  }
  if (m.aggregate.empty())
    throw InputError("aggregate '" + aggregate + "': not one of the fib Model Code 2010's (Table 5.1-6); allowed: " +
                     listed(aggregates));
  const double fck = m.f_ck, fcm = fck + kDeltaF;
  m.f_cm = fcm * kMPa;
  m.f_ctm = (fck <= 50 ? 0.3 * std::pow(fck, 2.0 / 3.0) : 2.12 * std::log(1 + 0.1 * fcm)) * kMPa;  // (5.1-3a/b)
  m.f_ctk_min = 0.7 * m.f_ctm;
  m.f_ctk_max = 1.3 * m.f_ctm;
  m.fracture_energy = 73 * std::pow(fcm, 0.18);                               // (5.1-9), N/m
  m.e_ci = kEc0 * m.alpha_e * std::cbrt(fcm / 10) * kMPa;                     // (5.1-21)
  m.e_c = std::min(0.8 + 0.2 * fcm / 88, 1.0) * m.e_ci;                       // (5.1-23, 5.1-24)
  m.f_ck *= kMPa;
  m.f_ck_cube *= kMPa;
  return m;
}

std::string model_code_json(const ModelCodeConcrete& m) {
  const std::pair<const char*, double> values[] = {
      {"f_ck", m.f_ck},           {"f_ck_cube", m.f_ck_cube},         {"f_cm", m.f_cm},
      {"f_ctm", m.f_ctm},         {"f_ctk_min", m.f_ctk_min},         {"f_ctk_max", m.f_ctk_max},
      {"G_F", m.fracture_energy}, {"E_ci", m.e_ci},                   {"E_c", m.e_c},
      {"nu", m.poisson},          {"alpha_E", m.alpha_e}};
  std::string j = "{\n  \"class\": " + json_quote(m.name) + ",\n  \"aggregate\": " + json_quote(m.aggregate) + ",\n";
  for (const auto& [name, value] : values) j += "  \"" + std::string(name) + "\": " + json_number(value) + ",\n";
  j += "  \"units\": {\"f_*\": \"Pa\", \"G_F\": \"N/m\", \"E_*\": \"Pa\", \"nu\": \"-\", \"alpha_E\": \"-\"},\n";
  j += "  \"source\": \"fib Model Code 2010, 5.1: f_cm = f_ck + 8 MPa, f_ctm = 0.3 f_ck^(2/3) (to C50; beyond, "
       "2.12 ln(1 + f_cm/10)), f_ctk = 0.7 and 1.3 f_ctm, G_F = 73 f_cm^0.18, E_ci = 21.5 GPa alpha_E (f_cm/10)^(1/3), "
       "E_c = (0.8 + 0.2 f_cm/88) E_ci\",\n";
  j += "  \"calibrate\": " + json_quote("--target class=" + m.name + (m.aggregate == "quartzite" ? "" : ",aggregate=" +
                                       m.aggregate)) + "\n}\n";
  return j;
}

}  // namespace mc
