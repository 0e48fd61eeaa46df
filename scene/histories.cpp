#include "scene/histories.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "engine/errors.hpp"

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

// Šmilauer, "Simulation setup" (uniaxial tension/compression): the supports at both ends strain the specimen
// along `axis`. Axial force: the mean of the two supports' reactions, F = ½(R⁺ − R⁻); stress F/A with A the
// bounding box's cross-section (or the scene's); strain and length from the supports' mean positions; lateral
// strain: the slope of the regression of Δx on x (and Δy on y, averaged) over the particles of the middle half
// of the specimen's length, away from the boundary effects at the supports. Signs: positive in the loading sense
// (the lateral strain: expansion positive).
template <int D, class Add>
void add_uniaxial(const Scene& s, const World<D>* w, Add& add) {
  const UniaxialSpec& u = s.uniaxial;
  const int ax = u.axis;
  const double sense = u.tension ? 1.0 : -1.0;
  struct Setup {
    std::vector<int> lo, hi, inner;  // support members, inner particles
    std::vector<Vec<D>> x0;          // all particles at the start
    double length0 = 0, area = 0;
  };
  auto st = std::make_shared<Setup>();
  auto mean_axial = [ax](const std::vector<int>& m, const std::vector<Vec<D>>& x) {
    double z = 0;
    for (int i : m) z += x[i][ax];
    return z / static_cast<double>(m.size());
  };
  if (w) {
    const auto& p = w->particles;
    st->lo = w->groups[u.supports[0]], st->hi = w->groups[u.supports[1]];
    if (st->lo.empty() || st->hi.empty())
      throw InputError(s.file + ": [uniaxial] supports: group '" + s.groups[u.supports[st->lo.empty() ? 0 : 1]].name +
                       "' selects no particle");
    st->x0 = p.x;
    const double zlo = mean_axial(st->lo, p.x), zhi = mean_axial(st->hi, p.x);
    st->length0 = zhi - zlo;
    if (!(st->length0 > 0))
      throw InputError(s.file + ": [uniaxial] supports: the first group must lie at the negative end of the " +
                       std::string(1, char('x' + ax)) + " axis, the second at the positive end");
    Vec<D> lo = Vec<D>::Constant(kInf), hi = Vec<D>::Constant(-kInf);
    for (int i = 0; i < p.size(); ++i) {
      lo = lo.cwiseMin(p.x[i] - Vec<D>::Constant(p.radius[i]));
      hi = hi.cwiseMax(p.x[i] + Vec<D>::Constant(p.radius[i]));
      if (std::abs(p.x[i][ax] - 0.5 * (zlo + zhi)) < 0.25 * st->length0) st->inner.push_back(i);
    }
    st->area = u.area;
    if (st->area == 0) {
      st->area = 1;
      for (int k = 0; k < D; ++k)
        if (k != ax) st->area *= hi[k] - lo[k];
    }
  }
  add("uniaxial.stress", "Pa", [w, st, ax, sense] {
    double rp = 0, rm = 0;  // reactions along the axis: what holds each support on its motion
    for (int i : st->hi) rp -= w->particles.f[i][ax];
    for (int i : st->lo) rm -= w->particles.f[i][ax];
    return sense * 0.5 * (rp - rm) / st->area;
  });
  add("uniaxial.length", "m", [w, st, ax, mean_axial] {
    return mean_axial(st->hi, w->particles.x) - mean_axial(st->lo, w->particles.x);
  });
  add("uniaxial.strain", "-", [w, st, ax, sense, mean_axial] {
    const double l = mean_axial(st->hi, w->particles.x) - mean_axial(st->lo, w->particles.x);
    return sense * (l - st->length0) / st->length0;
  });
  add("uniaxial.lateral_strain", "-", [w, st, ax] {
    double sum = 0;
    int n = 0;
    for (int k = 0; k < D; ++k) {
      if (k == ax) continue;
      double m0 = 0, md = 0;
      for (int i : st->inner) m0 += st->x0[i][k], md += w->particles.x[i][k] - st->x0[i][k];
      m0 /= static_cast<double>(st->inner.size()), md /= static_cast<double>(st->inner.size());
      double sxy = 0, sxx = 0;
      for (int i : st->inner) {
        const double a = st->x0[i][k] - m0, b = w->particles.x[i][k] - st->x0[i][k] - md;
        sxy += a * b, sxx += a * a;
      }
      sum += sxx > 0 ? sxy / sxx : 0.0;
      ++n;
    }
    return sum / n;
  });
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
  if (s.uniaxial.supports[0] >= 0) add_uniaxial<D>(s, w, add);
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
