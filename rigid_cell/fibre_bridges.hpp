// The fibres' bridging forces on the rigid cells (Květoň §5.4, (5.11)): at each crossing of a fibre with a contact
// facet, a virtual facet of the fibre's section carries the fibre's force across the crack, between the two cells
// the facet parts, at the crossing point. A crossing takes part from the step after its facet has begun to crack (the fibres'
// stiffness in the elastic range is neglected, §5.4); from then on the facet's stress is the matrix's plus the
// fibres' (5.11). The opening a crossing sees is the jump Δ of the two cells' motions there: the flexible fibre is
// pulled out by w = |Δ| and pulls along Δ. The spalling length s_f (5.8) moves the exit points R and L s_f back
// along the fibre, R − L = Δ + 2 s_f f (5.7), which sets the angle φ'_f (5.6) of snubbing and strength, and it
// shortens the embedments. (Taken into the opening too, w = |R − L| − 2 s_f along R − L, it left a secant k = F/|R − L|
// far below the fibre's stiffness along f where Δ ≪ s_f, and a force 2 k s_f f of its own: the iteration of a
// 120 × 40 × 10 mm prism with k_sp 500 had not done 4 steps in 12 min; 11 s without spalling.)
//
// Several cracks on one fibre (§5.2): each crossing's embedment on a side is the fibre's length to its end there,
// less the lengths the other cracks on that side have debonded (from their last converged states), and less the
// spalling. (Cut at the next crack instead, the embedments of the §6.3 prism's fibres shrank to the 1-2 mm between
// facets as soon as those had begun to damage, before any had opened: one crack, and no hardening.) What the thesis
// leaves out, and this does too: debonded zones of two cracks that overlap, and a middle piece of fibre freed on
// both sides, which would slide with the cells rather than hold them.
//
// The secant iteration of a static or implicit step evaluates every crossing from its last converged state at each
// iterate (trial), puts each crossing's secant on its two cells, and keeps the trial once the step has converged. The
// fibre pulls with F along Δ, F Δ/|Δ| = k Δ, k = F/|Δ|: an isotropic spring k I on the jump (a zero-length cable's
// secant, positive definite whatever way the crack moves). A secant k e eᵀ along the pull alone, also exact at the
// iterate, turns with e from iterate to iterate: on the prism of §6.3 its iteration swung by 2 % of the fibres' force
// and never settled.
#pragma once
#include <cstddef>
#include <vector>

#include "rigid_cell/cell_assembly.hpp"
#include "rigid_cell/fibre_crossings.hpp"
#include "rigid_cell/fibre_pullout.hpp"

namespace mc::rigid_cell {

// One fibre crossing one contact facet.
template <int D>
struct BridgeSite {
  int fibre = -1;            // its fibre, in the order the fibres were placed
  int family = 0;            // the fibre's family: its material
  std::size_t contact = 0;   // the facet
  double at = 0;             // the crossing's distance from the fibre's end a [m]
  double length = 0;         // the fibre's length [m]
  bool a_on_cell_a = true;   // the fibre's end a lies on the side of the facet's cell a
  Vec<D> direction = Vec<D>::Zero();  // f: the fibre's unit direction from cell a's side to cell b's
  double theta = 0;          // the fibre's angle to the facet's normal [rad]
  Vec<D> point = Vec<D>::Zero();      // where it crosses [m]
};

// A crossing's state: the bridge's history, its spalling length and the force it carried when last evaluated, and
// the secant it was put into the stiffness with.
template <int D>
struct BridgeState {
  FibreBridge bridge;
  double spalling = 0;      // s_f (5.8) [m], from the normal force of the last converged state
  double normal_force = 0;  // P_N [N]
  double force = 0;         // F [N]
  double secant = 0;        // k [N/m]
  Vec<D> pull = Vec<D>::Zero();  // e: the unit vector of Δ, along which the fibre pulls
  double active = 0;        // 1 once its facet has begun to crack
};

// Each crossing (fibre_crossings.hpp) of the fibres, of the families `family` (per fibre), as a bridge site: the
// fibre's direction turned from cell a's side to cell b's, its angle to the normal, which of its ends is on a's side.
std::vector<BridgeSite<3>> bridge_sites(const std::vector<Fibre>& fibres, const std::vector<int>& family,
                                        const std::vector<FibreCrossing>& crossings);

template <int D>
class FibreBridges {
 public:
  static constexpr int kDofs = CellAssembly<D>::kDofs;
  using Element = Eigen::Matrix<double, 2 * kDofs, 2 * kDofs>;

  // `sites` ordered fibre by fibre, each fibre's from its end a; `materials` by family.
  FibreBridges(const Tessellation<D>& t, const CellAssembly<D>& model, std::vector<FibreMaterial> materials,
               std::vector<BridgeSite<D>> sites);

  std::size_t sites() const { return sites_.size(); }
  const BridgeSite<D>& site(std::size_t i) const { return sites_[i]; }
  const BridgeState<D>& state(std::size_t i) const { return trial_[i]; }
  const FibreMaterial& material(std::size_t i) const { return materials_[sites_[i].family]; }
  // The contacts some fibre crosses, ascending; bridged(c) is c's index among them, or −1.
  const std::vector<std::size_t>& contacts() const { return contacts_; }
  int bridged(std::size_t contact) const { return index_[contact]; }

  // Every crossing that takes part at the cells' displacements, from its converged state. Returns the largest change
  // of a crossing's force since the last evaluation, over the largest force (0 when none carries any). `monotone`
  // (a snap-through, static_solver.hpp): no crossing's secant rises above the last evaluation's, as no facet's damage
  // falls below it; the iteration then settles, with the force below the law where the secant was held (stored as
  // the force at that opening, so unloading and reloading go through it).
  double evaluate(const Eigen::VectorXd& u_cells, bool monotone = false);
  // Keeps the last evaluation, and lets the crossings of the facets whose converged damage is above zero take part
  // from the next step on. Within a step the crossings that take part stay the same: a crossing that joined as its
  // facet's damage rose above zero in an iterate would carry its force at once, unload the facet, whose damage
  // then fell back, and leave again (a cycle of four iterates on the prism of §6.3 that never settled).
  void commit(const std::vector<double>& damage);
  void discard() { trial_ = converged_; }

  // The bridges of contact (index among contacts()) as a stiffness on its two cells: Σ k G_fᵀ G_f.
  Element contact_stiffness(std::size_t j) const;
  // f += the secant forces Σ G_fᵀ k G_f q: what the stiffness above gives.
  void add_secant_forces(const Eigen::VectorXd& u_cells, Eigen::VectorXd& f) const;
  // f += Σ G_fᵀ k_b G_f q with every crossing at its stiffest, the bonded fibre's k_b = E_f A_f/d_f: above the secant
  // and the tangent of the law anywhere ((5.1)'s slope is largest at its start, 4·10⁴ N/m for §6.1's fibre against
  // k_b 9.4·10⁵ N/m), so that the stiffness it gives bounds the fibres' at any state.
  void add_stiffest_forces(const Eigen::VectorXd& u_cells, Eigen::VectorXd& f) const;
  // f += the crossings' forces of the last evaluation, Σ G_fᵀ F e.
  void add_forces(Eigen::VectorXd& f) const;
  // The force the bridges of a contact exert on its cell b (on a: its opposite) [N].
  Vec<D> contact_force(std::size_t contact) const;

  // The secants the stiffness is built from (one per crossing, after `from` numbers of the key), and setting them: a
  // checkpoint keeps those of the factorised stiffness.
  std::vector<double> stiffness_key() const;
  void set_stiffness_key(const std::vector<double>& key, std::size_t from);

  // The wall time spent so far evaluating the crossings, spreading their secants and adding their forces [s]: the
  // fibres' share of a run (serial calls; `evaluate` is parallel inside).
  double seconds() const { return seconds_; }

  // The converged states (a checkpoint's), and taking them back: throws InputError for another number of crossings.
  const std::vector<BridgeState<D>>& converged() const { return converged_; }
  void restore(std::vector<BridgeState<D>> states);

 private:
  using Jump = Eigen::Matrix<double, D, 2 * kDofs>;
  std::vector<FibreMaterial> materials_;
  std::vector<BridgeSite<D>> sites_;
  std::vector<Jump> jumps_;            // Δ = jump · (q_a, q_b) at each crossing point
  std::vector<std::pair<int, int>> cells_;  // each crossing's cells a, b
  std::vector<double> matrix_strength_;     // f_t of each crossing's facet (5.8)
  std::vector<Vec<D>> normals_;
  std::vector<std::size_t> contacts_;
  std::vector<int> index_;
  std::vector<std::size_t> first_, by_contact_;  // contact j's crossings: by_contact_[first_[j], first_[j + 1])
  std::vector<std::size_t> fibre_first_;          // crossings of one fibre: [fibre_first_[k], fibre_first_[k + 1])
  std::vector<std::size_t> fibre_of_site_;        // the index k of a crossing's fibre range
  std::vector<BridgeState<D>> converged_, trial_;
  mutable double seconds_ = 0;

  Eigen::Matrix<double, 2 * kDofs, 1> gather(std::size_t i, const Eigen::VectorXd& u_cells) const;
  template <typename Stiffness>
  void add_spring_forces(const Eigen::VectorXd& u_cells, Eigen::VectorXd& f, Stiffness k) const;
  void embedments(std::size_t i, double spalled, double out[2]) const;
};

extern template class FibreBridges<2>;
extern template class FibreBridges<3>;

}  // namespace mc::rigid_cell
