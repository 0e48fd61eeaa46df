#include "scene/rigid_cell_histories.hpp"

#include <sstream>

namespace mc {

std::string section_history_name(const SectionSpec& s) {
  std::ostringstream m;
  m << "section."
    << "xyz"[s.axis] << "_" << s.at * 1e3 << "mm";
  return m.str();
}

const char* const* strain_component_names(int dimension) {
  static const char* const two[] = {"xx", "yy", "xy"};
  static const char* const three[] = {"xx", "yy", "zz", "yz", "zx", "xy"};
  return dimension == 2 ? two : three;
}

std::vector<CellSeries> rigid_cell_series(const Scene& s) {
  using W = CellSeries::What;
  std::vector<CellSeries> out = {{W::Time, "time", "s"},
                                 {W::Step, "step", "-"},
                                 {W::Iterations, "iterations", "-"},
                                 {W::Residual, "residual", "-"},
                                 {W::Cuts, "step_cuts", "-"},
                                 {W::SnapThroughs, "snap_throughs", "-"},
                                 {W::FacetsDamaged, "facets.damaged", "-"},
                                 {W::FacetsCracked, "facets.cracked", "-"},
                                 {W::MaxDamage, "damage.max", "-"}};
  const int d = s.dimension, dofs = d == 2 ? 3 : 6;
  const char* names[2][6] = {{"x", "y", "z", "", "", ""}, {"x", "y", "z", "x", "y", "z"}};
  for (std::size_t g = 0; g < s.groups.size(); ++g) {
    const std::string pre = "group." + s.groups[g].name + ".";
    for (int k = 0; k < dofs; ++k) {
      const bool rotation = k >= d;
      const std::string axis = rotation ? (d == 2 ? "z" : names[1][k]) : names[0][k];
      const int p = static_cast<int>(g);
      out.push_back(
          {W::PlateReaction, pre + (rotation ? "moment_" : "reaction_") + axis, rotation ? "N m" : "N", p, k});
      out.push_back(
          {W::PlateDisplacement, pre + (rotation ? "rotation_" : "disp_") + axis, rotation ? "rad" : "m", p, k});
      if (s.rigid_cell && s.rigid_cell->dynamics && !rotation)
        out.push_back({W::PlateVelocity, pre + "velocity_" + axis, "m/s", p, k});
    }
  }
  for (std::size_t p = 0; p < s.probes.size(); ++p)
    out.push_back({W::Opening, s.probes[p].name, "m", static_cast<int>(p)});
  if (s.rigid_cell)
    for (std::size_t i = 0; i < s.rigid_cell->sections.size(); ++i) {
      const std::string name = section_history_name(s.rigid_cell->sections[i]);
      out.push_back({W::SectionStress, name, "Pa", static_cast<int>(i)});
      if (!s.rigid_cell->fibres.empty())
        out.push_back({W::SectionBridging, name + ".bridging_force", "N", static_cast<int>(i)});
    }
  if (s.rigid_cell && s.rigid_cell->strain)
    for (int c = 0; c < (d == 2 ? 3 : 6); ++c)
      out.push_back({W::Strain, std::string("strain.") + strain_component_names(d)[c], "-", -1, c});
  if (s.rigid_cell && !s.rigid_cell->fibres.empty()) {
    out.push_back({W::FibresBridging, "fibres.bridging", "-"});
    out.push_back({W::FibresPulledOut, "fibres.pulled_out", "-"});
    out.push_back({W::FibresRuptured, "fibres.ruptured", "-"});
  }
  if (s.rigid_cell && s.rigid_cell->energy) {
    out.push_back({W::BoundaryWork, "energy.boundary_work", "J"});
    out.push_back({W::StrainEnergy, "energy.strain", "J"});
    if (s.rigid_cell->dynamics) out.push_back({W::KineticEnergy, "energy.kinetic", "J"});
    out.push_back({W::Dissipated, "energy.dissipated", "J"});
  }
  return out;
}

}  // namespace mc
