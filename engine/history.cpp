#include "engine/history.hpp"

#include <algorithm>

namespace mc {

namespace {
const char* axis_name(int k) { return k == 0 ? "x" : k == 1 ? "y" : "z"; }
std::string tensor_name(int i, int j) { return std::string(axis_name(i)) + axis_name(j); }
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
std::vector<Series> make_series(const Scene& s, const World<D>* w, const Observers<D>* obs) {
  std::vector<Series> out;
  auto add = [&](std::string name, std::string unit, std::function<double()> f) {
    out.push_back({std::move(name), std::move(unit), w ? std::move(f) : nullptr});
  };
  add("time", "s", [w] { return w->time; });
  add("step", "-", [w] { return static_cast<double>(w->step_count); });
  add("dt", "s", [w] { return w->dt; });
  add("contacts", "-", [w] { return static_cast<double>(w->contact_count()); });
  if (s.bond_tolerance >= 0) {
    // Bonds and their cracks: intact bonds, breaks by mode, first yields (softening bonds), and breaks per
    // bonded phase pair when there are several.
    add("bonds.intact", "-", [w] { return static_cast<double>(w->bond_count()); });
    for (CrackMode m : {CrackMode::Tensile, CrackMode::Shear})
      add(std::string("cracks.") + mode_name(m), "-", [w, m] { return static_cast<double>(w->crack_count(CrackKind::Break, m)); });
    if (std::any_of(s.contacts.begin(), s.contacts.end(), [](const ContactSpec& c) { return c.model.yields; }))
      add("cracks.yield", "-", [w] {
        return static_cast<double>(w->crack_count(CrackKind::Yield, CrackMode::Tensile) + w->crack_count(CrackKind::Yield, CrackMode::Shear));
      });
    const auto bonded = std::count_if(s.contacts.begin(), s.contacts.end(), [](const ContactSpec& c) { return c.model.bonds; });
    if (bonded > 1)
      for (const ContactSpec& c : s.contacts) {
        if (!c.model.bonds) continue;
        const int a = c.phase_a, b = c.phase_b;
        for (CrackMode m : {CrackMode::Tensile, CrackMode::Shear})
          add("cracks." + s.phases[a].name + "-" + s.phases[b].name + "." + mode_name(m), "-",
              [w, m, a, b] { return static_cast<double>(w->crack_count(CrackKind::Break, m, a, b)); });
      }
  }
  for (std::size_t i = 0; i < s.walls.size(); ++i) {
    const std::string pre = "wall." + s.walls[i].name + ".";
    for (int k = 0; k < D; ++k) add(pre + "force_" + axis_name(k), "N", [w, i, k] { return w->walls[i].force[k]; });
    add(pre + "stress", "Pa", [w, i] { return w->walls[i].normal_stress(); });
    for (int k = 0; k < D; ++k) add(pre + "disp_" + axis_name(k), "m", [w, i, k] { return w->walls[i].displacement[k]; });
    // Moment about the wall's origin (2D: the z component only).
    for (int k = 0; k < Dim<D>::rot; ++k)
      add(pre + "moment_" + axis_name(D == 2 ? 2 : k), "N m", [w, i, k] { return w->walls[i].moment[k]; });
  }
  for (std::size_t gi = 0; gi < s.groups.size(); ++gi) {
    // What holds a group on its prescribed motion: the supports' force on it (minus the force the rest of the
    // specimen exerts), and its mean displacement from the start.
    const std::string pre = "group." + s.groups[gi].name + ".";
    auto x0 = std::make_shared<std::vector<Vec<D>>>();
    if (w)
      for (int i : w->groups[gi]) x0->push_back(w->particles.x[i]);
    for (int k = 0; k < D; ++k)
      add(pre + "reaction_" + axis_name(k), "N", [w, gi, k] {
        double f = 0;
        for (int i : w->groups[gi]) f -= w->particles.f[i][k];
        return f;
      });
    for (int k = 0; k < D; ++k)
      add(pre + "disp_" + axis_name(k), "m", [w, gi, k, x0] {
        double u = 0;
        const auto& m = w->groups[gi];
        for (std::size_t n = 0; n < m.size(); ++n) u += w->particles.x[m[n]][k] - (*x0)[n][k];
        return u / static_cast<double>(m.size());
      });
  }
  for (const WallStrainSpec& g : s.wall_strains) {
    // Engineering strain between two walls along the first one's normal, tension positive.
    const int a = g.walls[0], b = g.walls[1];
    add("strain." + g.name, "-", [w, a, b] {
      const auto& wa = w->walls[a];
      const auto& wb = w->walls[b];
      const double gap = (wb.origin - wa.origin).dot(wa.normal);
      const double gap0 = (wb.origin - wb.displacement - (wa.origin - wa.displacement)).dot(wa.normal);
      return (gap - gap0) / gap0;
    });
  }
  if (s.energy) {
    const EnergyTrace* e = w ? &w->energy : nullptr;
    add("energy.kinetic", "J", [e] { return e->kinetic; });
    add("energy.strain", "J", [e] { return e->strain; });
    add("energy.body_work", "J", [e] { return e->body_work; });
    add("energy.boundary_work", "J", [e] { return e->boundary_work; });
    add("energy.dissipated_contacts", "J", [e] { return e->dissipated_contacts; });
    add("energy.dissipated_local", "J", [e] { return e->dissipated_local; });
    add("energy.residual", "J", [e] { return e->residual(); });
  }
  for (std::size_t r = 0; r < s.regions.size(); ++r) {
    const RegionSpec& rs = s.regions[r];
    const std::string pre = "measure." + rs.name + ".";
    const Region<D>* g = obs ? &obs->regions[r] : nullptr;
    if (rs.stress) {
      // One stress evaluation per row: the first component computes it, the others read the cache.
      auto cache = std::make_shared<Tensor<D>>();
      for (int i = 0; i < D; ++i)
        for (int j = i; j < D; ++j)
          add(pre + "stress_" + tensor_name(i, j), "Pa", [w, g, cache, i, j] {
            if (i == 0 && j == 0) *cache = symmetric_part<D>(average_stress(*w, *g));
            return (*cache)(i, j);
          });
    }
    if (rs.strain)
      for (int i = 0; i < D; ++i)
        for (int j = i; j < D; ++j) add(pre + "strain_" + tensor_name(i, j), "-", [obs, r, i, j] { return obs->strain[r].strain(i, j); });
    if (rs.porosity) add(pre + "porosity", "-", [w, g] { return porosity(*w, *g); });
    if (rs.coordination) add(pre + "coordination", "-", [w, g] { return coordination_number(*w, *g); });
  }
  // Probes name particles by the specimen's ids; samplers use their indices.
  auto index_of = [w](std::int64_t id) {
    if (!w) return -1;
    return static_cast<int>(std::find(w->ids.begin(), w->ids.end(), id) - w->ids.begin());
  };
  for (const ProbeSpec& p : s.probes) {
    const int a = index_of(p.particles[0]);
    const int b = p.particles.size() > 1 ? index_of(p.particles[1]) : -1;
    const int c = p.component;
    using K = ProbeSpec::Kind;
    switch (p.kind) {
      case K::Overlap:
      case K::Gap: {
        const double sign = p.kind == K::Overlap ? 1.0 : -1.0;
        add(p.name, "m", [w, a, b, sign] {
          const auto& q = w->particles;
          return sign * (q.radius[a] + q.radius[b] - (q.x[b] - q.x[a]).norm());
        });
        break;
      }
      case K::RelativeSpeed:
        // Along the line of centres (positive when separating), or one component of v_b − v_a.
        add(p.name, "m/s", [w, a, b, c] {
          const auto& q = w->particles;
          const Vec<D> dv = q.v[b] - q.v[a];
          return c >= 0 ? dv[c] : dv.dot((q.x[b] - q.x[a]).normalized());
        });
        break;
      case K::Position: add(p.name, "m", [w, a, c] { return c >= 0 ? w->particles.x[a][c] : w->particles.x[a].norm(); }); break;
      case K::Velocity: add(p.name, "m/s", [w, a, c] { return c >= 0 ? w->particles.v[a][c] : w->particles.v[a].norm(); }); break;
      case K::AngularVelocity:
        add(p.name, "rad/s", [w, a, c] {
          const auto& om = w->particles.w[a];
          return D == 2 ? om[0] : (c >= 0 ? om[c] : om.norm());
        });
        break;
    }
  }
  return out;
}

std::vector<std::string> history_names(const Scene& s) {
  std::vector<Series> series = s.dimension == 2 ? make_series<2>(s, nullptr, nullptr) : make_series<3>(s, nullptr, nullptr);
  std::vector<std::string> names;
  for (const auto& x : series) names.push_back(x.name);
  return names;
}

template struct Observers<2>;
template struct Observers<3>;
template std::vector<Series> make_series<2>(const Scene&, const World<2>*, const Observers<2>*);
template std::vector<Series> make_series<3>(const Scene&, const World<3>*, const Observers<3>*);

}  // namespace mc
