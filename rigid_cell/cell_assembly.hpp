// The rigid-cell model's mechanics on a tessellation (Květoň §3.2): each cell a rigid body with D translations and
// its rotations at its node; each contact facet's strain from the two cells' motion (3.1)-(3.5), its stress from
// the facet law, the cell forces and the secant stiffness by virtual work (3.9)-(3.10).
#pragma once
#include <Eigen/Core>
#include <utility>
#include <vector>

#include "rigid_cell/facet_law.hpp"
#include "rigid_cell/tessellation.hpp"

namespace mc::rigid_cell {

template <int D>
class CellAssembly {
 public:
  static constexpr int kDofs = D + Dim<D>::rot;  // per cell: translations, then rotations
  using Jump = Eigen::Matrix<double, 3, 2 * kDofs>;

  // One law per contact facet (t.facets[0, t.contacts)).
  CellAssembly(const Tessellation<D>& t, std::vector<FacetParams> params);

  int cells() const { return cells_; }
  int dofs() const { return kDofs * cells_; }
  std::size_t contacts() const { return contacts_.size(); }
  const FacetParams& params(std::size_t c) const { return params_[c]; }
  double length(std::size_t c) const { return contacts_[c].length; }
  std::pair<int, int> cells_of(std::size_t c) const { return {contacts_[c].a, contacts_[c].b}; }

  // The facet's local strain e = (e_N, e_M, e_L) (2D: e_L = 0) for the displacements u (cells × kDofs), (3.5).
  Eigen::Vector3d strain(std::size_t c, const Eigen::VectorXd& u) const;
  // The force the facet exerts on cell b (on a: its opposite) for u and the facet's damage: A Rᵀ s.
  Vec<D> force(std::size_t c, const Eigen::VectorXd& u, double damage) const;
  // The undamaged stiffness of contact c on the two cells' degrees of freedom (a's, then b's), (3.10); a damage D
  // scales it by 1 − D (3.11).
  Eigen::Matrix<double, 2 * kDofs, 2 * kDofs> element_stiffness(std::size_t c) const;
  // The cells' internal forces and moments for u and the damage of each contact.
  Eigen::VectorXd internal_forces(const Eigen::VectorXd& u, const std::vector<double>& damage) const;

 private:
  struct Contact {
    int a, b;
    double area, length;
    Eigen::Matrix<double, 3, D> R;  // local axes (n, m, l) as rows, (3.4)
    Jump G;  // R [−A_a | A_b]: the jump at the facet's centroid in local axes (n, m, l), (3.3)-(3.4)
  };
  int cells_;
  std::vector<Contact> contacts_;
  std::vector<FacetParams> params_;

  Eigen::Matrix<double, 2 * kDofs, 1> gather(const Contact& c, const Eigen::VectorXd& u) const;
  Eigen::Vector3d moduli(std::size_t c, double damage) const;
};

extern template class CellAssembly<2>;
extern template class CellAssembly<3>;

}  // namespace mc::rigid_cell
