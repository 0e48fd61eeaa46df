#include "rigid_cell/tessellation.hpp"

#include <sstream>

#include "engine/errors.hpp"
#include "rigid_cell/node_placement.hpp"

namespace mc::rigid_cell {

template <int D>
void check_nodes(const std::vector<Vec<D>>& nodes, const SpecimenShape<D>& shape) {
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (!shape.inside(nodes[i])) {
      std::ostringstream m;
      m << "rigid cells: node " << i << " at (" << nodes[i].transpose() << ") m lies outside the specimen";
      throw InputError(m.str());
    }
  }
  const NearestPair p = nearest_pair(nodes);
  if (p.a >= 0 && p.distance < 1e-9 * (shape.hi() - shape.lo()).norm()) {
    std::ostringstream m;
    m << "rigid cells: nodes " << p.a << " and " << p.b << " coincide (" << p.distance << " m apart, at ("
      << nodes[p.a].transpose() << ") m)";
    throw InputError(m.str());
  }
}

template <int D>
void add_cell_masses(Tessellation<D>& t) {
  for (const auto& f : t.facets) {
    for (int c : {f.a, f.b}) {
      if (c < 0) continue;
      std::vector<Vec<D>> about(f.vertices.size());
      for (std::size_t j = 0; j < about.size(); ++j) about[j] = f.vertices[j] - t.cells[c].node;
      t.cells[c].mass += pyramid<D>(about);
    }
  }
}

template void add_cell_masses(Tessellation<2>&);
template void add_cell_masses(Tessellation<3>&);
template void check_nodes(const std::vector<Vec<2>>&, const SpecimenShape<2>&);
template void check_nodes(const std::vector<Vec<3>>&, const SpecimenShape<3>&);

}  // namespace mc::rigid_cell
