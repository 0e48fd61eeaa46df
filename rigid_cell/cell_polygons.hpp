// The cells of a tessellation as polygons that can be drawn (engine/system.hpp, CellGeometry): each cell keeps its own
// copy of its corners, so that its surface moves with it, by the same small rigid motion as the facet kinematics,
// u = U + Θ × (x − node) (Květoň (3.2)).
#pragma once
#include <Eigen/Core>
#include <vector>

#include "engine/system.hpp"
#include "rigid_cell/tessellation.hpp"

namespace mc::rigid_cell {

template <int D>
class CellPolygons {
 public:
  explicit CellPolygons(const Tessellation<D>& t);
  const CellGeometry& geometry() const { return geometry_; }
  // The corners (C·D, as CellGeometry::corner) moved with their cells' displacements u (cells × (D + rotations)).
  std::vector<double> moved(const Eigen::VectorXd& u) const;

 private:
  CellGeometry geometry_;
  std::vector<int> cell_;     // per corner, its cell
  std::vector<Vec<D>> node_;  // per cell, its node: the point its rotation turns about
};

extern template class CellPolygons<2>;
extern template class CellPolygons<3>;

}  // namespace mc::rigid_cell
