#include "rigid_cell/fibre_bridges.hpp"

#include <algorithm>
#include <cmath>

#include "engine/errors.hpp"
#include "rigid_cell/point_motion.hpp"

namespace mc::rigid_cell {

template <int D>
FibreBridges<D>::FibreBridges(const Tessellation<D>& t, const CellAssembly<D>& model,
                              std::vector<FibreMaterial> materials, std::vector<BridgeSite<D>> sites)
    : materials_(std::move(materials)), sites_(std::move(sites)), index_(model.contacts(), -1) {
  for (std::size_t i = 0; i < sites_.size(); ++i) {
    const BridgeSite<D>& s = sites_[i];
    if (s.contact >= model.contacts() || s.family < 0 || static_cast<std::size_t>(s.family) >= materials_.size())
      throw InputError("fibre " + std::to_string(s.fibre) + ": a crossing names no contact facet or no family");
    const auto [a, b] = model.cells_of(s.contact);
    Jump jump;
    jump << -point_motion<D>(t.cells[a].node, s.point), point_motion<D>(t.cells[b].node, s.point);
    jumps_.push_back(jump);
    cells_.emplace_back(a, b);
    matrix_strength_.push_back(model.params(s.contact).tensile_strength);
    normals_.push_back(t.facets[s.contact].normal);
    if (i == 0 || s.fibre != sites_[i - 1].fibre) fibre_first_.push_back(i);
    fibre_of_site_.push_back(fibre_first_.size() - 1);
    contacts_.push_back(s.contact);
  }
  fibre_first_.push_back(sites_.size());
  std::sort(contacts_.begin(), contacts_.end());
  contacts_.erase(std::unique(contacts_.begin(), contacts_.end()), contacts_.end());
  for (std::size_t j = 0; j < contacts_.size(); ++j) index_[contacts_[j]] = static_cast<int>(j);
  first_.assign(contacts_.size() + 1, 0);
  for (const BridgeSite<D>& s : sites_) ++first_[index_[s.contact] + 1];
  for (std::size_t j = 0; j < contacts_.size(); ++j) first_[j + 1] += first_[j];
  by_contact_.resize(sites_.size());
  std::vector<std::size_t> next(first_.begin(), first_.end() - 1);
  for (std::size_t i = 0; i < sites_.size(); ++i) by_contact_[next[index_[sites_[i].contact]]++] = i;
  converged_.assign(sites_.size(), BridgeState<D>{});
  trial_ = converged_;
}

template <int D>
Eigen::Matrix<double, 2 * FibreBridges<D>::kDofs, 1> FibreBridges<D>::gather(std::size_t i,
                                                                            const Eigen::VectorXd& u_cells) const {
  Eigen::Matrix<double, 2 * kDofs, 1> q;
  q << u_cells.template segment<kDofs>(kDofs * cells_[i].first), u_cells.template segment<kDofs>(kDofs * cells_[i].second);
  return q;
}

// §5.2: each side reaches to the nearest cracked crossing of the fibre beyond it, less what that one has debonded
// towards this one (its converged state), or to the fibre's end; then less the spalling at this exit point.
template <int D>
void FibreBridges<D>::embedments(std::size_t i, double spalled, double out[2]) const {
  const BridgeSite<D>& s = sites_[i];
  const std::size_t k = fibre_of_site_[i], begin = fibre_first_[k], end = fibre_first_[k + 1];
  auto debonded_towards = [&](std::size_t j, bool towards_end_b) {
    const BridgeSite<D>& o = sites_[j];
    const int side = (o.a_on_cell_a == towards_end_b) ? 1 : 0;  // the side of j on which this crossing lies
    const TwoSidedPullout& t = converged_[j].bridge.sides;
    return side_debonded_length(materials_[o.family], t.embedment[side], t.pullout[side]);
  };
  double towards_a = s.at, towards_b = s.length - s.at;
  for (std::size_t j = i; j-- > begin;)
    if (converged_[j].active != 0) {
      towards_a = s.at - sites_[j].at - debonded_towards(j, true);
      break;
    }
  for (std::size_t j = i + 1; j < end; ++j)
    if (converged_[j].active != 0) {
      towards_b = sites_[j].at - s.at - debonded_towards(j, false);
      break;
    }
  out[s.a_on_cell_a ? 0 : 1] = std::max(0.0, towards_a - spalled);
  out[s.a_on_cell_a ? 1 : 0] = std::max(0.0, towards_b - spalled);
}

template <int D>
double FibreBridges<D>::evaluate(const Eigen::VectorXd& u_cells, const std::vector<double>& damage) {
  double change = 0, largest = 0;
  for (std::size_t i = 0; i < sites_.size(); ++i) {
    const BridgeSite<D>& s = sites_[i];
    BridgeState<D> next = converged_[i];
    if (next.active == 0 && damage[s.contact] > 0) next.active = 1;
    if (next.active != 0) {
      const FibreMaterial& f = materials_[s.family];
      next.spalling = spalling_length(f, converged_[i].normal_force, s.theta, matrix_strength_[i]);  // (5.8)
      embedments(i, next.spalling, next.bridge.sides.embedment);
      const Vec<D> jump = jumps_[i] * gather(i, u_cells);
      const Vec<D> span = jump + 2 * next.spalling * s.direction;  // R − L (5.7)
      const double length = span.norm();
      next.force = 0, next.secant = 0;
      const bool anchored = next.bridge.sides.embedment[0] > 0 && next.bridge.sides.embedment[1] > 0;
      if (length > 0 && anchored) {
        next.pull = span / length;
        const double phi = std::acos(std::clamp(next.pull.dot(s.direction), -1.0, 1.0));  // (5.6)
        const double w = std::max(0.0, length - 2 * next.spalling);
        next.force = bridge_force(f, next.bridge, w, phi);
        const double along = next.pull.dot(jump);
        next.secant = along > 0 ? next.force / along : 0.0;
        next.normal_force = next.force * std::abs(next.pull.dot(normals_[i]));
      }
    }
    change = std::max(change, std::abs(next.force - trial_[i].force));
    largest = std::max(largest, next.force);
    trial_[i] = next;
  }
  return largest > 0 ? change / largest : 0.0;
}

template <int D>
typename FibreBridges<D>::Element FibreBridges<D>::contact_stiffness(std::size_t j) const {
  Element K = Element::Zero();
  for (std::size_t k = first_[j]; k < first_[j + 1]; ++k) {
    const std::size_t i = by_contact_[k];
    if (trial_[i].secant == 0) continue;
    const Eigen::Matrix<double, 2 * kDofs, 1> g = jumps_[i].transpose() * trial_[i].pull;
    K.noalias() += trial_[i].secant * g * g.transpose();
  }
  return K;
}

template <int D>
void FibreBridges<D>::add_secant_forces(const Eigen::VectorXd& u_cells, Eigen::VectorXd& f) const {
  for (std::size_t i = 0; i < sites_.size(); ++i) {
    if (trial_[i].secant == 0) continue;
    const Eigen::Matrix<double, 2 * kDofs, 1> g = jumps_[i].transpose() * trial_[i].pull;
    const Eigen::Matrix<double, 2 * kDofs, 1> fe = trial_[i].secant * g.dot(gather(i, u_cells)) * g;
    f.template segment<kDofs>(kDofs * cells_[i].first) += fe.template head<kDofs>();
    f.template segment<kDofs>(kDofs * cells_[i].second) += fe.template tail<kDofs>();
  }
}

template <int D>
void FibreBridges<D>::add_forces(Eigen::VectorXd& f) const {
  for (std::size_t i = 0; i < sites_.size(); ++i) {
    if (trial_[i].force == 0) continue;
    const Eigen::Matrix<double, 2 * kDofs, 1> fe = trial_[i].force * (jumps_[i].transpose() * trial_[i].pull);
    f.template segment<kDofs>(kDofs * cells_[i].first) += fe.template head<kDofs>();
    f.template segment<kDofs>(kDofs * cells_[i].second) += fe.template tail<kDofs>();
  }
}

template <int D>
Vec<D> FibreBridges<D>::contact_force(std::size_t contact) const {
  Vec<D> F = Vec<D>::Zero();
  const int j = index_[contact];
  if (j < 0) return F;
  for (std::size_t k = first_[j]; k < first_[j + 1]; ++k) F -= trial_[by_contact_[k]].force * trial_[by_contact_[k]].pull;
  return F;
}

template <int D>
std::vector<double> FibreBridges<D>::stiffness_key() const {
  std::vector<double> key;
  key.reserve((D + 1) * trial_.size());
  for (const BridgeState<D>& s : trial_) {
    key.push_back(s.secant);
    for (int k = 0; k < D; ++k) key.push_back(s.pull[k]);
  }
  return key;
}

template <int D>
void FibreBridges<D>::set_stiffness_key(const std::vector<double>& key, std::size_t from) {
  if (key.size() != from + (D + 1) * trial_.size())
    throw InputError("its checkpoint holds other fibres than the scene places; resume with the scene that wrote it");
  for (std::size_t i = 0; i < trial_.size(); ++i) {
    trial_[i].secant = key[from + (D + 1) * i];
    for (int k = 0; k < D; ++k) trial_[i].pull[k] = key[from + (D + 1) * i + 1 + k];
  }
}

template <int D>
void FibreBridges<D>::restore(std::vector<BridgeState<D>> states) {
  if (states.size() != sites_.size())
    throw InputError("its checkpoint holds other fibres than the scene places; resume with the scene that wrote it");
  converged_ = std::move(states);
  trial_ = converged_;
}

template class FibreBridges<2>;
template class FibreBridges<3>;

}  // namespace mc::rigid_cell
