#include "rigid_cell/random_field.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <queue>
#include <set>
#include <sstream>

#include "engine/errors.hpp"
#include "engine/random_stream.hpp"

namespace mc::rigid_cell {

namespace {

// Mixed into the seed, so that a field seeded like the node placement (rigid_cell/node_placement.cpp) does not
// draw the very numbers that placed the nodes.
constexpr std::uint64_t kFieldStream = 0x243f6a8885a308d3ull;

// The nodes of one axis from lo to hi, at most `spacing` apart, and the eigenpairs of their correlation matrix
// exp(−(x_i − x_j)²/l_c²), largest eigenvalue first.
struct AxisDecomposition {
  Eigen::VectorXd nodes, lambda;
  Eigen::MatrixXd vectors;
};

AxisDecomposition decompose_axis(double lo, double hi, double spacing, double lc) {
  const int intervals = std::max(1, static_cast<int>(std::ceil((hi - lo) / spacing - 1e-9)));
  AxisDecomposition a;
  a.nodes = Eigen::VectorXd::LinSpaced(intervals + 1, lo, hi);
  const Eigen::Index n = a.nodes.size();
  Eigen::MatrixXd C(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) C(i, j) = std::exp(-std::pow((a.nodes[i] - a.nodes[j]) / lc, 2));
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(C);  // ascending
  a.lambda = solver.eigenvalues().reverse();
  a.vectors = solver.eigenvectors().rowwise().reverse();
  return a;
}

}  // namespace

template <int D>
RandomField<D>::RandomField(const Vec<D>& lo, const Vec<D>& hi, const RandomFieldParams& p)
    : lc_(p.correlation_length), marginal_(p.deviation, p.tail) {
  std::array<Eigen::MatrixXd, D> vectors;
  for (int d = 0; d < D; ++d) {
    AxisDecomposition a = decompose_axis(lo[d], hi[d], p.grid_spacing, lc_);
    axes_[d].nodes = std::move(a.nodes);
    axes_[d].lambda = std::move(a.lambda);
    vectors[d] = std::move(a.vectors);
  }
  keep_modes(p.variance_kept);
  for (int d = 0; d < D; ++d) {
    int used = 0;
    for (const auto& m : modes_) used = std::max(used, m[d] + 1);
    const Eigen::VectorXd inverse_root = axes_[d].lambda.head(used).cwiseSqrt().cwiseInverse();
    axes_[d].projector = (vectors[d].leftCols(used) * inverse_root.asDiagonal()).transpose();
  }
  draw(p.seed);
}

// The grid's modes are the products of the axes' eigenpairs, λ = Π λ_{i_d}. They are taken largest first from a
// frontier: each axis's eigenvalues are sorted, so a product's successors along any axis are no larger than it.
template <int D>
void RandomField<D>::keep_modes(double fraction) {
  struct Candidate {
    double lambda;
    std::array<int, D> index;
  };
  // The larger product first; equal products (a square grid's symmetric pairs) by their indices, so that the set
  // kept does not depend on the queue's internals.
  const auto comes_later = [](const Candidate& a, const Candidate& b) {
    return a.lambda < b.lambda || (a.lambda == b.lambda && a.index > b.index);
  };
  std::priority_queue<Candidate, std::vector<Candidate>, decltype(comes_later)> frontier(comes_later);
  std::set<std::array<int, D>> seen;
  const auto product = [&](const std::array<int, D>& i) {
    double l = 1;
    for (int d = 0; d < D; ++d) l *= axes_[d].lambda[i[d]];
    return l;
  };
  double trace = 1;
  for (const Axis& a : axes_) trace *= a.lambda.sum();
  const std::array<int, D> first{};
  frontier.push({product(first), first});
  seen.insert(first);
  double kept = 0;
  while (kept < fraction * trace && !frontier.empty()) {
    const Candidate c = frontier.top();
    frontier.pop();
    modes_.push_back(c.index);
    kept += c.lambda;
    if (modes_.size() > kMaxModes) {
      std::ostringstream m;
      m << "keeping " << fraction << " of the variance of a random field of correlation length " << lc_
        << " m over a box of";
      for (const Axis& a : axes_) m << " " << a.nodes[a.nodes.size() - 1] - a.nodes[0];
      m << " m needs more than " << kMaxModes
        << " Karhunen-Loeve modes: a longer correlation length, less variance kept or a smaller specimen";
      throw InputError(m.str());
    }
    for (int d = 0; d < D; ++d) {
      std::array<int, D> next = c.index;
      if (++next[d] < axes_[d].lambda.size() && seen.insert(next).second) frontier.push({product(next), next});
    }
  }
  kept_fraction_ = kept / trace;
}

// ξ_k by Box–Muller from the engine's stream: the same numbers for a seed on every platform.
template <int D>
void RandomField<D>::draw(std::uint64_t seed) {
  RandomStream random(seed ^ kFieldStream);
  const Eigen::Index n = static_cast<Eigen::Index>(modes_.size());
  xi_.resize(n);
  for (Eigen::Index k = 0; k < n; k += 2) {
    const double r = std::sqrt(-2 * std::log(1 - random.uniform())), angle = 2 * M_PI * random.uniform();
    xi_[k] = r * std::cos(angle);
    if (k + 1 < n) xi_[k + 1] = r * std::sin(angle);
  }
}

// Along each axis ψ_i(x_d) = φ_iᵀ c_d(x_d)/√λ_i with c_d the correlation of x_d with the axis's nodes; a mode's
// φ_kᵀ C_{x,grid}/√λ_k is the product of its axes' ψ.
template <int D>
double RandomField<D>::gaussian(const Vec<D>& x) const {
  std::array<Eigen::VectorXd, D> psi;
  for (int d = 0; d < D; ++d) {
    const Axis& a = axes_[d];
    psi[d] = a.projector * (-((a.nodes.array() - x[d]) / lc_).square()).exp().matrix();
  }
  double g = 0, variance = 0;
  for (std::size_t k = 0; k < modes_.size(); ++k) {
    double v = 1;
    for (int d = 0; d < D; ++d) v *= psi[d][modes_[k][d]];
    g += xi_[static_cast<Eigen::Index>(k)] * v;
    variance += v * v;
  }
  return g / std::sqrt(variance);
}

template class RandomField<2>;
template class RandomField<3>;

}  // namespace mc::rigid_cell
