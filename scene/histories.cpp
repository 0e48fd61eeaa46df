#include "scene/histories.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>

#include "scene/analysis.hpp"
#include "scene/rigid_cell_histories.hpp"

namespace mc {

namespace {

const char* axis_name(int k) { return k == 0 ? "x" : k == 1 ? "y" : "z"; }
std::string tensor_name(int i, int j) { return std::string(axis_name(i)) + axis_name(j); }

// Appends series to a list; with no world, their names alone. Particles are read in `bodies` and opening gauges in
// `gauges`: the world's own, or a split world's whole view of them.
template <int D>
struct SeriesList {
  std::vector<Series> out;
  World<D>* w;
  const Particles<D>* bodies;
  const std::vector<OpeningGauge<D>>* gauges;
  void add(std::string name, std::string unit, std::function<double()> f) {
    out.push_back({std::move(name), std::move(unit), w ? std::move(f) : nullptr});
  }
};

// Bonds and their cracks: intact bonds, breaks by mode, first yields (softening bonds), and breaks per bonded
// phase pair when there are several.
template <int D>
void add_bonds(const Scene& s, SeriesList<D>& l) {
  const World<D>* w = l.w;
  l.add("bonds.intact", "-", [w] { return static_cast<double>(w->bond_count()); });
  for (CrackMode m : {CrackMode::Tensile, CrackMode::Shear})
    l.add(std::string("cracks.") + mode_name(m), "-",
          [w, m] { return static_cast<double>(w->crack_count(CrackKind::Break, m)); });
  if (std::any_of(s.contacts.begin(), s.contacts.end(), [](const ContactSpec& c) { return c.model.yields; }))
    l.add("cracks.yield", "-", [w] {
      return static_cast<double>(w->crack_count(CrackKind::Yield, CrackMode::Tensile) +
                                 w->crack_count(CrackKind::Yield, CrackMode::Shear));
    });
  const auto bonded =
      std::count_if(s.contacts.begin(), s.contacts.end(), [](const ContactSpec& c) { return c.model.bonds; });
  if (bonded < 2) return;
  for (const ContactSpec& c : s.contacts) {
    if (!c.model.bonds) continue;
    const int a = c.phase_a, b = c.phase_b;
    for (CrackMode m : {CrackMode::Tensile, CrackMode::Shear})
      l.add("cracks." + s.phases[a].name + "-" + s.phases[b].name + "." + mode_name(m), "-",
            [w, m, a, b] { return static_cast<double>(w->crack_count(CrackKind::Break, m, a, b)); });
  }
}

// Each wall's force, stress, displacement and moment about its origin (2D: the z component only).
template <int D>
void add_walls(const Scene& s, SeriesList<D>& l) {
  const World<D>* w = l.w;
  for (std::size_t i = 0; i < s.walls.size(); ++i) {
    const std::string pre = "wall." + s.walls[i].name + ".";
    for (int k = 0; k < D; ++k) l.add(pre + "force_" + axis_name(k), "N", [w, i, k] { return w->walls[i].force[k]; });
    l.add(pre + "stress", "Pa", [w, i] { return w->walls[i].normal_stress(); });
    for (int k = 0; k < D; ++k)
      l.add(pre + "disp_" + axis_name(k), "m", [w, i, k] { return w->walls[i].displacement[k]; });
    for (int k = 0; k < Dim<D>::rot; ++k)
      l.add(pre + "moment_" + axis_name(D == 2 ? 2 : k), "N m", [w, i, k] { return w->walls[i].moment[k]; });
  }
}

// What holds a group on its prescribed motion: the supports' force on it (minus the force the rest of the
// specimen exerts), and its mean displacement from the start.
template <int D>
void add_groups(const Scene& s, const SpecimenInfo* info, SeriesList<D>& l) {
  const Particles<D>* p = l.bodies;
  for (std::size_t gi = 0; gi < s.groups.size(); ++gi) {
    const std::string pre = "group." + s.groups[gi].name + ".";
    const std::vector<int>* members = info ? &info->groups[gi] : nullptr;
    auto x0 = std::make_shared<std::vector<Vec<D>>>();
    if (p)
      for (int i : *members) x0->push_back(p->x[i]);
    for (int k = 0; k < D; ++k)
      l.add(pre + "reaction_" + axis_name(k), "N", [p, members, k] {
        double f = 0;
        for (int i : *members) f -= p->f[i][k];
        return f;
      });
    for (int k = 0; k < D; ++k)
      l.add(pre + "disp_" + axis_name(k), "m", [p, members, k, x0] {
        double u = 0;
        for (std::size_t n = 0; n < members->size(); ++n) u += p->x[(*members)[n]][k] - (*x0)[n][k];
        return u / static_cast<double>(members->size());
      });
  }
}

// Engineering strain between two walls along the first one's normal, tension positive.
template <int D>
void add_wall_strains(const Scene& s, SeriesList<D>& l) {
  const World<D>* w = l.w;
  for (const WallStrainSpec& g : s.wall_strains) {
    const int a = g.walls[0], b = g.walls[1];
    l.add("strain." + g.name, "-", [w, a, b] {
      const auto& wa = w->walls[a];
      const auto& wb = w->walls[b];
      const double gap = (wb.origin - wa.origin).dot(wa.normal);
      const double gap0 = (wb.origin - wb.displacement - (wa.origin - wa.displacement)).dot(wa.normal);
      return (gap - gap0) / gap0;
    });
  }
}

// Tang (3.74)–(3.80): the first of them brings the kinetic and strain terms up to the current time.
template <int D>
void add_energy(SeriesList<D>& l) {
  World<D>* w = l.w;
  const EnergyTrace* e = w ? &w->energy : nullptr;
  l.add("energy.kinetic", "J", [w, e] {
    w->update_energy();
    return e->kinetic;
  });
  l.add("energy.strain", "J", [e] { return e->strain; });
  l.add("energy.body_work", "J", [e] { return e->body_work; });
  l.add("energy.boundary_work", "J", [e] { return e->boundary_work; });
  l.add("energy.dissipated_contacts", "J", [e] { return e->dissipated_contacts; });
  l.add("energy.dissipated_bonds", "J", [e] { return e->dissipated_bonds; });
  l.add("energy.dissipated_local", "J", [e] { return e->dissipated_local; });
  l.add("energy.residual", "J", [e] { return e->residual(); });
}

// Measurement regions (Tang §3.4): stress (3.63), strain (3.64–3.73), porosity, coordination number.
template <int D>
void add_regions(const Scene& s, const Observers<D>* obs, SeriesList<D>& l) {
  const World<D>* w = l.w;
  for (std::size_t r = 0; r < s.regions.size(); ++r) {
    const RegionSpec& rs = s.regions[r];
    const std::string pre = "measure." + rs.name + ".";
    const Region<D>* g = obs ? &obs->regions[r] : nullptr;
    if (rs.stress) {
      // One stress evaluation per row: the first component computes it, the others read the cache.
      auto cache = std::make_shared<Tensor<D>>();
      for (int i = 0; i < D; ++i)
        for (int j = i; j < D; ++j)
          l.add(pre + "stress_" + tensor_name(i, j), "Pa", [w, g, cache, i, j] {
            if (i == 0 && j == 0) *cache = symmetric_part<D>(average_stress(*w, *g));
            return (*cache)(i, j);
          });
    }
    if (rs.strain)
      for (int i = 0; i < D; ++i)
        for (int j = i; j < D; ++j)
          l.add(pre + "strain_" + tensor_name(i, j), "-", [obs, r, i, j] { return obs->strain[r].strain(i, j); });
    if (rs.porosity) l.add(pre + "porosity", "-", [w, g] { return porosity(*w, *g); });
    if (rs.coordination) l.add(pre + "coordination", "-", [w, g] { return coordination_number(*w, *g); });
  }
}

// Probes name particles by the specimen's ids; samplers use their indices.
template <int D>
void add_probes(const Scene& s, const SpecimenInfo* info, SeriesList<D>& l) {
  const Particles<D>* q = l.bodies;
  const std::vector<OpeningGauge<D>>* gauges = l.gauges;
  auto index_of = [info](std::int64_t id) {
    if (!info) return -1;
    return static_cast<int>(std::find(info->ids.begin(), info->ids.end(), id) - info->ids.begin());
  };
  for (const ProbeSpec& p : s.probes) {
    if (p.kind == ProbeSpec::Kind::Opening) {
      const int g = s.opening_gauge(p.name);
      l.add(p.name, "m", [q, gauges, g] { return (*gauges)[g].value(*q); });
      continue;
    }
    const int a = index_of(p.particles[0]);
    const int b = p.particles.size() > 1 ? index_of(p.particles[1]) : -1;
    const int c = p.component;
    using K = ProbeSpec::Kind;
    switch (p.kind) {
      case K::Overlap:
      case K::Gap: {
        const double sign = p.kind == K::Overlap ? 1.0 : -1.0;
        l.add(p.name, "m",
              [q, a, b, sign] { return sign * (q->radius[a] + q->radius[b] - (q->x[b] - q->x[a]).norm()); });
        break;
      }
      case K::RelativeSpeed:
        // Along the line of centres (positive when separating), or one component of v_b − v_a.
        l.add(p.name, "m/s", [q, a, b, c] {
          const Vec<D> dv = q->v[b] - q->v[a];
          return c >= 0 ? dv[c] : dv.dot((q->x[b] - q->x[a]).normalized());
        });
        break;
      case K::Position: l.add(p.name, "m", [q, a, c] { return c >= 0 ? q->x[a][c] : q->x[a].norm(); }); break;
      case K::Velocity: l.add(p.name, "m/s", [q, a, c] { return c >= 0 ? q->v[a][c] : q->v[a].norm(); }); break;
      case K::Opening: break;  // above
      case K::AngularVelocity:
        l.add(p.name, "rad/s", [q, a, c] {
          const auto& om = q->w[a];
          return D == 2 ? om[0] : (c >= 0 ? om[c] : om.norm());
        });
        break;
    }
  }
}

}  // namespace

template <int D>
Observers<D>::Observers(const Scene& s) {
  for (const auto& r : s.regions) {
    Region<D> g;
    for (int k = 0; k < D; ++k) g.centre[k] = r.centre[k];
    g.radius = r.radius;
    regions.push_back(g);
    strain.push_back(StrainIntegrator<D>{g});
  }
}

template <int D>
void Observers<D>::every_step(const World<D>& w, const Scene& s) {
  for (std::size_t r = 0; r < regions.size(); ++r)
    if (s.regions[r].strain) strain[r].update(w);
}

template <int D>
std::vector<Series> make_series(const Scene& s, World<D>* w, const Observed<D>& view, const SpecimenInfo* info,
                                const Observers<D>* obs) {
  SeriesList<D> l{{}, w, view.bodies, view.gauges};
  l.add("time", "s", [w] { return w->time; });
  l.add("step", "-", [w] { return static_cast<double>(w->step_count); });
  l.add("dt", "s", [w] { return w->dt; });
  l.add("contacts", "-", [w] { return static_cast<double>(w->contact_count()); });
  if (s.bond_tolerance >= 0) add_bonds<D>(s, l);
  add_walls<D>(s, l);
  add_groups<D>(s, info, l);
  for (const auto& a : s.analyses) a->add_histories(l.out, view);
  add_wall_strains<D>(s, l);
  if (s.energy) add_energy<D>(l);
  add_regions<D>(s, obs, l);
  add_probes<D>(s, info, l);
  return std::move(l.out);
}

std::vector<std::string> history_names(const Scene& s) {
  std::vector<std::string> names;
  if (s.rigid_cell) {
    for (const auto& x : rigid_cell_series(s)) names.push_back(x.name);
    return names;
  }
  const std::vector<Series> series = s.dimension == 2 ? make_series<2>(s, nullptr, {}, nullptr, nullptr)
                                                      : make_series<3>(s, nullptr, {}, nullptr, nullptr);
  for (const auto& x : series) names.push_back(x.name);
  return names;
}

template struct Observers<2>;
template struct Observers<3>;
template std::vector<Series> make_series<2>(const Scene&, World<2>*, const Observed<2>&, const SpecimenInfo*,
                                            const Observers<2>*);
template std::vector<Series> make_series<3>(const Scene&, World<3>*, const Observed<3>&, const SpecimenInfo*,
                                            const Observers<3>*);

}  // namespace mc
