// [specimen] and [mesostructure]: what the particles are and where the coarse aggregate goes.
#include "scene/scene_read_parts.hpp"

#include <array>
#include <sstream>

#include "engine/errors.hpp"

namespace mc::scene_read {

void read_specimen(const Table& root, Scene& s) {
  const Table t = root.table("specimen");
  SpecimenSpec& sp = s.specimen;
  const int d = s.dimension;
  const std::string kind = t.choice("kind", {"particles", "sphere_list", "output", "random_box", "lattice", "packing"});
  if (kind == "particles") {
    sp.kind = SpecimenSpec::Kind::Particles;
    for (const Table& p : t.tables("particles")) {
      InlineParticle ip;
      ip.x = vec(p, "x", Unit::Length, d);
      ip.radius = p.number("radius", Unit::Length, Range::positive());
      ip.v = p.has("velocity") ? vec(p, "velocity", Unit::Velocity, d) : std::vector<double>(d, 0.0);
      ip.w = p.has("angular_velocity") ? vec(p, "angular_velocity", Unit::Rate, d == 2 ? 1 : 3)
                                       : std::vector<double>(d == 2 ? 1 : 3, 0.0);
      ip.phase = s.phases.size() == 1 && !p.has("phase") ? 0 : phase_index(p, "phase", s.phases);
      sp.particles.push_back(ip);
      p.finish();
    }
    if (sp.particles.empty()) t.fail("particles", "kind = \"particles\" needs at least one [[specimen.particles]]");
  } else if (kind == "sphere_list" || kind == "output") {
    sp.kind = kind == "output" ? SpecimenSpec::Kind::Output : SpecimenSpec::Kind::SphereList;
    sp.file = relative_to(s.file, t.string("file"));
    if (kind == "sphere_list") {
      std::vector<std::string> names;
      for (const auto& p : s.phases) names.push_back(p.name);
      if (t.has("tag_phases")) {
        // tag_phases = "concrete,concrete,concrete": the phase of each tag, in tag order.
        std::stringstream ss(t.string("tag_phases"));
        std::string item;
        while (std::getline(ss, item, ',')) {
          item.erase(0, item.find_first_not_of(' '));
          item.erase(item.find_last_not_of(' ') + 1);
          const auto it = std::find(names.begin(), names.end(), item);
          if (it == names.end()) t.fail("tag_phases", "'" + item + "' is not a phase name");
          sp.tag_phase.push_back(static_cast<int>(it - names.begin()));
        }
      }
    }
  } else {
    sp.kind = kind == "lattice"   ? SpecimenSpec::Kind::Lattice
              : kind == "packing" ? SpecimenSpec::Kind::Packing
                                  : SpecimenSpec::Kind::RandomBox;
    sp.box_lo = vec(t, "lo", Unit::Length, d);
    sp.box_hi = vec(t, "hi", Unit::Length, d);
    check_box(t, "lo", sp.box_lo, "hi", sp.box_hi);
    if (kind == "lattice") {  // equal particles: hexagonal (2D) or face-centred cubic (3D), Tang §8.1.1
      sp.radius_min = sp.radius_max = t.number("radius", Unit::Length, Range::positive());
      for (int k = 0; k < d; ++k)
        if (sp.box_hi[k] - sp.box_lo[k] < 2 * sp.radius_min)
          t.fail("radius", "the box [lo, hi] must be at least one diameter wide in every direction");
    } else if (kind == "packing") {  // PFC material genesis, Tang §5.2
      sp.radius_min = t.number("radius_min", Unit::Length, Range::positive());
      sp.radius_ratio = t.number("radius_ratio", Unit::None, Range::at_least(1.0), 1.66);
      sp.porosity = t.number("porosity", Unit::None, Range{0.05, 0.9, true, true}, d == 2 ? 0.16 : 0.36);
      sp.stress = t.number("stress", Unit::Pressure, Range::positive(), 1e5);
      sp.modulus = t.number("modulus", Unit::Pressure, Range::positive());
      // The disc inscribed in the box (2D), the cylinder along z inscribed in it (3D): a Brazilian disc.
      sp.cylinder = t.choice("shape", {"box", d == 2 ? "disc" : "cylinder"}, "box") != "box";
      // Potyondy & Cundall 2004, genesis step 4: PFC uses n_f = 3. A floater fills its cage, whose largest ball
      // touches D + 1 neighbours: more cannot be asked of it without pressing it into them.
      sp.floater_contacts = static_cast<int>(t.integer("floater_contacts", Range::closed(0, d + 1), 0));
      for (int k = 0; k < d; ++k)
        if (sp.box_hi[k] - sp.box_lo[k] < 6 * sp.radius_min * sp.radius_ratio)
          t.fail("radius_min", "the box [lo, hi] must be at least three largest diameters wide in every direction");
    } else {
      sp.count = t.integer("count", Range::closed(1, 5e7));
      sp.radius_min = t.number("radius_min", Unit::Length, Range::positive());
      sp.radius_max = t.number("radius_max", Unit::Length, Range::at_least(sp.radius_min), sp.radius_min);
    }
    sp.phase = s.phases.size() == 1 && !t.has("phase") ? 0 : phase_index(t, "phase", s.phases);
  }
  for (const Table& c : t.tables("cuts")) {
    std::vector<double> lo = vec(c, "box_lo", Unit::Length, d), hi = vec(c, "box_hi", Unit::Length, d);
    check_box(c, "box_lo", lo, "box_hi", hi);
    sp.cuts.emplace_back(std::move(lo), std::move(hi));
    c.finish();
  }
  for (const Table& r : t.tables("regions")) {
    SpecimenSpec::Region g;
    g.lo = vec(r, "box_lo", Unit::Length, d), g.hi = vec(r, "box_hi", Unit::Length, d);
    check_box(r, "box_lo", g.lo, "box_hi", g.hi);
    g.phase = phase_index(r, "phase", s.phases);
    sp.regions.push_back(std::move(g));
    r.finish();
  }
  t.finish();
}

void read_mesostructure(const Table& root, Scene& s) {
  auto t = root.optional_table("mesostructure");
  if (!t) return;
  const int d = s.dimension;
  MesostructureSpec& m = s.mesostructure;
  m.present = true;
  // 0: no aggregate at all, the mortar alone (the same scene without its coarse aggregate, e.g. to check the
  // mortar's fracture energy in the beam it is part of).
  m.fraction = t->number("fraction", Unit::None, Range::open_fraction());
  // Tang Table 4.1 (4–8, 8–16, 16–32, 32–64 mm at 2:2:3:3), scaled by size_scale; or explicit ranges.
  const std::string grading = t->choice("grading", {"table_4_1", "ranges"}, "table_4_1");
  const double scale = t->number("size_scale", Unit::None, Range::positive(), 1.0);
  if (grading == "table_4_1") {
    for (auto [lo, hi, share] : {std::array<double, 3>{4, 8, 2}, {8, 16, 2}, {16, 32, 3}, {32, 64, 3}})
      m.ranges.push_back({lo * 1e-3 * scale, hi * 1e-3 * scale, share / 10});
  } else {
    double total = 0;
    for (const Table& r : t->tables("ranges")) {
      const double lo = r.number("lo", Unit::Length, Range::positive());
      const double hi = r.number("hi", Unit::Length, Range{lo, kInf, true, false});
      const double share = r.number("share", Unit::None, Range::positive());
      m.ranges.push_back({lo * scale, hi * scale, share});
      total += share;
      r.finish();
    }
    if (m.ranges.empty())
      t->fail("ranges", "grading = \"ranges\" needs at least one [[mesostructure.ranges]] with lo, hi, share");
    for (auto& r : m.ranges) r[2] /= total;
  }
  m.lo = opt_vec(*t, "lo", Unit::Length, d);
  m.hi = opt_vec(*t, "hi", Unit::Length, d);
  if (m.lo.empty() != m.hi.empty()) t->fail(m.lo.empty() ? "hi" : "lo", "lo and hi go together");
  if (!m.lo.empty()) check_box(*t, "lo", m.lo, "hi", m.hi);
  for (const Table& k : t->tables("keep_out")) {
    if (k.has("radius")) {
      m.keep_out_centre.push_back(vec(k, "centre", Unit::Length, d));
      m.keep_out_radius.push_back(k.number("radius", Unit::Length, Range::positive()));
    } else {
      m.keep_out_lo.push_back(vec(k, "box_lo", Unit::Length, d));
      m.keep_out_hi.push_back(vec(k, "box_hi", Unit::Length, d));
      check_box(k, "box_lo", m.keep_out_lo.back(), "box_hi", m.keep_out_hi.back());
    }
    k.finish();
  }
  m.cells_per_dmin = t->number("cells_per_dmin", Unit::None, Range::closed(5, 10), 5);
  m.mortar_phase = phase_index(*t, "mortar_phase", s.phases);
  m.aggregate_phase = phase_index(*t, "aggregate_phase", s.phases);
  if (m.mortar_phase == m.aggregate_phase) t->fail("aggregate_phase", "must differ from mortar_phase");
  t->finish();
}

}  // namespace mc::scene_read
