// The small rigid motion of Květoň (3.2): a body moving with (u, θ) at its node x carries a point c by
// u + θ × (c − x), the linear map A_x^c of its degrees of freedom. The facet kinematics (cell_assembly), the plates'
// constraints (plate_constraints) and the cells drawn in the output (cell_polygons) all move points by it.
#pragma once
#include <Eigen/Core>

#include "engine/dim.hpp"

namespace mc::rigid_cell {

template <int D>
Eigen::Matrix<double, D, D + Dim<D>::rot> point_motion(const Vec<D>& x, const Vec<D>& c) {
  Eigen::Matrix<double, D, D + Dim<D>::rot> A;
  A.template leftCols<D>().setIdentity();
  const Vec<D> r = c - x;
  if constexpr (D == 2) {
    A.col(2) << -r.y(), r.x();  // θ e_z × r
  } else {
    A.template rightCols<3>() << 0, r.z(), -r.y(),  //
        -r.z(), 0, r.x(),                           //
        r.y(), -r.x(), 0;                           // θ × r = −[r]× θ
  }
  return A;
}

}  // namespace mc::rigid_cell
