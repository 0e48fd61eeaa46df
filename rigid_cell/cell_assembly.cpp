#include "rigid_cell/cell_assembly.hpp"

#include <string>

#include "engine/errors.hpp"
#include "rigid_cell/point_motion.hpp"

namespace mc::rigid_cell {

namespace {

// Local axes of a facet (3.4): its normal n and tangents m (and l in 3D), as the rows of R.
template <int D>
Eigen::Matrix<double, 3, D> local_axes(const Vec<D>& n) {
  Eigen::Matrix<double, 3, D> R = Eigen::Matrix<double, 3, D>::Zero();
  R.row(0) = n.transpose();
  if constexpr (D == 2) {
    R.row(1) << -n.y(), n.x();
  } else {
    const Vec<3> helper = std::abs(n.x()) < 0.9 ? Vec<3>::UnitX() : Vec<3>::UnitY();
    const Vec<3> m = n.cross(helper).normalized();
    R.row(1) = m.transpose();
    R.row(2) = n.cross(m).transpose();
  }
  return R;
}

}  // namespace

template <int D>
CellAssembly<D>::CellAssembly(const Tessellation<D>& t, std::vector<FacetParams> params)
    : cells_(static_cast<int>(t.cells.size())), params_(std::move(params)) {
  if (params_.size() != t.contacts) throw InputError("rigid cells: one facet law per contact facet is needed");
  contacts_.reserve(t.contacts);
  for (std::size_t k = 0; k < t.contacts; ++k) {
    const Facet<D>& f = t.facets[k];
    if (params_[k].tensile_strength > 0) {  // a facet whose softening would snap back is refused now, not when it cracks
      try {
        crack_band_slopes(params_[k], f.length);
      } catch (const InputError& e) {
        throw InputError("rigid cells: facet " + std::to_string(k) + " between cells " + std::to_string(f.a) + " and " +
                         std::to_string(f.b) + ": " + e.what());
      }
    }
    Contact c{f.a, f.b, f.area, f.length, local_axes<D>(f.normal), Jump::Zero()};
    Eigen::Matrix<double, D, 2 * kDofs> P;
    P << -point_motion<D>(t.cells[f.a].node, f.centroid), point_motion<D>(t.cells[f.b].node, f.centroid);
    c.G = c.R * P;
    contacts_.push_back(c);
  }
}

template <int D>
Eigen::Matrix<double, 2 * CellAssembly<D>::kDofs, 1> CellAssembly<D>::gather(const Contact& c,
                                                                             const Eigen::VectorXd& u) const {
  Eigen::Matrix<double, 2 * kDofs, 1> q;
  q << u.template segment<kDofs>(kDofs * c.a), u.template segment<kDofs>(kDofs * c.b);
  return q;
}

template <int D>
Eigen::Vector3d CellAssembly<D>::strain(std::size_t c, const Eigen::VectorXd& u) const {
  const Contact& k = contacts_[c];
  return k.G * gather(k, u) / k.length;  // (3.5)
}

template <int D>
Eigen::Vector3d CellAssembly<D>::moduli(std::size_t c, double damage) const {
  const FacetParams& p = params_[c];
  return (1 - damage) * p.E0 * Eigen::Vector3d(1, p.alpha, p.alpha);  // (3.6), (3.11)
}

template <int D>
Vec<D> CellAssembly<D>::force(std::size_t c, const Eigen::VectorXd& u, double damage) const {
  const Contact& k = contacts_[c];
  return -k.area * k.R.transpose() * moduli(c, damage).cwiseProduct(strain(c, u));
}

template <int D>
Eigen::Matrix<double, 2 * CellAssembly<D>::kDofs, 2 * CellAssembly<D>::kDofs> CellAssembly<D>::element_stiffness(
    std::size_t c) const {
  const Contact& k = contacts_[c];
  return k.area / k.length * k.G.transpose() * moduli(c, 0).asDiagonal() * k.G;  // K = A L Bᵀ Rᵀ E R B, B = G/L
}

template <int D>
Eigen::VectorXd CellAssembly<D>::internal_forces(const Eigen::VectorXd& u, const std::vector<double>& damage) const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(dofs());
  for (std::size_t c = 0; c < contacts_.size(); ++c) {
    const Contact& k = contacts_[c];
    const Eigen::Vector3d s = moduli(c, damage[c]).cwiseProduct(strain(c, u));
    const Eigen::Matrix<double, 2 * kDofs, 1> fe = k.area * k.G.transpose() * s;  // (3.9)
    f.template segment<kDofs>(kDofs * k.a) += fe.template head<kDofs>();
    f.template segment<kDofs>(kDofs * k.b) += fe.template tail<kDofs>();
  }
  return f;
}

template class CellAssembly<2>;
template class CellAssembly<3>;

}  // namespace mc::rigid_cell
