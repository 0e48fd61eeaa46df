#include "scene/analyses/bending.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "engine/errors.hpp"
#include "scene/analyses/records.hpp"
#include "scene/json.hpp"
#include "scene/scene.hpp"
#include "scene/specimen_build.hpp"  // vec_of

namespace mc {

namespace {

using V3 = std::array<double, 3>;

V3 v3(const std::vector<double>& v) {
  V3 o{};
  for (std::size_t k = 0; k < std::min<std::size_t>(3, v.size()); ++k) o[k] = v[k];
  return o;
}
double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V3 minus(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V3 unit(const V3& a) {
  const double n = std::sqrt(dot(a, a));
  return {a[0] / n, a[1] / n, a[2] / n};
}

// A wall's centre: a segment's midpoint, a rectangle's centre, a plane's point.
V3 wall_centre(const WallSpec& w) {
  if (w.kind != WallSpec::Kind::Segment) return v3(w.point);
  const V3 a = v3(w.a), b = v3(w.b);
  return {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2])};
}

// A wall's unit normal towards the material (a segment's: across it, on the side of its `inside` point).
V3 wall_normal(const WallSpec& w) {
  if (w.kind != WallSpec::Kind::Segment) return unit(v3(w.normal));
  const V3 t = minus(v3(w.b), v3(w.a));
  V3 n = unit(V3{-t[1], t[0], 0});
  if (dot(n, minus(v3(w.inside), v3(w.a))) < 0) n = {-n[0], -n[1], 0};
  return n;
}

}  // namespace

const KeyTable& bending_keys() {
  static const KeyTable t{
      .name = "bending",
      .title = "[bending]: three-point bending (Tang §7.1; RILEM 50-FMC)",
      .about = "A notched beam on two support walls, loaded by a third. Histories bending.load [N, along the load "
               "wall's normal], bending.cmod [m], bending.deflection [m], with gravity bending.self_weight [N]. "
               "summary adds the peak load (scaled to `thickness`), CMOD and deflection at the peak, G_F = (W_0 + "
               "m g δ_0)/(ligament × thickness) with W_0 the area under load-deflection to the end of the record "
               "(stop the run well past the peak), the stiffness (secant 10-40 % of the peak), with a crack log the "
               "crack path and the cracks per phase pair at the peak and the end, with energy tracing the balance.",
      .keys = {
          {.name = "load_wall", .type = KeyType::Text, .need = Need::Required, .doc = "the moving wall on the beam"},
          {.name = "supports", .type = KeyType::Text, .need = Need::Required, .doc = "\"left right\": two other walls"},
          {.name = "cmod", .type = KeyType::Text, .need = Need::Required, .doc = "an opening probe: the crack-mouth opening"},
          {.name = "span", .unit = Unit::Length, .range = Range::positive(), .need = Need::Required,
           .doc = "between the supports"},
          {.name = "depth", .unit = Unit::Length, .range = Range::positive(), .need = Need::Required,
           .doc = "the beam's"},
          {.name = "ligament", .unit = Unit::Length, .range = Range::positive(),
           .doc = "the depth minus the notch", .shown_default = "depth"},
          {.name = "thickness", .unit = Unit::Length, .range = Range::positive(),
           .doc = "the beam's; 2D: the report's beam, loads scaled from the discs' unit thickness to it; 3D: "
                  "required",
           .shown_default = "0.1 m in 2D"},
          {.name = "deflection_groups", .type = KeyType::Text,
           .doc = "\"mid left right\": three [[groups]] (on the neutral axis at mid-span and above the supports) "
                  "whose mean displacements give the deflection free of the indentations; absent: the load wall's "
                  "displacement minus the supports'"},
      }};
  return t;
}

std::string BendingAnalysis::name() const { return std::string(bending_keys().name); }

std::shared_ptr<const Analysis> read_bending(const KeyReader& k, const Scene& s) {
  auto b = std::make_shared<BendingAnalysis>();
  b->scene_file = s.file;
  b->dimension = s.dimension;
  b->gravity = s.gravity;
  const auto wall_name = [](const WallSpec& w) { return w.name; };
  b->load_wall = named(k, "load_wall", 1, s.walls, wall_name, "[[walls]]")[0];
  const std::vector<int> sup = named(k, "supports", 2, s.walls, wall_name, "[[walls]]");
  b->supports = {sup[0], sup[1]};
  if (b->supports[0] == b->load_wall || b->supports[1] == b->load_wall)
    k.fail("supports", "names the loading wall '" + s.walls[b->load_wall].name + "': give the two support walls");
  if (k.has("deflection_groups")) {
    const std::vector<int> g = named(
        k, "deflection_groups", 3, s.groups, [](const GroupSpec& x) { return x.name; }, "[[groups]]");
    b->deflection_groups = {g[0], g[1], g[2]};
  }
  for (const PhaseSpec& p : s.phases) b->phase_names.push_back(p.name);
  b->top = wall_centre(s.walls[b->load_wall]);
  b->down = wall_normal(s.walls[b->load_wall]);
  b->along = unit(minus(wall_centre(s.walls[b->supports[1]]), wall_centre(s.walls[b->supports[0]])));
  b->cmod_probe = k.string("cmod");
  b->cmod_gauge = s.opening_gauge(b->cmod_probe);
  if (b->cmod_gauge < 0)
    k.fail("cmod", "'" + b->cmod_probe + "' is not the name of an opening probe ([[probes]] with kind = \"opening\")");
  b->span = k.number("span");
  b->depth = k.number("depth");
  b->ligament = k.number("ligament", b->depth);
  if (b->ligament > b->depth)
    k.fail("ligament", "the ligament (depth minus notch) cannot exceed the depth, " + json_number(b->depth) + " m");
  // 2D: the discs have unit thickness; the report scales loads to the real beam's (Tang §7.1: 100 mm).
  b->thickness = s.dimension == 2 ? k.number("thickness", 0.1) : k.required_number("thickness");
  return b;
}

void BendingAnalysis::check(const KeyReader& k, const Scene& s, const std::vector<std::string>& histories) const {
  (void)histories;  // it reads only the histories it records itself
  const WallSpec& w = s.walls[load_wall];
  if (w.control == WallControl::Fixed)
    k.fail("load_wall", "wall '" + w.name + "' is fixed: the loading wall must move (velocity, servo or opening)");
}

void BendingAnalysis::add_histories(std::vector<Series>& out, const Observed<2>& o) const { add<2>(out, o); }
void BendingAnalysis::add_histories(std::vector<Series>& out, const Observed<3>& o) const { add<3>(out, o); }

namespace {
// A support that touches no particle carries nothing, and the beam rests on the other alone or on none: the load
// it reads is no bending test's. Refused when the gap from a support to the nearest particle's surface exceeds the
// largest radius (a beam placed on its supports touches them, or lies within a particle's reach of them).
template <int D>
void check_supports_touch(const std::string& file, const std::array<int, 2>& supports,
                          const std::vector<Wall<D>>& walls, const Particles<D>& p) {
  double largest = 0;
  for (int i = 0; i < p.size(); ++i) largest = std::max(largest, p.radius[i]);
  for (const int s : supports) {
    double gap = kInf;
    for (int i = 0; i < p.size(); ++i) gap = std::min(gap, (p.x[i] - walls[s].closest(p.x[i])).norm() - p.radius[i]);
    if (gap <= largest) continue;
    std::ostringstream m;
    m.precision(4);
    m << file << ": key 'bending.supports': wall '" << walls[s].name << "' lies " << gap
      << " m from the nearest particle's surface (more than the largest radius, " << largest
      << " m): a support must touch the beam; move the wall or the specimen";
    throw InputError(m.str());
  }
}
}  // namespace

// The load is what the beam pushes back on the loading wall, along the wall's normal (which points into the
// beam); the deflection is the loading point's displacement along that normal minus the mean of the supports'
// (walls, or a yoke: three groups on the beam, free of the indentation at the load and the supports); the CMOD
// is the opening probe's reading.
template <int D>
void BendingAnalysis::add(std::vector<Series>& out, const Observed<D>& o) const {
  const Particles<D>* p = o.bodies;
  const std::vector<Wall<D>>* walls = o.walls;
  if (p && p->size() > 0) check_supports_touch<D>(scene_file, supports, *walls, *p);
  auto put = [&](std::string name, std::string unit, std::function<double()> f) {
    out.push_back({std::move(name), std::move(unit), p ? std::move(f) : nullptr});
  };
  const int lw = load_wall;
  put("bending.load", "N", [walls, lw] { return -(*walls)[lw].force.dot((*walls)[lw].normal); });
  put("bending.cmod", "m", [o, g = cmod_gauge] { return (*o.gauges)[g].value(*o.bodies); });
  if (deflection_groups[0] < 0) {
    const auto sup = supports;
    put("bending.deflection", "m", [walls, lw, sup] {
      const auto& w = *walls;
      return (w[lw].displacement - 0.5 * (w[sup[0]].displacement + w[sup[1]].displacement)).dot(w[lw].normal);
    });
  } else {
    auto members = std::make_shared<std::array<std::vector<int>, 3>>();
    auto x0 = std::make_shared<std::array<Vec<D>, 3>>();
    auto centre = [p](const std::vector<int>& m) {
      Vec<D> c = Vec<D>::Zero();
      for (int i : m) c += p->x[i];
      return Vec<D>(c / static_cast<double>(m.size()));
    };
    if (p)
      for (int k = 0; k < 3; ++k) (*members)[k] = (*o.groups)[deflection_groups[k]], (*x0)[k] = centre((*members)[k]);
    put("bending.deflection", "m", [walls, lw, members, x0, centre] {
      Vec<D> u[3];
      for (int k = 0; k < 3; ++k) u[k] = centre((*members)[k]) - (*x0)[k];
      return (u[0] - 0.5 * (u[1] + u[2])).dot((*walls)[lw].normal);
    });
  }
  if (gravity) {
    // RILEM 50-FMC: the weight of the beam between the supports (m1 g; the loading wall has no mass, m2 = 0),
    // along the load direction.
    double weight = 0;
    if (p) {
      const Vec<D> g = vec_of<D>(*gravity), n = (*walls)[lw].normal;
      const Vec<D> a = (*walls)[supports[0]].origin, b = (*walls)[supports[1]].origin;
      const Vec<D> along = (b - a).normalized();
      for (int i = 0; i < p->size(); ++i) {
        const double s = (p->x[i] - a).dot(along);
        if (s >= 0 && s <= (b - a).dot(along)) weight += p->mass[i] * g.dot(n);
      }
    }
    put("bending.self_weight", "N", [weight] { return weight; });
  }
}

// Tang §7.1 and RILEM 50-FMC: peak load; CMOD and deflection there; W0 the area under the load–deflection curve
// (trapezoids) to the end of the record; G_F = (W0 + m g δ0) / (ligament × thickness), δ0 the final deflection;
// the initial stiffness as the secant between the first pre-peak crossings of 10 % and 40 % of the peak.
BendingResult BendingAnalysis::result(const Histories& h) const {
  BendingResult r;
  static const std::vector<double> none;
  auto series = [&](const std::string& name) -> const std::vector<double>& {
    const auto it = h.find(name);
    return it == h.end() ? none : it->second;
  };
  const std::vector<double>& load = series("bending.load");
  const std::vector<double>& cmod = series("bending.cmod");
  const std::vector<double>& defl = series("bending.deflection");
  const std::size_t n = std::min({load.size(), cmod.size(), defl.size()});
  if (n < 2) return r;
  const std::size_t peak = static_cast<std::size_t>(std::max_element(load.begin(), load.begin() + n) - load.begin());
  r.peak_load = load[peak];
  r.peak_passed = passed_peak(load, peak, n);
  const std::vector<double>& time = series("time");
  if (peak < time.size()) r.peak_time = time[peak];
  r.cmod_at_peak = cmod[peak];
  r.deflection_at_peak = defl[peak];
  double w0 = 0;
  for (std::size_t k = 1; k < n; ++k) w0 += 0.5 * (load[k] + load[k - 1]) * (defl[k] - defl[k - 1]);
  r.work = w0;
  r.final_deflection = defl[n - 1];
  r.final_load_ratio = load[n - 1] / r.peak_load;
  const std::vector<double>& weight = series("bending.self_weight");
  if (!weight.empty()) r.self_weight_work = weight.front() * (r.final_deflection - defl[0]);
  r.fracture_energy = (r.work + r.self_weight_work) / ligament_area();
  auto crossing = [&](double level) {
    for (std::size_t k = 1; k <= peak; ++k)
      if (load[k] >= level && load[k - 1] < level)
        return defl[k - 1] + (level - load[k - 1]) / (load[k] - load[k - 1]) * (defl[k] - defl[k - 1]);
    return kNaN;
  };
  r.stiffness = 0.3 * r.peak_load / (crossing(0.4 * r.peak_load) - crossing(0.1 * r.peak_load));
  return r;
}

CrackPath BendingAnalysis::crack_path(const std::vector<LoggedCrack>& cracks, double until) const {
  const int nb = CrackPath::kBands;
  const double band = ligament / nb, bottom = depth - ligament;  // heights above the beam's underside [m]
  std::vector<std::vector<double>> at(nb);                       // positions along the beam, per band
  for (const LoggedCrack& c : cracks) {
    if (c.time > until || c.kind != CrackKind::Break) continue;
    const V3 r = minus(c.position, top);
    const double s = dot(r, along), height = depth - dot(r, down);
    if (std::abs(s) > 0.5 * depth || height < bottom || height >= depth) continue;
    at[std::min(nb - 1, static_cast<int>((height - bottom) / band))].push_back(s);
  }
  CrackPath p;
  double length = 0, first = 0, prev_s = 0, prev_h = 0;
  for (int k = 0; k < nb; ++k) {
    std::vector<double>& v = at[k];
    if (v.empty()) continue;
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    const double s = v[v.size() / 2], h = bottom + (k + 0.5) * band;
    if (p.bands > 0)
      length += std::hypot(s - prev_s, h - prev_h);
    else
      first = h;
    prev_s = s, prev_h = h, ++p.bands;
  }
  if (p.bands >= 2) {
    p.length = length;
    p.height = prev_h - first;
    p.tortuosity = length / p.height;
  }
  return p;
}

std::string BendingAnalysis::summary_json(const RunRecord& run) const {
  const Histories& h = run.histories;
  const BendingResult r = result(h);
  if (!std::isfinite(r.peak_load)) return "null";
  const double f = load_scale();
  std::ostringstream o;
  o << "{\n    \"thickness\": " << json_number(thickness) << ",\n    \"span\": " << json_number(span)
    << ",\n    \"depth\": " << json_number(depth) << ",\n    \"ligament\": " << json_number(ligament)
    << ",\n    \"peak_passed\": " << (r.peak_passed ? "true" : "false")
    << ",\n    \"peak_passed_definition\": " << json_quote(kPeakPassedDefinition)
    << ",\n    \"peak_load\": " << json_number(r.peak_load * f)
    << ",\n    \"peak_load_simulated\": " << json_number(r.peak_load) << ",\n    \"load_definition\": "
    << json_quote(dimension == 2 ? "peak_load for the beam's thickness; _simulated per metre of the discs' thickness"
                                 : "as simulated")
    << ",\n    \"cmod_at_peak\": " << json_number(r.cmod_at_peak)
    << ",\n    \"deflection_at_peak\": " << json_number(r.deflection_at_peak)
    << ",\n    \"stiffness\": " << json_number(r.stiffness * f)
    << ",\n    \"stiffness_simulated\": " << json_number(r.stiffness)
    << ",\n    \"stiffness_definition\": \"secant of load-deflection between 10 % and 40 % of the peak, pre-peak\""
    << ",\n    \"G_F\": " << json_number(r.fracture_energy)
    << ",\n    \"G_F_definition\": \"RILEM 50-FMC: (W0 + m g delta0) / (ligament x thickness), W0 the area under "
       "load-deflection to the end of the record\""
    << ",\n    \"work_of_fracture\": " << json_number(r.work * f)
    << ",\n    \"self_weight_work\": " << json_number(r.self_weight_work * f) << ",\n    \"self_weight\": "
    << json_quote(gravity ? "m g delta0, m the beam's mass between the supports"
                          : "none: gravity is off, so no self-weight acts and the load returns to zero by itself")
    << ",\n    \"final_deflection\": " << json_number(r.final_deflection)
    << ",\n    \"final_load_over_peak\": " << json_number(r.final_load_ratio);
  if (!run.cracks.empty()) {
    const CrackPath p = crack_path(run.cracks, kInf);
    o << ",\n    \"crack_path\": {\"bands\": " << p.bands << ", \"length\": " << json_number(p.length)
      << ", \"height\": " << json_number(p.height) << ", \"tortuosity\": " << json_number(p.tortuosity)
      << ", \"height_over_ligament\": " << json_number(p.height / ligament)
      << ",\n      \"definition\": \"the broken bonds within half a depth of mid-span, median position along the "
         "beam in each of 20 bands of the ligament, joined; tortuosity = length / height spanned\"}"
      << ",\n    \"cracks_at_peak\": " << crack_counts_json(run.cracks, r.peak_time, phase_names)
      << ",\n    \"cracks_final\": " << crack_counts_json(run.cracks, kInf, phase_names);
  }
  o << ",\n    \"energy\": " << energy_json(h, ligament_area(), "G_F_bonds", "ligament");
  o << ",\n    \"units\": "
    << units_json({{"thickness", "m"},
                   {"span", "m"},
                   {"depth", "m"},
                   {"ligament", "m"},
                   {"peak_load", "N"},
                   {"peak_load_simulated", "N"},
                   {"cmod_at_peak", "m"},
                   {"deflection_at_peak", "m"},
                   {"stiffness", "N/m"},
                   {"stiffness_simulated", "N/m"},
                   {"G_F", "J/m^2"},
                   {"work_of_fracture", "J"},
                   {"self_weight_work", "J"},
                   {"final_deflection", "m"},
                   {"final_load_over_peak", "-"}})
    << "\n  }";
  return o.str();
}

}  // namespace mc
