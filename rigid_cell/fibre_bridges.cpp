#include "rigid_cell/fibre_bridges.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "engine/errors.hpp"
#include "rigid_cell/point_motion.hpp"

namespace mc::rigid_cell {

namespace {
// Adds the wall time of its scope to a total: what the fibres cost a run (FibreBridges::seconds).
class Charged {
 public:
  explicit Charged(double& total) : total_(total), start_(std::chrono::steady_clock::now()) {}
  ~Charged() { total_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }
  Charged(const Charged&) = delete;
  Charged& operator=(const Charged&) = delete;

 private:
  double& total_;
  std::chrono::steady_clock::time_point start_;
};
}  // namespace

std::vector<BridgeSite<3>> bridge_sites(const std::vector<Fibre>& fibres, const std::vector<int>& family,
                                        const std::vector<FibreCrossing>& crossings) {
  std::vector<BridgeSite<3>> sites;
  sites.reserve(crossings.size());
  for (const FibreCrossing& c : crossings) {
    const Fibre& f = fibres[c.fibre];
    const Vec<3> u = (f.b - f.a).normalized();
    BridgeSite<3> s;
    s.fibre = c.fibre, s.family = family[c.fibre], s.contact = static_cast<std::size_t>(c.facet);
    s.at = c.at, s.length = (f.b - f.a).norm(), s.a_on_cell_a = c.cosine > 0;
    s.direction = c.cosine > 0 ? u : Vec<3>(-u);
    s.theta = std::acos(std::min(1.0, std::abs(c.cosine)));
    s.point = c.point;
    sites.push_back(s);
  }
  return sites;
}

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

// §5.2: each side reaches to the fibre's end, less the lengths the other cracks on that side have debonded (both
// sides of each, from their converged states), less the spalling at this exit point.
template <int D>
void FibreBridges<D>::embedments(std::size_t i, double spalled, double out[2]) const {
  const BridgeSite<D>& s = sites_[i];
  const std::size_t k = fibre_of_site_[i], begin = fibre_first_[k], end = fibre_first_[k + 1];
  auto debonded = [&](std::size_t j) {
    const FibreMaterial& f = materials_[sites_[j].family];
    const TwoSidedPullout& t = converged_[j].bridge.sides;
    return side_debonded_length(f, t.embedment[0], t.pullout[0]) + side_debonded_length(f, t.embedment[1], t.pullout[1]);
  };
  double towards_a = s.at, towards_b = s.length - s.at;
  for (std::size_t j = begin; j < end; ++j) {
    if (j == i || converged_[j].active == 0) continue;
    (j < i ? towards_a : towards_b) -= debonded(j);
  }
  out[s.a_on_cell_a ? 0 : 1] = std::max(0.0, towards_a - spalled);
  out[s.a_on_cell_a ? 1 : 0] = std::max(0.0, towards_b - spalled);
}

template <int D>
double FibreBridges<D>::evaluate(const Eigen::VectorXd& u_cells, bool monotone) {
  const Charged charged(seconds_);
  double change = 0, largest = 0;
  // Each crossing from its own converged state and its fibre's other crossings' converged ones: independent, so
  // spread over the threads with the same result for any count (the maxima are order-free). Nothing may throw out
  // of the parallel loop (it would end the process): the first crossing whose opening is not finite is kept.
  const auto n = static_cast<std::ptrdiff_t>(sites_.size());
  std::ptrdiff_t not_finite = n;
#pragma omp parallel for schedule(dynamic, 256) reduction(max : change, largest) reduction(min : not_finite)
  for (std::ptrdiff_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    const BridgeSite<D>& s = sites_[i];
    BridgeState<D> next = converged_[i];
    if (next.active != 0) {
      const FibreMaterial& f = materials_[s.family];
      next.spalling = spalling_length(f, converged_[i].normal_force, s.theta, matrix_strength_[i]);  // (5.8)
      embedments(i, next.spalling, next.bridge.sides.embedment);
      const Vec<D> jump = jumps_[i] * gather(i, u_cells);
      const double length = jump.norm();
      if (!std::isfinite(length)) {
        not_finite = std::min(not_finite, ii);
        continue;
      }
      next.force = 0, next.secant = 0;
      const bool anchored = next.bridge.sides.embedment[0] > 0 && next.bridge.sides.embedment[1] > 0;
      if (length > 0 && anchored) {
        next.pull = jump / length;
        const Vec<D> exits = jump + 2 * next.spalling * s.direction;  // R − L (5.7)
        const double phi = std::acos(std::clamp(exits.normalized().dot(s.direction), -1.0, 1.0));  // (5.6)
        const double w = length;
        next.force = bridge_force(f, next.bridge, w, phi);
        next.secant = next.force / length;
        if (monotone && next.secant > trial_[i].secant) {  // a snap-through: the secant only falls
          next.secant = trial_[i].secant;
          next.force = next.bridge.force = next.secant * length;
        }
        next.normal_force = next.force * std::abs(next.pull.dot(normals_[i]));
      }
    }
    change = std::max(change, std::abs(next.force - trial_[i].force));
    largest = std::max(largest, next.force);
    trial_[i] = next;
  }
  if (not_finite < n) {
    const BridgeSite<D>& s = sites_[static_cast<std::size_t>(not_finite)];
    throw InstabilityError("rigid cells: the crossing of fibre " + std::to_string(s.fibre) + " with facet " +
                           std::to_string(s.contact) +
                           " opens by a displacement that is not finite: the cells' motion diverged (a load step "
                           "far too large for the specimen, or a plate driven without bound)");
  }
  return largest > 0 ? change / largest : 0.0;
}

template <int D>
typename FibreBridges<D>::Element FibreBridges<D>::contact_stiffness(std::size_t j) const {
  const Charged charged(seconds_);
  Element K = Element::Zero();
  for (std::size_t k = first_[j]; k < first_[j + 1]; ++k) {
    const std::size_t i = by_contact_[k];
    if (trial_[i].secant == 0) continue;
    // A 12 × 3 by 3 × 12 product: coefficient by coefficient (Eigen's blocked product for it took most of a step).
    K.noalias() += trial_[i].secant * jumps_[i].transpose().lazyProduct(jumps_[i]);
  }
  return K;
}

// f += Σ G_fᵀ k_i G_f q: each crossing as an isotropic spring k_i on the jump at its point.
template <int D>
template <typename Stiffness>
void FibreBridges<D>::add_spring_forces(const Eigen::VectorXd& u_cells, Eigen::VectorXd& f, Stiffness k) const {
  for (std::size_t i = 0; i < sites_.size(); ++i) {
    const double ki = k(i);
    if (ki == 0) continue;
    const Eigen::Matrix<double, 2 * kDofs, 1> fe = jumps_[i].transpose() * (ki * (jumps_[i] * gather(i, u_cells)));
    f.template segment<kDofs>(kDofs * cells_[i].first) += fe.template head<kDofs>();
    f.template segment<kDofs>(kDofs * cells_[i].second) += fe.template tail<kDofs>();
  }
}

template <int D>
void FibreBridges<D>::add_secant_forces(const Eigen::VectorXd& u_cells, Eigen::VectorXd& f) const {
  const Charged charged(seconds_);
  add_spring_forces(u_cells, f, [&](std::size_t i) { return trial_[i].secant; });
}

template <int D>
void FibreBridges<D>::add_stiffest_forces(const Eigen::VectorXd& u_cells, Eigen::VectorXd& f) const {
  add_spring_forces(u_cells, f, [&](std::size_t i) { return bonded_stiffness(materials_[sites_[i].family]); });
}

template <int D>
void FibreBridges<D>::add_forces(Eigen::VectorXd& f) const {
  const Charged charged(seconds_);
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
  key.reserve(trial_.size());
  for (const BridgeState<D>& s : trial_) key.push_back(s.secant);
  return key;
}

template <int D>
void FibreBridges<D>::set_stiffness_key(const std::vector<double>& key, std::size_t from) {
  if (key.size() != from + trial_.size())
    throw InputError("its checkpoint holds other fibres than the scene places; resume with the scene that wrote it");
  for (std::size_t i = 0; i < trial_.size(); ++i) trial_[i].secant = key[from + i];
}

template <int D>
void FibreBridges<D>::commit(const std::vector<double>& damage) {
  converged_ = trial_;
  for (std::size_t i = 0; i < sites_.size(); ++i)
    if (converged_[i].active == 0 && damage[sites_[i].contact] > 0) trial_[i].active = converged_[i].active = 1;
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
