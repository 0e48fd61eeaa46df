#include "scene/analyses/uniaxial.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "engine/errors.hpp"
#include "scene/analyses/records.hpp"
#include "scene/json.hpp"
#include "scene/scene.hpp"

namespace mc {

const KeyTable& uniaxial_keys() {
  static const KeyTable t{
      .name = "uniaxial",
      .title = "[uniaxial]: the uniaxial test (Tang ch. 5, Šmilauer's calibration test)",
      .about = "Compression or tension of a specimen between platens (walls, whose histories it names) or its own "
               "bonded end layers (two [[groups]], `supports`). It records uniaxial.inside_strain (the regression "
               "of the axial displacements on the axial positions of the middle half of the specimen, free of the "
               "platens' give) and, with supports, uniaxial.stress, .strain, .length and .lateral_strain; summary "
               "adds E (secant 25-50 % of the peak), ν, the strength, the strain at the peak, in tension G_f, the "
               "crack-initiation stress and the crack counts. Needs [bonds].",
      .keys = {
          {.name = "loading", .type = KeyType::Word, .doc = "compression or tension", .words = {"compression", "tension"},
           .shown_default = "compression"},
          {.name = "axis", .type = KeyType::Word, .doc = "the strained axis", .words = {"x", "y", "z"}, .shown_default = "y in 2D, z in 3D"},
          {.name = "axial_strain_from", .type = KeyType::Word,
           .doc = "platens (the named axial_strain, or the supports') or inside: the strain E and ν are read from; "
                  "summary gives both as E_platens, nu_platens, E_inside, nu_inside",
           .words = {"platens", "inside"},
           .shown_default = "platens with supports, else inside"},
          {.name = "plane", .type = KeyType::Word,
           .when = "2D",
           .doc = "strain (Tang ch. 5: ν = ν₂/(1 + ν₂), E = E₂(1 − ν²) from the disc assembly's own E₂, ν₂) or "
                  "stress (the ratios as they are)",
           .words = {"strain", "stress"},
           .shown_default = "strain"},
          {.name = "supports", .type = KeyType::Text,
           .doc = "\"bottom top\": two [[groups]] at the negative and positive end of the axis that strain the "
                  "specimen"},
          {.name = "area", .unit = Unit::Length, .range = Range::positive(), .when = "2D",
           .doc = "with supports: the cross-section the reactions are divided by [m, per unit thickness]",
           .shown_default = "the specimen's bounding box's"},
          {.name = "area", .range = Range::positive(), .when = "3D",
           .doc = "with supports: the cross-section the reactions are divided by [m²]",
           .shown_default = "the specimen's bounding box's"},
          {.name = "stress", .type = KeyType::Text, .need = Need::Required, .when = "without supports",
           .doc = "the history of the axial stress (signs free: the loading sense is taken positive)"},
          {.name = "axial_strain", .type = KeyType::Text, .need = Need::Required, .when = "without supports", .doc = "the history of the axial strain"},
          {.name = "lateral_strain", .type = KeyType::Text, .need = Need::Required, .when = "without supports",
           .doc = "the lateral strain histories, separated by spaces, whose mean is taken (3D: both lateral axes)"},
      }};
  return t;
}

std::string UniaxialAnalysis::name() const { return std::string(uniaxial_keys().name); }

std::shared_ptr<const Analysis> read_uniaxial(const KeyReader& k, const Scene& s) {
  auto u = std::make_shared<UniaxialAnalysis>();
  u->scene_file = s.file;
  u->tension = k.choice("loading") == "tension";
  u->dimension = s.dimension;
  const std::string axis =
      k.choice("axis", s.dimension == 2 ? std::vector<std::string>{"x", "y"} : std::vector<std::string>{"x", "y", "z"},
               s.dimension == 2 ? "y" : "z");
  u->axis = axis[0] - 'x';
  // Platens touch the specimen through unbonded contacts whose give enters their gap: E read from it rises with
  // L/R (3D: +23 % from L/R 15 to 25, against +15 % inside; 2D from 40 to 120: +10 % against +1 %), so inside is
  // the default. Supports are the specimen's own bonded end layers, and their strain is Šmilauer's definition.
  const bool supported = k.has("supports");
  u->strain_inside = k.choice("axial_strain_from", supported ? "platens" : "inside") == "inside";
  if (s.dimension == 2)
    u->plane_strain = k.choice("plane") == "strain";
  else if (k.has("plane"))
    k.fail("plane", "a 3D specimen gives E and ν directly; the plane reading is for 2D specimens");
  if (k.has("supports")) {
    // supports = "bottom top": the groups at the negative and the positive end of the strained axis.
    for (const char* key : {"stress", "axial_strain", "lateral_strain"})
      if (k.has(key)) k.fail(key, "given together with 'supports', which defines the uniaxial.* histories itself");
    std::stringstream ss(k.string("supports"));
    std::vector<std::string> two;
    for (std::string n; ss >> n;) two.push_back(n);
    if (two.size() != 2)
      k.fail("supports", "give the names of two groups, the negative end first, separated by a space");
    for (int i = 0; i < 2; ++i) {
      for (std::size_t g = 0; g < s.groups.size(); ++g)
        if (s.groups[g].name == two[i]) u->supports[i] = static_cast<int>(g);
      if (u->supports[i] < 0) k.fail("supports", "'" + two[i] + "' is not the name of a [[groups]] entry");
      u->support_names[i] = two[i];
    }
    u->area = k.number(k.key("area", s.dimension == 2 ? "2D" : "3D"), 0.0);
    u->stress = "uniaxial.stress", u->axial_strain = "uniaxial.strain", u->lateral_strain = {"uniaxial.lateral_strain"};
  } else {
    u->stress = k.string("stress");
    u->axial_strain = k.string("axial_strain");
    std::istringstream names(k.string("lateral_strain"));
    for (std::string n; names >> n;) u->lateral_strain.push_back(n);
    if (u->lateral_strain.empty()) k.fail("lateral_strain", "give one or more history names, separated by spaces");
  }
  return u;
}

void UniaxialAnalysis::check(const KeyReader& k, const Scene& s, const std::vector<std::string>& histories) const {
  std::string list;
  for (const auto& h : histories) list += (list.empty() ? "" : ", ") + h;
  std::vector<std::pair<std::string, std::string>> named{{"stress", stress}, {"axial_strain", axial_strain}};
  for (const auto& n : lateral_strain) named.push_back({"lateral_strain", n});
  for (const auto& [key, name] : named)
    if (std::find(histories.begin(), histories.end(), name) == histories.end())
      k.fail(key, "'" + name + "' is not a history of this scene; recorded: " + list);
  if (s.bond_tolerance < 0) k.fail("stress", "the crack-initiation stress needs bonds: declare [bonds]");
}

void UniaxialAnalysis::add_histories(std::vector<Series>& out, const Observed<2>& o) const {
  if (supports[0] >= 0) add_support_histories<2>(out, o);
  add_inside_strain<2>(out, o);
}
void UniaxialAnalysis::add_histories(std::vector<Series>& out, const Observed<3>& o) const {
  if (supports[0] >= 0) add_support_histories<3>(out, o);
  add_inside_strain<3>(out, o);
}

namespace {

// The specimen as the supports hold it at the start: their members, the particles of the middle half of its
// length (away from the boundary effects at the supports), every position, the gauge length and the area.
template <int D>
struct SupportSetup {
  std::vector<int> lo, hi, inner;
  std::vector<Vec<D>> x0;
  double length0 = 0, area = 0;
};

template <int D>
double mean_along(const std::vector<int>& members, const std::vector<Vec<D>>& x, int axis) {
  double z = 0;
  for (int i : members) z += x[i][axis];
  return z / static_cast<double>(members.size());
}

// The slope of the regression of the displacements along `axis` on the positions along it, over `members`.
template <int D>
double stretch_along(const std::vector<int>& members, const std::vector<Vec<D>>& x0, const std::vector<Vec<D>>& x,
                     int axis) {
  double m0 = 0, md = 0;
  for (int i : members) m0 += x0[i][axis], md += x[i][axis] - x0[i][axis];
  m0 /= static_cast<double>(members.size()), md /= static_cast<double>(members.size());
  double sxy = 0, sxx = 0;
  for (int i : members) {
    const double a = x0[i][axis] - m0, b = x[i][axis] - x0[i][axis] - md;
    sxy += a * b, sxx += a * a;
  }
  return sxx > 0 ? sxy / sxx : 0.0;
}

// The lateral strain, expansion positive: the stretch along each lateral axis, averaged over them.
template <int D>
double lateral_strain_of(const SupportSetup<D>& st, const std::vector<Vec<D>>& x, int axis) {
  double sum = 0;
  for (int k = 0; k < D; ++k)
    if (k != axis) sum += stretch_along<D>(st.inner, st.x0, x, k);
  return sum / (D - 1);
}

}  // namespace

// The axial strain inside the specimen: the particles whose centres lie in the middle half of its extent along
// the axis at the start, their axial displacements regressed on their axial positions. Positive in the loading
// sense.
template <int D>
void UniaxialAnalysis::add_inside_strain(std::vector<Series>& out, const Observed<D>& o) const {
  const Particles<D>* b = o.bodies;
  const int ax = axis;
  const double sense = tension ? 1.0 : -1.0;
  auto x0 = std::make_shared<std::vector<Vec<D>>>();
  auto inner = std::make_shared<std::vector<int>>();
  if (b) {
    *x0 = b->x;
    double lo = kInf, hi = -kInf;
    for (const auto& x : b->x) lo = std::min(lo, x[ax]), hi = std::max(hi, x[ax]);
    for (int i = 0; i < b->size(); ++i)
      if (std::abs(b->x[i][ax] - 0.5 * (lo + hi)) < 0.25 * (hi - lo)) inner->push_back(i);
    if (inner->size() < 2)
      throw InputError(scene_file + ": [uniaxial] the middle half of the specimen along " +
                       std::string(1, char('x' + ax)) + " holds fewer than two particles: no inside strain");
  }
  out.push_back({"uniaxial.inside_strain", "-",
                 b ? std::function<double()>(
                         [b, x0, inner, ax, sense] { return sense * stretch_along<D>(*inner, *x0, b->x, ax); })
                   : nullptr});
}

// Šmilauer, "Simulation setup": the supports at both ends strain the specimen along `axis`. Axial force: the
// mean of the two supports' reactions, F = ½(R⁺ − R⁻); stress F/A with A the bounding box's cross-section (or
// the scene's); strain and length from the supports' mean positions. Signs: positive in the loading sense.
template <int D>
void UniaxialAnalysis::add_support_histories(std::vector<Series>& out, const Observed<D>& o) const {
  const int ax = axis;
  const double sense = tension ? 1.0 : -1.0;
  const Particles<D>* b = o.bodies;
  auto st = std::make_shared<SupportSetup<D>>();
  if (b) {
    st->lo = (*o.groups)[supports[0]], st->hi = (*o.groups)[supports[1]];
    if (st->lo.empty() || st->hi.empty())
      throw InputError(scene_file + ": [uniaxial] supports: group '" + support_names[st->lo.empty() ? 0 : 1] +
                       "' selects no particle");
    st->x0 = b->x;
    const double zlo = mean_along<D>(st->lo, b->x, ax), zhi = mean_along<D>(st->hi, b->x, ax);
    st->length0 = zhi - zlo;
    if (!(st->length0 > 0))
      throw InputError(scene_file + ": [uniaxial] supports: the first group must lie at the negative end of the " +
                       std::string(1, char('x' + ax)) + " axis, the second at the positive end");
    Vec<D> lo = Vec<D>::Constant(kInf), hi = Vec<D>::Constant(-kInf);
    for (int i = 0; i < b->size(); ++i) {
      lo = lo.cwiseMin(b->x[i] - Vec<D>::Constant(b->radius[i]));
      hi = hi.cwiseMax(b->x[i] + Vec<D>::Constant(b->radius[i]));
      if (std::abs(b->x[i][ax] - 0.5 * (zlo + zhi)) < 0.25 * st->length0) st->inner.push_back(i);
    }
    st->area = area;
    if (st->area == 0) {
      st->area = 1;
      for (int k = 0; k < D; ++k)
        if (k != ax) st->area *= hi[k] - lo[k];
    }
  }
  auto add = [&](std::string name, std::string unit, std::function<double()> f) {
    out.push_back({std::move(name), std::move(unit), b ? std::move(f) : nullptr});
  };
  add("uniaxial.stress", "Pa", [b, st, ax, sense] {
    double rp = 0, rm = 0;  // reactions along the axis: what holds each support on its motion
    for (int i : st->hi) rp -= b->f[i][ax];
    for (int i : st->lo) rm -= b->f[i][ax];
    return sense * 0.5 * (rp - rm) / st->area;
  });
  add("uniaxial.length", "m",
      [b, st, ax] { return mean_along<D>(st->hi, b->x, ax) - mean_along<D>(st->lo, b->x, ax); });
  add("uniaxial.strain", "-", [b, st, ax, sense] {
    const double l = mean_along<D>(st->hi, b->x, ax) - mean_along<D>(st->lo, b->x, ax);
    return sense * (l - st->length0) / st->length0;
  });
  add("uniaxial.lateral_strain", "-", [b, st, ax] { return lateral_strain_of<D>(*st, b->x, ax); });
}

}  // namespace mc

namespace mc {

// Tang §5.2: the pre-peak curve σ(ε_axial) gives E as the secant between 25 % and 50 % of the peak and ν as
// −Δε_lateral/Δε_axial over the same stretch; UCS (f_c, or in tension f_t) is the peak; the crack-initiation
// stress is the stress when the cracks reach 1 % of their count at the peak. Compression is positive for the
// stress and the axial strain (whatever signs the histories carry), the lateral strain keeps its sign
// (expansion positive).
UniaxialResult UniaxialAnalysis::result(const Histories& h) const {
  UniaxialResult r = result_from(h, strain_inside ? "uniaxial.inside_strain" : axial_strain);
  const UniaxialResult other = result_from(h, strain_inside ? axial_strain : "uniaxial.inside_strain");
  const UniaxialResult& platens = strain_inside ? other : r;
  const UniaxialResult& inside = strain_inside ? r : other;
  r.modulus_platens = platens.modulus, r.poisson_platens = platens.poisson;
  r.modulus_inside = inside.modulus, r.poisson_inside = inside.poisson;
  return r;
}

UniaxialResult UniaxialAnalysis::result_from(const Histories& h, const std::string& axial) const {
  UniaxialResult r;
  static const std::vector<double> none;
  auto series = [&](const std::string& name) -> const std::vector<double>& {
    const auto it = h.find(name);
    return it == h.end() ? none : it->second;
  };
  std::vector<double> s = series(stress), ea = series(axial), el(s.size(), 0.0);
  for (const auto& name : lateral_strain) {
    const std::vector<double>& y = series(name);
    el.resize(std::min(el.size(), y.size()));
    for (std::size_t k = 0; k < el.size(); ++k) el[k] += y[k] / static_cast<double>(lateral_strain.size());
  }
  const std::vector<double>& ct = series("cracks.tensile");
  const std::vector<double>& cs = series("cracks.shear");
  const std::size_t n = std::min({s.size(), ea.size(), el.size(), ct.size(), cs.size()});
  if (n < 3) return r;
  for (std::size_t k = 0; k < n; ++k) s[k] = std::abs(s[k]), ea[k] = std::abs(ea[k]);
  std::size_t peak = 0;
  for (std::size_t k = 0; k < n; ++k)
    if (s[k] > s[peak]) peak = k;
  r.ucs = s[peak];
  r.peak_passed = passed_peak(s, peak, n);
  // The first pre-peak crossing of a stress level, interpolated: returns the fractional row.
  auto crossing = [&](double level) {
    for (std::size_t k = 1; k <= peak; ++k)
      if (s[k] >= level && s[k - 1] < level) return (k - 1) + (level - s[k - 1]) / (s[k] - s[k - 1]);
    return kNaN;
  };
  auto at = [&](const std::vector<double>& y, double row) {
    if (!std::isfinite(row)) return kNaN;
    const auto k = static_cast<std::size_t>(row);
    const double f = row - static_cast<double>(k);
    return k + 1 < n ? y[k] + f * (y[k + 1] - y[k]) : y[k];
  };
  const double r25 = crossing(0.25 * r.ucs), r50 = crossing(0.5 * r.ucs);
  // Compression widens the specimen, tension narrows it: ν is the lateral expansion per axial shortening, or
  // the lateral contraction per axial elongation.
  const double nu = (tension ? -1.0 : 1.0) * (at(el, r50) - at(el, r25)) / (at(ea, r50) - at(ea, r25));
  const double e = 0.25 * r.ucs / (at(ea, r50) - at(ea, r25));
  const double e_0_50 = (0.5 * r.ucs - s[0]) / (at(ea, r50) - ea[0]);
  const double e_tangent = 0.1 * r.ucs / (at(ea, crossing(0.55 * r.ucs)) - at(ea, crossing(0.45 * r.ucs)));
  // Plane strain: a 2D assembly with ratios E₂, ν₂ is the section of a material with ν = ν₂/(1 + ν₂) and
  // E = E₂(1 − ν²) (Tang ch. 5: "the two dimensional elastic constants are obtained by assuming the plane strain
  // condition").
  const bool convert = dimension == 2 && plane_strain;
  r.poisson = convert ? nu / (1 + nu) : nu;
  const double factor = convert ? 1 - r.poisson * r.poisson : 1.0;
  r.modulus = e * factor, r.modulus_secant_0_50 = e_0_50 * factor, r.modulus_tangent_50 = e_tangent * factor;
  if (dimension == 2) r.modulus_raw_2d = e, r.poisson_raw_2d = nu;
  r.strain_at_peak = ea[peak];
  // Cracks: the breaks; in a run without any break but with first yields (a CPM specimen, whose contacts damage
  // without breaking by default), the first yields, i.e. the contacts that started to damage.
  const auto yi = h.find("cracks.yield");
  r.cracks_by_yield = ct[n - 1] + cs[n - 1] == 0 && yi != h.end() && yi->second.size() >= n && yi->second[n - 1] > 0;
  auto cracks = [&](std::size_t k) { return r.cracks_by_yield ? yi->second[k] : ct[k] + cs[k]; };
  r.cracks_at_peak = cracks(peak);
  for (std::size_t k = 0; k <= peak; ++k)
    if (cracks(k) >= std::max(1.0, 0.01 * r.cracks_at_peak)) {
      r.initiation_stress = s[k];
      break;
    }
  r.cracks_tensile = ct[n - 1];
  r.cracks_shear = cs[n - 1];
  if (tension) {
    // Šmilauer Fig. 19: the conventional G_f, the area under the σ–ε curve up to where the softening branch falls
    // to 0.2 f_t, times the gauge length (the supports' initial distance): the energy per unit cross-section
    // of a specimen whose crack localises. NaN when the run stopped before 0.2 f_t.
    double work = 0;
    for (std::size_t k = 1; k < n; ++k) {
      const double s0 = s[k - 1], s1 = s[k];
      if (k > peak && s1 <= 0.2 * r.ucs) {
        const double f = s0 > s1 ? (s0 - 0.2 * r.ucs) / (s0 - s1) : 1.0;
        work += 0.5 * (s0 + (s0 + f * (s1 - s0))) * f * (ea[k] - ea[k - 1]);
        r.strain_at_02ft = ea[k - 1] + f * (ea[k] - ea[k - 1]);
        break;
      }
      work += 0.5 * (s0 + s1) * (ea[k] - ea[k - 1]);
    }
    const auto len = h.find("uniaxial.length");
    r.gauge_length = len != h.end() && !len->second.empty() ? len->second.front() : kNaN;
    r.fracture_energy = std::isfinite(r.strain_at_02ft) ? work * r.gauge_length : kNaN;
  }
  return r;
}

std::string UniaxialAnalysis::summary_json(const RunRecord& run) const {
  const UniaxialResult r = result(run.histories);
  if (!std::isfinite(r.ucs)) return "null";
  std::ostringstream o;
  o << "{\n    \"loading\": " << (tension ? "\"tension\"" : "\"compression\"")
    << ",\n    \"peak_passed\": " << (r.peak_passed ? "true" : "false")
    << ",\n    \"peak_passed_definition\": " << json_quote(kPeakPassedDefinition);
  o << ",\n    \"E\": " << json_number(r.modulus)
    << ",\n    \"E_definition\": \"secant between 25 % and 50 % of the peak stress\""
    << ",\n    \"nu\": " << json_number(r.poisson);
  if (dimension == 2)
    o << ",\n    \"plane\": " << (plane_strain ? "\"strain\"" : "\"stress\"")
      << ",\n    \"E_raw_2d\": " << json_number(r.modulus_raw_2d)
      << ",\n    \"nu_raw_2d\": " << json_number(r.poisson_raw_2d)
      << ",\n    \"raw_2d_definition\": \"the disc assembly's own ratios in its plane (the plane-stress reading)\"";
  o << ",\n    \"axial_strain_from\": " << (strain_inside ? "\"inside\"" : "\"platens\"")
    << ",\n    \"E_platens\": " << json_number(r.modulus_platens)
    << ",\n    \"E_inside\": " << json_number(r.modulus_inside)
    << ",\n    \"nu_platens\": " << json_number(r.poisson_platens)
    << ",\n    \"nu_inside\": " << json_number(r.poisson_inside)
    << ",\n    \"E_inside_definition\": \"axial strain from the regression of the axial displacements of the "
       "middle half of the specimen\"";
  o << ",\n    \"E_secant_0_50\": " << json_number(r.modulus_secant_0_50)
    << ",\n    \"E_tangent_50\": " << json_number(r.modulus_tangent_50)
    << ",\n    \"E_tangent_50_definition\": \"secant between 45 % and 55 % of the peak stress\"";
  if (tension)
    o << ",\n    \"f_t\": " << json_number(r.ucs) << ",\n    \"G_f\": " << json_number(r.fracture_energy)
      << ",\n    \"G_f_definition\": \"area under stress-strain to 0.2 f_t post-peak, times the gauge length\""
      << ",\n    \"gauge_length\": " << json_number(r.gauge_length)
      << ",\n    \"strain_at_0.2_f_t\": " << json_number(r.strain_at_02ft);
  else
    o << ",\n    \"ucs\": " << json_number(r.ucs) << ",\n    \"f_c\": " << json_number(r.ucs);
  o << ",\n    \"strain_at_peak\": " << json_number(r.strain_at_peak)
    << ",\n    \"crack_initiation_stress\": " << json_number(r.initiation_stress)
    << ",\n    \"crack_initiation_ratio\": " << json_number(r.initiation_stress / r.ucs)
    << ",\n    \"cracks_counted\": " << (r.cracks_by_yield ? "\"first yields\"" : "\"breaks\"")
    << ",\n    \"cracks_at_peak\": " << json_number(r.cracks_at_peak)
    << ",\n    \"cracks_tensile\": " << json_number(r.cracks_tensile)
    << ",\n    \"cracks_shear\": " << json_number(r.cracks_shear);
  std::vector<std::pair<std::string, std::string>> units{{"E", "Pa"}, {"nu", "-"}};
  if (dimension == 2) units.insert(units.end(), {{"E_raw_2d", "Pa"}, {"nu_raw_2d", "-"}});
  units.insert(units.end(), {{"E_platens", "Pa"}, {"E_inside", "Pa"}, {"nu_platens", "-"}, {"nu_inside", "-"},
                             {"E_secant_0_50", "Pa"}, {"E_tangent_50", "Pa"}});
  if (tension)
    units.insert(units.end(), {{"f_t", "Pa"}, {"G_f", "J/m^2"}, {"gauge_length", "m"}, {"strain_at_0.2_f_t", "-"}});
  else
    units.insert(units.end(), {{"ucs", "Pa"}, {"f_c", "Pa"}});
  units.insert(units.end(), {{"strain_at_peak", "-"}, {"crack_initiation_stress", "Pa"},
                             {"crack_initiation_ratio", "-"}, {"cracks_at_peak", "-"}, {"cracks_tensile", "-"},
                             {"cracks_shear", "-"}});
  o << ",\n    \"units\": " << units_json(units) << "\n  }";
  return o.str();
}

}  // namespace mc
