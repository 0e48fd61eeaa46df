// The spatial random field of Květoň §3.4: one field h(x) of mean 1 scales each facet's tensile strength and
// fracture energy, f_t(x) = f̄_t h(x), G_t(x) = Ḡ_t h(x)² (3.21). Its autocorrelation is the squared exponential
// ρ(Δx) = exp(−|Δx|²/l_c²) and its distribution Gaussian with a grafted Weibull left tail (grafted_distribution.hpp).
//
// A standard Gaussian field is expanded on a regular grid over a box by Karhunen–Loève: ρ is a product of one
// factor per axis, so the grid's correlation matrix is the Kronecker product of each axis's, whose eigenpairs
// (λ_i, φ_i) give the grid's as products (Vořechovský 2008); the expansion keeps the largest products. It is
// carried to any point by EOLE (Li & Der Kiureghian 1993), ĝ(x) = Σ_k ξ_k/√λ_k φ_kᵀ C_{x,grid}, in which
// C_{x,grid} is a product over axes as well, and mapped to h by h = F⁻¹(Φ(ĝ)).
#pragma once
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "engine/dim.hpp"
#include "rigid_cell/grafted_distribution.hpp"

namespace mc::rigid_cell {

struct RandomFieldParams {
  double correlation_length = 0;  // l_c [m]
  double deviation = 0;           // standard deviation of h [-] (its mean is 1)
  double grid_spacing = 0;        // of the grid expanded on [m]; each axis's nodes are as far apart or closer
  // The modes kept carry this fraction of the grid's variance (its trace): the count needed grows as
  // (box/l_c)^D, and a fraction keeps the truncation the same for any box. The modes dropped are the shortest
  // waves; at 0.99 the field, set back to unit variance, correlates at l_c at 0.373 instead of e⁻¹ = 0.368 (0.999:
  // 0.368, with 1.5 times the modes).
  double variance_kept = 0.99;
  WeibullTail tail;
  std::uint64_t seed = 1;
};

template <int D>
class RandomField {
 public:
  // More modes than this are refused: each point costs one product per mode.
  static constexpr std::size_t kMaxModes = 1000000;

  // Expands the field over the box [lo, hi] and draws its realisation from `p.seed`. Throws InputError when the
  // variance kept needs more than kMaxModes modes, or the tail cannot give the deviation (grafted_distribution.hpp).
  RandomField(const Vec<D>& lo, const Vec<D>& hi, const RandomFieldParams& p);

  // ĝ(x), the standard Gaussian field at x: EOLE over the modes kept, divided by its own standard deviation there.
  // That deviation falls short of 1 by the variance of the modes dropped and by EOLE's error between nodes
  // (together about 1 − variance_kept); h must have the declared distribution at every point.
  double gaussian(const Vec<D>& x) const;
  // h(x) = F⁻¹(Φ(ĝ(x))), (3.21).
  double h(const Vec<D>& x) const { return marginal_.of_normal(gaussian(x)); }

  std::size_t modes() const { return modes_.size(); }
  // The fraction of the grid's variance the modes kept carry: variance_kept or just above.
  double variance_fraction() const { return kept_fraction_; }
  // Along one axis: the grid's nodes, and the eigenvalues of their correlation matrix, largest first.
  const Eigen::VectorXd& nodes(int axis) const { return axes_[axis].nodes; }
  const Eigen::VectorXd& eigenvalues(int axis) const { return axes_[axis].lambda; }

 private:
  struct Axis {
    Eigen::VectorXd nodes, lambda;
    Eigen::MatrixXd projector;  // row i: φ_iᵀ/√λ_i, for the modes kept along this axis
  };
  double lc_;
  std::array<Axis, D> axes_;
  std::vector<std::array<int, D>> modes_;  // each mode kept: its eigenpair along each axis
  Eigen::VectorXd xi_;                     // ξ_k, independent standard normals
  double kept_fraction_ = 0;
  GraftedWeibullGauss marginal_;

  void keep_modes(double fraction);
  void draw(std::uint64_t seed);
};

extern template class RandomField<2>;
extern template class RandomField<3>;

}  // namespace mc::rigid_cell
