#include "scene/analyses/pullout.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>

#include "engine/errors.hpp"
#include "engine/opening_gauge.hpp"
#include "scene/analyses/records.hpp"
#include "scene/json.hpp"
#include "scene/scene.hpp"
#include "scene/scene_read_parts.hpp"  // phase_index

namespace mc {

namespace {

// The FRP particles whose centres lie within one radius of x = s (a column of the sheet; two discs where s falls
// between them), with room for the round-off of lattice coordinates.
template <int D>
std::vector<int> frp_column(const Particles<D>& p, int frp, double s) {
  std::vector<int> out;
  for (int i = 0; i < p.size(); ++i)
    if (p.phase[i] == frp && std::abs(p.x[i][0] - s) <= 1.001 * p.radius[i]) out.push_back(i);
  return out;
}

// The first row where `load` reaches `level` on its way to the peak; −1 if it never does.
long first_reaching(const std::vector<double>& load, std::size_t peak, double level) {
  for (std::size_t k = 0; k <= peak && k < load.size(); ++k)
    if (load[k] >= level) return static_cast<long>(k);
  return -1;
}

// A sheet of axial stiffness E_p t_p on a rigid substrate through an interface of stiffness K, pulled at x = 0 and
// free at x = L: E_p t_p u'' = K u gives ε(x) = ε₀ sinh(λ(L − x))/sinh(λL), λ = √(K/(E_p t_p)) (the linear
// bond-slip shear-lag solution, Tang §8.1). A gauge over [x0, x1] reads its mean.
double shear_lag_gauge_strain(double eps0, double lambda, double length, double x0, double x1) {
  return eps0 * (std::cosh(lambda * (length - x0)) - std::cosh(lambda * (length - x1))) /
         (lambda * (x1 - x0) * std::sinh(lambda * length));
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return kNaN;
  const std::size_t k = std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())));
  std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
  return v[k];
}

}  // namespace

const KeyTable& pullout_keys() {
  static const KeyTable t{
      .name = "pullout",
      .title = "[pullout]: the FRP-to-concrete single-shear pull test (Tang §8.1)",
      .about = "2D, y up, the sheet on top, pulled along x. Histories pullout.load [N per metre of the discs' "
               "thickness], pullout.slip [m], pullout.strain_<k>. summary adds the capacity (for the sheet's width, "
               "and times β_w of (8.1)), the slip at it, the strain profiles at the load levels, with a crack log "
               "the cracks per phase pair at 31, 60, 90 and 100 % of the capacity and the failure mode, with "
               "energy tracing the balance; report draws the load-slip curve, the profiles and the cracks.",
      .keys = {
          {.name = "pulled", .type = KeyType::Text, .need = Need::Required,
           .doc = "a driven [[groups]] entry: the sheet's loaded end (velocity, fix, ramp_time)"},
          {.name = "slip", .type = KeyType::Text, .need = Need::Required,
           .doc = "an opening probe with a direction, e.g. from the concrete to the sheet at the bonded length's "
                  "loaded end, along the pull"},
          {.name = "frp_phase", .type = KeyType::Text, .need = Need::Required, .doc = "the sheet's phase"},
          {.name = "bonded_from", .unit = Unit::Length, .need = Need::Required,
           .doc = "x of the bonded length's loaded end"},
          {.name = "bonded_to", .unit = Unit::Length, .need = Need::Required, .doc = "x of its far end"},
          {.name = "gauges", .type = KeyType::Integer, .range = Range::closed(1, 1000),
           .doc = "equal stretches of the bonded length, each a strain gauge between the sheet's particles at its "
                  "ends",
           .fallback = 10},
          {.name = "width", .unit = Unit::Length, .range = Range::positive(), .need = Need::Required,
           .doc = "b_f, the report's sheet: loads are scaled from the discs' unit thickness to it"},
          {.name = "prism_width", .unit = Unit::Length, .range = Range::positive(), .need = Need::Required,
           .doc = "b_c, the report's prism, for β_w (8.1)"},
          {.name = "frp_modulus", .unit = Unit::Pressure, .range = Range::positive(), .need = Need::Required,
           .doc = "E_p, for ε₀ of (8.5)"},
          {.name = "frp_thickness", .unit = Unit::Length, .range = Range::positive(), .need = Need::Required,
           .doc = "t_p, for ε₀ of (8.5)"},
          {.name = "load_levels", .type = KeyType::Reals, .unit = Unit::Force, .range = Range::positive(),
           .doc = "loads of the reported width where the strain profiles are taken, e.g. [\"4 kN\", \"8 kN\"] "
                  "(Tang Fig. 8.8)"},
          {.name = "interface_stiffness", .unit = Unit::StiffnessPerArea, .range = Range::positive(),
           .doc = "K, the bond's shear stress per slip of an elastic joint: summary and report set the final strain "
                  "profile beside the linear shear-lag solution ε(x) = ε₀ sinh(λ(L − x))/sinh(λL), "
                  "λ = √(K/(E_p t_p))"},
      }};
  return t;
}

std::string PulloutAnalysis::name() const { return std::string(pullout_keys().name); }

std::shared_ptr<const Analysis> read_pullout(const KeyReader& k, const Scene& s) {
  if (s.dimension != 2)
    throw InputError(s.file + ": [pullout]: the pull test is 2D (Tang §8.1: y up, the sheet on top, pulled along x)");
  auto a = std::make_shared<PulloutAnalysis>();
  a->scene_file = s.file;
  a->pulled_group = named(
      k, "pulled", 1, s.groups, [](const GroupSpec& g) { return g.name; }, "[[groups]]")[0];
  const GroupSpec& g = s.groups[a->pulled_group];
  if (!g.ramp_time)
    k.fail("pulled", "group '" + g.name + "' is not driven: give it 'velocity', 'fix' and 'ramp_time' ([[groups]])");
  const double speed = std::hypot(g.velocity[0], g.velocity[1]);
  if (!(speed > 0)) k.fail("pulled", "group '" + g.name + "' has velocity zero: the pulled end must move");
  a->pull = {g.velocity[0] / speed, g.velocity[1] / speed};
  a->slip_probe = k.string("slip");
  a->slip_gauge = s.opening_gauge(a->slip_probe);
  if (a->slip_gauge < 0)
    k.fail("slip", "'" + a->slip_probe + "' is not the name of an opening probe ([[probes]] with kind = \"opening\")");
  for (const PhaseSpec& p : s.phases) a->phase_names.push_back(p.name);
  a->frp_phase = scene_read::phase_index(k, "frp_phase", s.phases);
  a->bonded_from = k.number("bonded_from");
  a->bonded_to = k.number("bonded_to");
  if (a->bonded_length() <= 0) k.fail("bonded_to", "equals bonded_from: the bonded length must be positive");
  // The loaded end is where the sheet leaves the bond: the pull moves it away from the far end.
  if (a->pull[0] * (a->bonded_from - a->bonded_to) <= 0)
    k.fail("bonded_to", "lies on the side the group '" + g.name + "' pulls towards (velocity x " +
                            json_number(g.velocity[0]) + " m/s) from bonded_from = " + json_number(a->bonded_from) +
                            " m: bonded_from is the loaded end, where the pull leaves the bond; swap the two");
  a->gauges = static_cast<int>(k.integer("gauges"));
  a->width = k.number("width");
  a->prism_width = k.number("prism_width");
  if (a->width > a->prism_width)
    k.fail("width", "the sheet (" + json_number(a->width) + " m) is wider than the prism (" +
                        json_number(a->prism_width) + " m): (8.1) holds for b_f ≤ b_c");
  a->frp_modulus = k.number("frp_modulus");
  a->frp_thickness = k.number("frp_thickness");
  if (k.has("load_levels")) a->load_levels = k.numbers("load_levels", 0);
  if (k.has("interface_stiffness")) a->interface_stiffness = k.number("interface_stiffness");
  return a;
}

void PulloutAnalysis::check(const KeyReader& k, const Scene& s, const std::vector<std::string>& histories) const {
  (void)k, (void)s, (void)histories;  // it reads only the histories it records itself
}

double PulloutAnalysis::beta_w() const {
  const double r = width / prism_width;
  return std::sqrt((2 - r) / (1 + r));  // Tang (8.1), Chen & Teng 2001
}

void PulloutAnalysis::add_histories(std::vector<Series>& out, const Observed<2>& o) const {
  const Particles<2>* p = o.bodies;
  auto put = [&](std::string name, std::string unit, std::function<double()> f) {
    out.push_back({std::move(name), std::move(unit), p ? std::move(f) : nullptr});
  };
  // The load: what holds the pulled end on its motion, along the pull (the rest of the specimen pulls it back).
  const std::vector<int>* members = o.groups ? &(*o.groups)[pulled_group] : nullptr;
  const Vec<2> e(pull[0], pull[1]);
  put("pullout.load", "N", [p, members, e] {
    double f = 0;
    for (int i : *members) f -= p->f[i].dot(e);
    return f;
  });
  put("pullout.slip", "m", [o, g = slip_gauge] { return (*o.gauges)[g].value(*o.bodies); });
  // Gauge k: the FRP's strain between columns at the ends of its stretch of the bonded length, from the loaded
  // end on.
  const double dir = bonded_to > bonded_from ? 1.0 : -1.0, length = bonded_length() / gauges;
  for (int k = 0; k < gauges; ++k) {
    auto gauge = std::make_shared<OpeningGauge<2>>();
    if (p) {
      const double s0 = bonded_from + dir * k * length, s1 = bonded_from + dir * (k + 1) * length;
      gauge->a = frp_column(*p, frp_phase, s0), gauge->b = frp_column(*p, frp_phase, s1);
      if (gauge->a.empty() || gauge->b.empty())
        throw InputError(scene_file + ": pullout.bonded_to = " + json_number(bonded_to) + " m: no particle of phase '" +
                         phase_names[frp_phase] + "' within a radius of x = " +
                         json_number(gauge->a.empty() ? s0 : s1) + " m, where strain gauge " + std::to_string(k) +
                         " ends: the sheet must cover the bonded length [bonded_from, bonded_to]");
      gauge->direction = Vec<2>(dir, 0);
      gauge->start = gauge->separation(*p);
    }
    put("pullout.strain_" + std::to_string(k), "-", [p, gauge] { return gauge->value(*p) / gauge->start; });
  }
  // The interface (the sheet's underside) and the prism's bottom, for the depth of the concrete's cracks.
  double interface = kInf, bottom = kInf;
  if (p)
    for (int i = 0; i < p->size(); ++i) {
      if (p->phase[i] == frp_phase) interface = std::min(interface, p->x[i][1] - p->radius[i]);
      bottom = std::min(bottom, p->x[i][1] - p->radius[i]);
    }
  put("pullout.interface_y", "m", [interface] { return interface; });
  put("pullout.bottom_y", "m", [bottom] { return bottom; });
}

void PulloutAnalysis::add_histories(std::vector<Series>&, const Observed<3>&) const {
  throw InputError(scene_file + ": [pullout]: the pull test is 2D");
}

// Tang §8.2.3: most joints fail in the concrete, a thin layer of it coming off with the sheet; an adhesive failure
// is rare; with no free zone a wedge of concrete splits off at the loaded end (§8.2.4). The concrete breaks that
// reach deeper than a third of the prism name the wedge. Only the breaks under the bonded length, or up to one
// prism height before its loaded end (where the wedge forms), count: elsewhere the prism may crack where it is
// held (its loaded face), which is not the joint's failure.
PulloutFailure PulloutAnalysis::failure(const std::vector<LoggedCrack>& cracks, double interface_y,
                                        double bottom_y) const {
  PulloutFailure f;
  std::vector<double> depths;
  const double height = interface_y - bottom_y, dir = bonded_to > bonded_from ? 1.0 : -1.0;
  for (const LoggedCrack& c : cracks) {
    if (c.kind != CrackKind::Break) continue;
    const double along = dir * (c.position[0] - bonded_from);  // from the loaded end towards the far end
    if (along < -height || along > bonded_length()) continue;
    if (c.phase_a == frp_phase || c.phase_b == frp_phase) {
      ++f.adhesive_breaks;
    } else {
      ++f.concrete_breaks;
      depths.push_back(interface_y - c.position[1]);
    }
  }
  f.depth_median = quantile(depths, 0.5);
  f.depth_p90 = quantile(depths, 0.9);
  f.depth_max = depths.empty() ? kNaN : *std::max_element(depths.begin(), depths.end());
  if (f.adhesive_breaks + f.concrete_breaks == 0)
    f.mode = "none";
  else if (f.adhesive_breaks > f.concrete_breaks)
    f.mode = "adhesive";
  else if (f.depth_p90 > height / 3)
    f.mode = "concrete wedge";
  else
    f.mode = "thin concrete layer";
  return f;
}

std::string PulloutAnalysis::summary_json(const RunRecord& run) const {
  const Histories& h = run.histories;
  auto series = [&](const std::string& n) -> const std::vector<double>* {
    const auto it = h.find(n);
    return it == h.end() || it->second.empty() ? nullptr : &it->second;
  };
  const std::vector<double>*load = series("pullout.load"), *slip = series("pullout.slip"), *time = series("time");
  if (!load || !slip || !time) return "null";
  const std::size_t peak = static_cast<std::size_t>(std::max_element(load->begin(), load->end()) - load->begin());
  const double capacity = (*load)[peak];
  std::ostringstream o;
  o << "{\n    \"width\": " << json_number(width) << ",\n    \"prism_width\": " << json_number(prism_width)
    << ",\n    \"beta_w\": " << json_number(beta_w()) << ",\n    \"bonded_length\": " << json_number(bonded_length())
    << ",\n    \"peak_passed\": " << (passed_peak(*load, peak, load->size()) ? "true" : "false")
    << ",\n    \"peak_passed_definition\": " << json_quote(kPeakPassedDefinition)
    << ",\n    \"capacity\": " << json_number(capacity * width)
    << ",\n    \"capacity_beta_w\": " << json_number(capacity * width * beta_w())
    << ",\n    \"capacity_simulated\": " << json_number(capacity)
    << ",\n    \"load_definition\": \"capacity for the sheet's width b_f; _beta_w times Chen & Teng's width factor "
       "(8.1); _simulated per metre of the discs' thickness\""
    << ",\n    \"slip_at_capacity\": " << json_number((*slip)[peak])
    << ",\n    \"final_load_over_capacity\": " << json_number(load->back() / capacity);
  // Strain profiles at the declared loads, on the way to the capacity (Tang Fig. 8.8), with ε₀ of (8.5).
  o << ",\n    \"strain_profiles\": [";
  for (std::size_t l = 0; l < load_levels.size(); ++l) {
    const long row = first_reaching(*load, peak, load_levels[l] / width);
    o << (l ? "," : "") << "\n      {\"load\": " << json_number(load_levels[l])
      << ", \"reached\": " << (row >= 0 ? "true" : "false");
    if (row >= 0) {
      const double f = (*load)[static_cast<std::size_t>(row)];
      o << ", \"time\": " << json_number((*time)[static_cast<std::size_t>(row)])
        << ", \"epsilon_0\": " << json_number(f / (frp_modulus * frp_thickness)) << ", \"positions\": [";
      for (int k = 0; k < gauges; ++k) o << (k ? ", " : "") << json_number(gauge_position(k));
      o << "], \"strains\": [";
      for (int k = 0; k < gauges; ++k) {
        const std::vector<double>* s = series("pullout.strain_" + std::to_string(k));
        o << (k ? ", " : "") << json_number(s ? (*s)[static_cast<std::size_t>(row)] : kNaN);
      }
      o << "]";
    }
    o << "}";
  }
  o << (load_levels.empty() ? "]" : "\n    ]")
    << ",\n    \"strain_definition\": \"gauge k spans the k-th of `gauges` equal stretches of the bonded length, "
       "positions from its loaded end; epsilon_0 = F / (E_p t_p b_f), Tang (8.5)\"";
  if (!run.cracks.empty()) {
    o << ",\n    \"cracks\": {";
    const double fractions[] = {0.31, 0.6, 0.9, 1.0};
    for (double fr : fractions) {
      const long row = first_reaching(*load, peak, fr * capacity);
      o << "\n      \"at_" << static_cast<int>(std::lround(fr * 100)) << "_percent\": "
        << crack_counts_json(run.cracks, (*time)[static_cast<std::size_t>(std::max(row, 0L))], phase_names) << ",";
    }
    o << "\n      \"final\": " << crack_counts_json(run.cracks, kInf, phase_names) << "\n    }";
    const std::vector<double>*iface = series("pullout.interface_y"), *bottom = series("pullout.bottom_y");
    if (iface && bottom) {
      const PulloutFailure f = failure(run.cracks, iface->front(), bottom->front());
      o << ",\n    \"failure\": {\"mode\": " << json_quote(f.mode) << ", \"adhesive_breaks\": " << f.adhesive_breaks
        << ", \"concrete_breaks\": " << f.concrete_breaks << ", \"depth_median\": " << json_number(f.depth_median)
        << ", \"depth_p90\": " << json_number(f.depth_p90) << ", \"depth_max\": " << json_number(f.depth_max)
        << ",\n      \"definition\": \"breaks of pairs with the FRP phase (adhesive) against the others (concrete), "
           "and the concrete breaks' depth below the sheet's underside, of the breaks under the bonded length or up to one "
           "prism height before its loaded end: adhesive if those dominate, concrete wedge if a tenth of the concrete "
           "breaks lie deeper than a third of the prism, else a thin concrete layer\"}";
    }
  }
  if (std::isfinite(interface_stiffness)) o << ",\n    \"shear_lag\": " << shear_lag_json(h);
  o << ",\n    \"energy\": " << energy_json(h, bonded_length(), "G_bonds", "bonded");
  o << ",\n    \"units\": "
    << units_json({{"width", "m"},
                   {"prism_width", "m"},
                   {"beta_w", "-"},
                   {"bonded_length", "m"},
                   {"capacity", "N"},
                   {"capacity_beta_w", "N"},
                   {"capacity_simulated", "N"},
                   {"slip_at_capacity", "m"},
                   {"final_load_over_capacity", "-"}})
    << "\n  }";
  return o.str();
}

std::string PulloutAnalysis::shear_lag_json(const Histories& h) const {
  const auto last = [&](const std::string& n) {
    const auto it = h.find(n);
    return it == h.end() || it->second.empty() ? kNaN : it->second.back();
  };
  const double ea = frp_modulus * frp_thickness, lambda = std::sqrt(interface_stiffness / ea);
  const double length = bonded_length(), dx = length / gauges, eps0 = last("pullout.load") / ea;
  std::ostringstream simulated, analytic;
  double deviation = 0;
  for (int k = 0; k < gauges; ++k) {
    const double got = last("pullout.strain_" + std::to_string(k));
    const double want = shear_lag_gauge_strain(eps0, lambda, length, k * dx, (k + 1) * dx);
    deviation = std::max(deviation, std::abs(got - want) / eps0);
    simulated << (k ? ", " : "") << json_number(got);
    analytic << (k ? ", " : "") << json_number(want);
  }
  std::ostringstream o;
  o << "{\"interface_stiffness\": " << json_number(interface_stiffness) << ", \"lambda\": " << json_number(lambda)
    << ", \"lambda_L\": " << json_number(lambda * length) << ", \"epsilon_0\": " << json_number(eps0)
    << ",\n      \"strains\": [" << simulated.str() << "],\n      \"strains_shear_lag\": [" << analytic.str()
    << "],\n      \"max_deviation_over_epsilon_0\": " << json_number(deviation)
    << ",\n      \"definition\": \"the gauges' strains at the run's end beside the mean over each gauge of "
       "epsilon_0 sinh(lambda (L - x)) / sinh(lambda L), lambda = sqrt(K / (E_p t_p)), epsilon_0 = F / (E_p t_p) of "
       "the final load per metre of thickness\""
    << ",\n      \"units\": "
    << units_json({{"interface_stiffness", "Pa/m"}, {"lambda", "1/m"}, {"lambda_L", "-"}, {"epsilon_0", "-"},
                   {"strains", "-"}, {"strains_shear_lag", "-"}, {"max_deviation_over_epsilon_0", "-"}})
    << "}";
  return o.str();
}

}  // namespace mc
