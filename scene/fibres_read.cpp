// [[rigid_cell.fibres]] (Květoň Part II): the table of a fibre family's keys and its reader: the material, bound to
// rigid_cell::FibreMaterial, then how the family is placed, read by hand.
#include <sstream>
#include <string>

#include "scene/scene_read_parts.hpp"

namespace mc {

// Květoň Part II (5.1)-(5.10): the fibres' material fills rigid_cell::FibreMaterial; how they are placed is read by
// hand (rigid_cell/fibre_placement.hpp).
const KeyTable& fibres_keys() {
  using P = rigid_cell::FibreMaterial;
  static const KeyTable t = [] {
    KeyTable k = key_table<P>(
        "rigid_cell.fibres", "[[rigid_cell.fibres]] (Květoň Part II, 3D)",
        "A family of short straight fibres in the specimen, independent of the cells (§5.4): placed by volume "
        "fraction or count, isotropic, aligned or about a direction, drawn again when partly outside (Květoň's "
        "rule; the wall effect) or cut at the surface; or given one by one. Where a fibre crosses a facet that "
        "cracks it bridges the crack with the two-sided pull-out of Naaman's law (5.1)-(5.5), snubbing (5.9), "
        "spalling (5.8) and the inclined fibre's lower strength (5.10), on a virtual facet of its section "
        "(5.11). Histories fibres.bridging, fibres.pulled_out, fibres.ruptured, and "
        "section.<axis>_<at>mm.bridging_force per section.",
        {
            {.name = "name", .type = KeyType::Text, .doc = "the family's name", .shown_default = "fibres<i>"},
            {.name = "volume_fraction", .range = Range{0.0, 1.0, true, true}, .need = Need::Required,
             .when = "placed by volume fraction", .doc = "V_f: N = V_f V/(π d_f²/4 l_f) fibres", .example = "0.02"},
            {.name = "count", .type = KeyType::Integer, .range = Range::closed(1, 1e8), .need = Need::Required,
             .when = "placed by count", .doc = "the number of fibres instead of V_f"},
            {.name = "ends", .type = KeyType::Reals, .unit = Unit::Length, .need = Need::Required,
             .when = "given one by one", .doc = "x, y, z of end a then of end b, per fibre, instead of placing them"},
            {.name = "length", .unit = Unit::Length, .range = Range::positive(), .need = Need::Required,
             .when = "placed", .doc = "l_f, at most the specimen's longest extent", .example = "8 mm"},
            {.name = "orientation", .type = KeyType::Word, .when = "placed",
             .doc = "isotropic, aligned (to direction) or preferential (about direction, von Mises-Fisher κ)",
             .words = {"isotropic", "aligned", "preferential"}, .shown_default = "isotropic"},
            {.name = "direction", .type = KeyType::Reals, .need = Need::Required,
             .when = "orientation = aligned or preferential", .doc = "the axis (any length but zero)"},
            {.name = "concentration", .range = Range::positive(), .need = Need::Required,
             .when = "orientation = preferential", .doc = "κ of the density ∝ exp(κ cos θ) about the axis"},
            {.name = "boundary", .type = KeyType::Word, .when = "placed",
             .doc = "redraw: a fibre partly outside is drawn again (Květoň §5.4); cut: it is cut at the surface",
             .words = {"redraw", "cut"}, .shown_default = "redraw"},
            bound(&P::diameter, {.name = "diameter", .unit = Unit::Length, .range = Range::positive(),
                                 .need = Need::Required, .doc = "d_f", .example = "0.04 mm"}),
            bound(&P::modulus, {.name = "modulus", .unit = Unit::Pressure, .range = Range::positive(),
                                .need = Need::Required, .doc = "E_f (5.1)-(5.2)", .example = "30 GPa"}),
            bound(&P::tensile_strength, {.name = "tensile_strength", .unit = Unit::Pressure,
                                         .range = Range::positive(), .need = Need::Required,
                                         .doc = "f_tf, lowered at an inclined exit point (5.10)", .example = "1000 MPa"}),
            bound(&P::friction_stress, {.name = "friction_stress", .unit = Unit::Pressure, .range = Range::positive(),
                                        .need = Need::Required, .doc = "τ_0 of the debonded interface (5.1)-(5.3)",
                                        .example = "2 MPa"}),
            bound(&P::debonding_energy, {.name = "debonding_energy", .unit = Unit::EnergyPerArea,
                                         .range = Range::non_negative(),
                                         .doc = "G_d of the chemical bond (5.1)-(5.2)", .example = "5 N/m"}),
            bound(&P::slip_hardening, {.name = "slip_hardening",
                                       .doc = "β_f: > 0 the friction grows as the fibre slides, < 0 it falls (5.1)",
                                       .example = "0"}),
            bound(&P::spalling_coefficient, {.name = "spalling_coefficient", .range = Range::non_negative(),
                                             .doc = "k_sp of the spalling length (5.8); 0: none", .example = "500"}),
            bound(&P::snubbing_coefficient, {.name = "snubbing_coefficient", .range = Range::non_negative(),
                                             .doc = "k_sn of the snubbing factor (5.9)", .example = "0.1"}),
            bound(&P::rupture_coefficient, {.name = "rupture_coefficient", .range = Range::non_negative(),
                                            .doc = "k_rup of the inclined strength (5.10)", .example = "0.33"}),
        });
    k.alternatives = {{.keys = {"volume_fraction", "count", "ends"},
                       .one_required = true,
                       .why = "fibres are placed by volume fraction or by count, or given by their ends"}};
    return k;
  }();
  return t;
}

namespace scene_read {

// [[rigid_cell.fibres]]: each family's material (bound keys), then how it is placed.
void read_fibres(const std::vector<Table>& tables, double longest, Scene& s) {
  for (std::size_t i = 0; i < tables.size(); ++i) {
    const KeyReader k(tables[i], fibres_keys());
    if (s.dimension != 3)
      k.fail("volume_fraction", "fibres are segments in a volume: they need a 3D scene (dimension = 3)");
    FibreFamilySpec f;
    k.read_bound(&f.material);
    f.name = k.string("name", "fibres" + std::to_string(i));
    for (const FibreFamilySpec& o : s.rigid_cell->fibres)
      if (o.name == f.name) k.fail("name", "another fibre family is called '" + f.name + "'");
    if (k.has("ends")) {
      f.ends = k.numbers("ends", 0);
      if (f.ends.empty() || f.ends.size() % 6 != 0)
        k.fail("ends", "gives " + std::to_string(f.ends.size()) + " numbers: 6 per fibre (end a, then end b)");
      for (std::size_t j = 0; j < f.ends.size(); j += 6)
        if (f.ends[j] == f.ends[j + 3] && f.ends[j + 1] == f.ends[j + 4] && f.ends[j + 2] == f.ends[j + 5])
          k.fail("ends", "fibre " + std::to_string(j / 6) + " has both ends at one point");
    } else {
      if (k.has("volume_fraction")) f.volume_fraction = k.number("volume_fraction");
      if (k.has("count")) f.count = k.integer("count");
      f.length = k.number("length");
      if (f.length > longest) {
        std::ostringstream m;
        m << "a fibre of " << f.length << " m is longer than the specimen's longest extent, " << longest << " m";
        k.fail("length", m.str());
      }
      const std::string o = k.choice("orientation", "isotropic");
      using O = FibreFamilySpec::Orientation;
      f.orientation = o == "aligned" ? O::Aligned : o == "preferential" ? O::Preferential : O::Isotropic;
      if (f.orientation == O::Isotropic && k.has("direction"))
        k.fail("direction", "isotropic fibres have no axis: a direction applies to orientation = \"aligned\" or "
                            "\"preferential\" (remove it, or change the orientation)");
      if (f.orientation != O::Isotropic) {
        f.direction = k.numbers("direction", 3);
        if (f.direction[0] == 0 && f.direction[1] == 0 && f.direction[2] == 0)
          k.fail("direction", "the fibres' axis cannot be zero");
      }
      if (f.orientation == O::Preferential) f.concentration = k.number("concentration");
      f.cut = k.choice("boundary", "redraw") == "cut";
    }
    s.rigid_cell->fibres.push_back(f);
    tables[i].finish();
  }
}

}  // namespace scene_read

}  // namespace mc
