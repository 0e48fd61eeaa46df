#include "rigid_cell/box_strain.hpp"

#include <string>

#include <Eigen/LU>

#include "engine/errors.hpp"

namespace mc::rigid_cell {

template <int D>
std::vector<Eigen::VectorXd> box_strain_rows(const std::vector<Vec<D>>& nodes, const Vec<D>& lo, const Vec<D>& hi,
                                             int dofs_per_cell) {
  const char* flat = D == 2 ? "line" : "plane";
  std::vector<int> in;
  Vec<D> mean = Vec<D>::Zero();
  for (int i = 0; i < static_cast<int>(nodes.size()); ++i)
    if ((nodes[i].array() >= lo.array()).all() && (nodes[i].array() <= hi.array()).all())
      in.push_back(i), mean += nodes[i];
  if (in.size() < static_cast<std::size_t>(D + 1))
    throw InputError("[rigid_cell.strain]: its box holds " + std::to_string(in.size()) + " cell nodes; the mean " +
                     "strain needs at least " + std::to_string(D + 1) + " not on one " + flat);
  mean /= static_cast<double>(in.size());
  Eigen::Matrix<double, D, D> m = Eigen::Matrix<double, D, D>::Zero();
  for (int i : in) m += (nodes[i] - mean) * (nodes[i] - mean).transpose();
  const Eigen::FullPivLU<Eigen::Matrix<double, D, D>> lu(m);
  if (lu.rank() < D)
    throw InputError("[rigid_cell.strain]: the nodes in its box lie on one " + std::string(flat) + ": widen the box");
  const Eigen::Matrix<double, D, D> m_inv = lu.inverse();
  // The index pairs (a, b) of each component, in the order above.
  constexpr int kComponents = D == 2 ? 3 : 6;
  const int pairs[6][2] = {{0, 0}, {1, 1}, {D == 2 ? 0 : 2, D == 2 ? 1 : 2}, {1, 2}, {2, 0}, {0, 1}};
  std::vector<Eigen::VectorXd> rows;
  for (int c = 0; c < kComponents; ++c) {
    const int a = pairs[c][0], b = pairs[c][1];
    Eigen::VectorXd row = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(nodes.size()) * dofs_per_cell);
    for (int i : in) {
      const Vec<D> w = m_inv * (nodes[i] - mean);
      row[i * dofs_per_cell + a] += 0.5 * w[b];  // ε_ab = ½ (G_ab + G_ba)
      row[i * dofs_per_cell + b] += 0.5 * w[a];
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

template std::vector<Eigen::VectorXd> box_strain_rows<2>(const std::vector<Vec<2>>&, const Vec<2>&, const Vec<2>&,
                                                         int);
template std::vector<Eigen::VectorXd> box_strain_rows<3>(const std::vector<Vec<3>>&, const Vec<3>&, const Vec<3>&,
                                                         int);

}  // namespace mc::rigid_cell
