// [specimen] and [mesostructure]: what the particles are and where the coarse aggregate goes.
#include <array>
#include <sstream>

#include "engine/errors.hpp"
#include "scene/scene_read_parts.hpp"

namespace mc {

namespace {

constexpr std::string_view kBoxKinds = "kind = random_box, lattice or packing";

}  // namespace

const KeyTable& specimen_keys() {
  static const KeyTable t{
      .name = "specimen",
      .title = "[specimen]",
      .about = "The particles: given one by one, read from a file, or generated in a box (random placement, a "
               "regular lattice, or PFC's material genesis, Potyondy & Cundall 2004). Then, whatever the kind, "
               "[[specimen.cuts]] removes particles and [[specimen.regions]] gives particles another phase.",
      .keys = {
          {.name = "kind", .type = KeyType::Word,
           .need = Need::Required,
           .doc = "particles ([[specimen.particles]]), sphere_list (a file of `id x y z r tag` lines; 2D `id x y r "
                  "tag`), output (an earlier run's last frame, at rest), random_box (non-overlapping random "
                  "placement), lattice (equal particles touching their neighbours: hexagonal rows along x in 2D, "
                  "Tang §8.1.1, face-centred cubic in 3D), packing (PFC genesis: placed at half size, grown to the "
                  "porosity, then all radii changed uniformly until the isotropic stress is `stress`)",
           .words = {"particles", "sphere_list", "output", "random_box", "lattice", "packing"}},
          {.name = "file", .type = KeyType::Text,
           .need = Need::Required,
           .when = "kind = sphere_list or output",
           .doc = "the file, relative to the scene's folder"},
          {.name = "tag_phases", .type = KeyType::Text,
           .when = "kind = sphere_list",
           .doc = "\"a,b,c\": the phase of tag 0, 1, 2 …; absent: every particle in the first phase"},
          {.name = "lo", .type = KeyType::Reals,
           .unit = Unit::Length,
           .need = Need::Required,
           .when = kBoxKinds,
           .doc = "the box's low corner"},
          {.name = "hi", .type = KeyType::Reals, .unit = Unit::Length, .need = Need::Required, .when = kBoxKinds, .doc = "its high corner"},
          {.name = "radius",
           .unit = Unit::Length,
           .range = Range::positive(),
           .need = Need::Required,
           .when = "kind = lattice",
           .doc = "the particles' radius; the box is at least one diameter wide"},
          {.name = "count", .type = KeyType::Integer,
           .range = Range::closed(1, 5e7),
           .need = Need::Required,
           .when = "kind = random_box",
           .doc = "how many particles"},
          {.name = "radius_min",
           .unit = Unit::Length,
           .range = Range::positive(),
           .need = Need::Required,
           .when = "kind = random_box or packing",
           .doc = "the smallest radius (random_box: radii uniform in [radius_min, radius_max])"},
          {.name = "radius_max",
           .unit = Unit::Length,
           .range = Range::positive(),
           .when = "kind = random_box",
           .doc = "the largest radius, at least radius_min",
           .shown_default = "radius_min"},
          {.name = "radius_ratio",
           .range = Range::at_least(1.0),
           .when = "kind = packing",
           .doc = "R_max/R_min, radii uniform between; the box is at least three largest diameters wide",
           .fallback = 1.66},
          {.name = "porosity",
           .range = Range{0.05, 0.9, true, true},
           .when = "kind = packing",
           .doc = "of the grown packing; relieved, it loosens to its jammed porosity (0.17-0.18 for 0.16 asked, "
                  "2D). The final stress, the porosity, the floaters and the coordination number are /specimen "
                  "attributes (packing_*)",
           .shown_default = "0.16 in 2D, 0.36 in 3D"},
          {.name = "stress",
           .unit = Unit::Pressure,
           .range = Range::positive(),
           .when = "kind = packing",
           .doc = "the isotropic stress the radii are changed to",
           .fallback = 1e5},
          {.name = "modulus",
           .unit = Unit::Pressure,
           .range = Range::positive(),
           .need = Need::Required,
           .when = "kind = packing",
           .doc = "E_c of the linear contacts the genesis packs with: the material's"},
          {.name = "shape", .type = KeyType::Word,
           .when = "kind = packing",
           .doc = "box; disc (2D) or cylinder along z (3D), inscribed in the box: a Brazilian disc",
           .words = {"box", "disc", "cylinder"},
           .shown_default = "box"},
          {.name = "floater_contacts", .type = KeyType::Integer,
           .range = Range::closed(0, 4),
           .when = "kind = packing",
           .doc = "PFC's n_f (Potyondy & Cundall's genesis step 4; PFC uses 3), 0 to D + 1: each particle with "
                  "fewer neighbours (a floater) is moved and grown to the largest ball its cage holds, then the "
                  "packing is settled and brought back to `stress`; 0: off",
           .fallback = 0},
          {.name = "phase", .type = KeyType::Text,
           .need = Need::Required,
           .when = kBoxKinds,
           .doc = "the particles' phase; may be left out when the scene has one phase"},
      }};
  return t;
}

const KeyTable& specimen_particles_keys() {
  static const KeyTable t{
      .name = "specimen.particles",
      .title = "[[specimen.particles]]",
      .about = "One particle of a specimen of kind = \"particles\".",
      .keys = {
          {.name = "x", .type = KeyType::Reals, .unit = Unit::Length, .need = Need::Required, .doc = "its centre"},
          {.name = "radius", .unit = Unit::Length, .range = Range::positive(), .need = Need::Required, .doc = "R"},
          {.name = "velocity", .type = KeyType::Reals, .unit = Unit::Velocity, .doc = "at the start", .shown_default = "0"},
          {.name = "angular_velocity", .type = KeyType::Reals,
           .unit = Unit::Rate,
           .doc = "at the start [rad/s]; one component in 2D",
           .shown_default = "0"},
          {.name = "phase", .type = KeyType::Text, .doc = "its phase; may be left out when the scene has one phase",
           .shown_default = "the only phase"},
      }};
  return t;
}

const KeyTable& specimen_cuts_keys() {
  static const KeyTable t{
      .name = "specimen.cuts",
      .title = "[[specimen.cuts]]",
      .about = "A box whose particles (by centre) are removed once the specimen is made: a notch (Tang §7.1). The "
               "other particles keep their ids, so probes and groups by id stay on the same particles.",
      .keys = {
          {.name = "box_lo", .type = KeyType::Reals, .unit = Unit::Length, .need = Need::Required, .doc = "the box's low corner"},
          {.name = "box_hi", .type = KeyType::Reals, .unit = Unit::Length, .need = Need::Required, .doc = "its high corner"},
      }};
  return t;
}

const KeyTable& specimen_regions_keys() {
  static const KeyTable t{
      .name = "specimen.regions",
      .title = "[[specimen.regions]]",
      .about = "A box whose particles (by centre) join a phase, with its density: an FRP sheet on a concrete prism "
               "(Tang §8.1). Where boxes overlap, the later one wins. The coarse aggregate of [mesostructure] is "
               "laid afterwards, over its mortar phase only.",
      .keys = {
          {.name = "box_lo", .type = KeyType::Reals, .unit = Unit::Length, .need = Need::Required, .doc = "the box's low corner"},
          {.name = "box_hi", .type = KeyType::Reals, .unit = Unit::Length, .need = Need::Required, .doc = "its high corner"},
          {.name = "phase", .type = KeyType::Text, .need = Need::Required, .doc = "the phase they join"},
      }};
  return t;
}

const KeyTable& mesostructure_keys() {
  static const KeyTable t{
      .name = "mesostructure",
      .title = "[mesostructure]: coarse aggregate (Tang ch. 4)",
      .about = "Laid over the specimen by take-and-place on a background grid (Tang §4.2): random convex polygons "
               "(2D) or polyhedra (3D), largest size range first, never overlapping. Particles of mortar_phase "
               "whose centres fall in an aggregate become aggregate_phase; each bond and contact then takes the "
               "model of its phase pair (mortar, aggregate, and the interface between them).",
      .keys = {
          {.name = "fraction",
           .range = Range::open_fraction(),
           .need = Need::Required,
           .doc = "the aggregate's area (2D) or volume (3D) fraction of the domain; 0: the mortar alone"},
          {.name = "grading", .type = KeyType::Word,
           .doc = "table_4_1: Tang's Table 4.1 (4-8, 8-16, 16-32, 32-64 mm at 2:2:3:3) times size_scale; ranges: "
                  "[[mesostructure.ranges]]",
           .words = {"table_4_1", "ranges"},
           .shown_default = "table_4_1"},
          {.name = "size_scale", .range = Range::positive(), .doc = "every size range times this", .fallback = 1},
          {.name = "lo", .type = KeyType::Reals, .unit = Unit::Length, .doc = "the domain's low corner", .shown_default = "the specimen's box"},
          {.name = "hi", .type = KeyType::Reals, .unit = Unit::Length, .doc = "its high corner", .shown_default = "the specimen's box"},
          {.name = "cells_per_dmin",
           .range = Range::closed(5, 10),
           .doc = "background grid cells per smallest aggregate size, Tang (4.6)",
           .fallback = 5},
          {.name = "mortar_phase", .type = KeyType::Text, .need = Need::Required, .doc = "the phase the aggregate is laid over"},
          {.name = "aggregate_phase", .type = KeyType::Text, .need = Need::Required, .doc = "the phase its particles join"},
      }};
  return t;
}

const KeyTable& grading_ranges_keys() {
  static const KeyTable t{
      .name = "mesostructure.ranges",
      .title = "[[mesostructure.ranges]]",
      .about = "A size range of the aggregate's grading (grading = \"ranges\"); the shares are normalised.",
      .keys = {
          {.name = "lo", .unit = Unit::Length, .range = Range::positive(), .need = Need::Required,
           .doc = "the smallest size"},
          {.name = "hi", .unit = Unit::Length, .range = Range::positive(), .need = Need::Required,
           .doc = "the largest size, above lo"},
          {.name = "share", .range = Range::positive(), .need = Need::Required, .doc = "its share of the aggregate"},
      }};
  return t;
}

const KeyTable& keep_out_keys() {
  static const KeyTable t{
      .name = "mesostructure.keep_out",
      .title = "[[mesostructure.keep_out]]",
      .about = "A region that stays mortar: a box (around a notch) or a ball (around its tip).",
      .keys = {
          {.name = "centre", .type = KeyType::Reals, .unit = Unit::Length, .need = Need::Required, .when = "a ball", .doc = "its centre"},
          {.name = "radius", .unit = Unit::Length, .range = Range::positive(), .when = "a ball", .doc = "its radius"},
          {.name = "box_lo", .type = KeyType::Reals, .unit = Unit::Length, .need = Need::Required, .when = "a box", .doc = "its low corner"},
          {.name = "box_hi", .type = KeyType::Reals, .unit = Unit::Length, .need = Need::Required, .when = "a box", .doc = "its high corner"},
      }};
  return t;
}

namespace scene_read {

void read_specimen(const Table& root, Scene& s) {
  const Table t = table_of(root, specimen_keys());
  const KeyReader k(t, specimen_keys());
  SpecimenSpec& sp = s.specimen;
  const int d = s.dimension;
  const std::string kind = k.choice("kind");
  if (kind == "particles") {
    sp.kind = SpecimenSpec::Kind::Particles;
    for (const Table& pt : tables_of(t, specimen_particles_keys())) {
      const KeyReader p(pt, specimen_particles_keys());
      InlineParticle ip;
      ip.x = vec(p, "x", d);
      ip.radius = p.number("radius");
      ip.v = p.has("velocity") ? vec(p, "velocity", d) : std::vector<double>(d, 0.0);
      ip.w = p.has("angular_velocity") ? vec(p, "angular_velocity", d == 2 ? 1 : 3)
                                       : std::vector<double>(d == 2 ? 1 : 3, 0.0);
      ip.phase = s.phases.size() == 1 && !p.has("phase") ? 0 : phase_index(p, "phase", s.phases);
      sp.particles.push_back(ip);
      pt.finish();
    }
    if (sp.particles.empty())
      k.fail(specimen_particles_keys(), "kind = \"particles\" needs at least one [[specimen.particles]]");
  } else if (kind == "sphere_list" || kind == "output") {
    sp.kind = kind == "output" ? SpecimenSpec::Kind::Output : SpecimenSpec::Kind::SphereList;
    sp.file = relative_to(s.file, k.string("file"));
    if (kind == "sphere_list") {
      std::vector<std::string> names;
      for (const auto& p : s.phases) names.push_back(p.name);
      if (k.has("tag_phases")) {
        // tag_phases = "concrete,concrete,concrete": the phase of each tag, in tag order.
        std::stringstream ss(k.string("tag_phases"));
        std::string item;
        while (std::getline(ss, item, ',')) {
          item.erase(0, item.find_first_not_of(' '));
          item.erase(item.find_last_not_of(' ') + 1);
          const auto it = std::find(names.begin(), names.end(), item);
          if (it == names.end()) k.fail("tag_phases", "'" + item + "' is not a phase name");
          sp.tag_phase.push_back(static_cast<int>(it - names.begin()));
        }
      }
    }
  } else {
    sp.kind = kind == "lattice"   ? SpecimenSpec::Kind::Lattice
              : kind == "packing" ? SpecimenSpec::Kind::Packing
                                  : SpecimenSpec::Kind::RandomBox;
    sp.box_lo = vec(k, "lo", d);
    sp.box_hi = vec(k, "hi", d);
    check_box(k, "lo", sp.box_lo, "hi", sp.box_hi);
    if (kind == "lattice") {  // equal particles: hexagonal (2D) or face-centred cubic (3D), Tang §8.1.1
      sp.radius_min = sp.radius_max = k.number("radius");
      for (int i = 0; i < d; ++i)
        if (sp.box_hi[i] - sp.box_lo[i] < 2 * sp.radius_min)
          k.fail("radius", "the box [lo, hi] must be at least one diameter wide in every direction");
    } else if (kind == "packing") {  // PFC material genesis, Tang §5.2
      sp.radius_min = k.number("radius_min");
      sp.radius_ratio = k.number("radius_ratio");
      sp.porosity = k.number("porosity", d == 2 ? 0.16 : 0.36);
      sp.stress = k.number("stress");
      sp.modulus = k.number("modulus");
      // The disc inscribed in the box (2D), the cylinder along z inscribed in it (3D): a Brazilian disc.
      sp.cylinder = k.choice("shape", {"box", d == 2 ? "disc" : "cylinder"}, "box") != "box";
      // Potyondy & Cundall 2004, genesis step 4: PFC uses n_f = 3. A floater fills its cage, whose largest ball
      // touches D + 1 neighbours: more cannot be asked of it without pressing it into them.
      sp.floater_contacts = static_cast<int>(k.integer_within("floater_contacts", Range::closed(0, d + 1)));
      for (int i = 0; i < d; ++i)
        if (sp.box_hi[i] - sp.box_lo[i] < 6 * sp.radius_min * sp.radius_ratio)
          k.fail("radius_min", "the box [lo, hi] must be at least three largest diameters wide in every direction");
    } else {
      sp.count = k.integer("count");
      sp.radius_min = k.number("radius_min");
      sp.radius_max = k.number_within("radius_max", Range::at_least(sp.radius_min), sp.radius_min);
    }
    sp.phase = s.phases.size() == 1 && !k.has("phase") ? 0 : phase_index(k, "phase", s.phases);
  }
  for (const Table& ct : tables_of(t, specimen_cuts_keys())) {
    const KeyReader c(ct, specimen_cuts_keys());
    std::vector<double> lo = vec(c, "box_lo", d), hi = vec(c, "box_hi", d);
    check_box(c, "box_lo", lo, "box_hi", hi);
    sp.cuts.emplace_back(std::move(lo), std::move(hi));
    ct.finish();
  }
  for (const Table& rt : tables_of(t, specimen_regions_keys())) {
    const KeyReader r(rt, specimen_regions_keys());
    SpecimenSpec::Region g;
    g.lo = vec(r, "box_lo", d), g.hi = vec(r, "box_hi", d);
    check_box(r, "box_lo", g.lo, "box_hi", g.hi);
    g.phase = phase_index(r, "phase", s.phases);
    sp.regions.push_back(std::move(g));
    rt.finish();
  }
  t.finish();
}

void read_mesostructure(const Table& root, Scene& s) {
  auto t = optional_table_of(root, mesostructure_keys());
  if (!t) return;
  const KeyReader k(*t, mesostructure_keys());
  const int d = s.dimension;
  MesostructureSpec& m = s.mesostructure;
  m.present = true;
  // 0: no aggregate at all, the mortar alone (the same scene without its coarse aggregate, e.g. to check the
  // mortar's fracture energy in the beam it is part of).
  m.fraction = k.number("fraction");
  // Tang Table 4.1 (4–8, 8–16, 16–32, 32–64 mm at 2:2:3:3), scaled by size_scale; or explicit ranges.
  const std::string grading = k.choice("grading");
  const double scale = k.number("size_scale");
  if (grading == "table_4_1") {
    for (auto [lo, hi, share] : {std::array<double, 3>{4, 8, 2}, {8, 16, 2}, {16, 32, 3}, {32, 64, 3}})
      m.ranges.push_back({lo * 1e-3 * scale, hi * 1e-3 * scale, share / 10});
  } else {
    double total = 0;
    for (const Table& rt : tables_of(*t, grading_ranges_keys())) {
      const KeyReader r(rt, grading_ranges_keys());
      const double lo = r.number("lo");
      const double hi = r.number_within("hi", Range{lo, kInf, true, false});
      const double share = r.number("share");
      m.ranges.push_back({lo * scale, hi * scale, share});
      total += share;
      rt.finish();
    }
    if (m.ranges.empty())
      k.fail(grading_ranges_keys(), "grading = \"ranges\" needs at least one [[mesostructure.ranges]] with lo, hi, share");
    for (auto& r : m.ranges) r[2] /= total;
  }
  m.lo = opt_vec(k, "lo", d);
  m.hi = opt_vec(k, "hi", d);
  if (m.lo.empty() != m.hi.empty()) k.fail(m.lo.empty() ? "hi" : "lo", "lo and hi go together");
  if (!m.lo.empty()) check_box(k, "lo", m.lo, "hi", m.hi);
  for (const Table& kt : tables_of(*t, keep_out_keys())) {
    const KeyReader o(kt, keep_out_keys());
    if (o.has("radius")) {
      m.keep_out_centre.push_back(vec(o, "centre", d));
      m.keep_out_radius.push_back(o.required_number("radius"));
    } else {
      m.keep_out_lo.push_back(vec(o, "box_lo", d));
      m.keep_out_hi.push_back(vec(o, "box_hi", d));
      check_box(o, "box_lo", m.keep_out_lo.back(), "box_hi", m.keep_out_hi.back());
    }
    kt.finish();
  }
  m.cells_per_dmin = k.number("cells_per_dmin");
  m.mortar_phase = phase_index(k, "mortar_phase", s.phases);
  m.aggregate_phase = phase_index(k, "aggregate_phase", s.phases);
  if (m.mortar_phase == m.aggregate_phase) k.fail("aggregate_phase", "must differ from mortar_phase");
  t->finish();
}

}  // namespace scene_read

}  // namespace mc
