#include "rigid_cell/free_stiffness.hpp"

#include <algorithm>
#include <tuple>

namespace mc::rigid_cell {

namespace {

struct Share {
  int row, col;
  double value;
  int local = 0;  // the element's entry (row · 2 kDofs + column) a bridge share takes
};

// Appends contact c's shares of the lower triangle of Mᵀ K_c M to `out`, one per entry, by column then row.
// `every`: one share per entry of the element and per pair of reduced degrees of freedom it maps to, each with its
// weight only (a bridge's), not merged; else the facet's non-zero entries times their weights, merged per entry.
template <int D>
void contact_shares(const CellAssembly<D>& model, std::size_t c,
                    const Eigen::SparseMatrix<double, Eigen::RowMajor>& to_cells, std::vector<Share>& out,
                    bool every = false) {
  constexpr int n = CellAssembly<D>::kDofs;
  const auto Ke = model.element_stiffness(c);
  const auto [a, b] = model.cells_of(c);
  const auto dof = [&](int i) { return (i < n ? a : b) * n + i % n; };
  std::vector<Share> local;
  for (int i = 0; i < 2 * n; ++i)
    for (int j = 0; j < 2 * n; ++j) {
      if (Ke(i, j) == 0 && !every) continue;
      using Row = Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator;
      for (Row p(to_cells, dof(i)); p; ++p)
        for (Row q(to_cells, dof(j)); q; ++q)
          if (p.col() >= q.col())
            local.push_back({static_cast<int>(p.col()), static_cast<int>(q.col()),
                             (every ? 1.0 : Ke(i, j)) * p.value() * q.value(), i * 2 * n + j});
    }
  if (every) {
    out.insert(out.end(), local.begin(), local.end());
    return;
  }
  std::sort(local.begin(), local.end(),
            [](const Share& x, const Share& y) { return std::tie(x.col, x.row) < std::tie(y.col, y.row); });
  for (std::size_t k = 0; k < local.size(); ++k) {
    if (k > 0 && local[k].row == out.back().row && local[k].col == out.back().col)
      out.back().value += local[k].value;
    else
      out.push_back(local[k]);
  }
}

}  // namespace

// free × all: the rows of the identity at the degrees of freedom not prescribed.
SparseMatrix free_rows(const std::vector<bool>& is_prescribed) {
  std::vector<Eigen::Triplet<double>> pick;
  const int n = static_cast<int>(is_prescribed.size());
  for (int d = 0, row = 0; d < n; ++d)
    if (!is_prescribed[d]) pick.emplace_back(row++, d, 1.0);
  SparseMatrix select(static_cast<Eigen::Index>(pick.size()), n);
  select.setFromTriplets(pick.begin(), pick.end());
  return select;
}

template <int D>
FreeStiffness<D>::FreeStiffness(const CellAssembly<D>& model, const SparseMatrix& to_cells,
                                const FibreBridges<D>* bridges)
    : bridges_(bridges) {
  const Eigen::SparseMatrix<double, Eigen::RowMajor> rows = to_cells;
  std::vector<Share> shares, bridge_shares;
  first_.reserve(model.contacts() + 1);
  first_.push_back(0);
  for (std::size_t c = 0; c < model.contacts(); ++c) {
    contact_shares(model, c, rows, shares);
    first_.push_back(shares.size());
  }
  bridge_first_.push_back(0);
  if (bridges_)
    for (std::size_t c : bridges_->contacts()) {
      contact_shares(model, c, rows, bridge_shares, true);
      bridge_first_.push_back(bridge_shares.size());
    }
  std::vector<Eigen::Triplet<double>> pattern;
  pattern.reserve(shares.size() + bridge_shares.size());
  for (const Share& s : shares) pattern.emplace_back(s.row, s.col, 0.0);
  for (const Share& s : bridge_shares) pattern.emplace_back(s.row, s.col, 0.0);
  K_.resize(to_cells.cols(), to_cells.cols());
  K_.setFromTriplets(pattern.begin(), pattern.end());
  K_.makeCompressed();
  entry_.reserve(shares.size());
  share_.reserve(shares.size());
  for (const Share& s : shares) {
    const int* begin = K_.innerIndexPtr() + K_.outerIndexPtr()[s.col];
    const int* end = K_.innerIndexPtr() + K_.outerIndexPtr()[s.col + 1];
    entry_.push_back(static_cast<int>(std::lower_bound(begin, end, s.row) - K_.innerIndexPtr()));
    share_.push_back(s.value);
  }
  for (const Share& s : bridge_shares) {
    const int* begin = K_.innerIndexPtr() + K_.outerIndexPtr()[s.col];
    const int* end = K_.innerIndexPtr() + K_.outerIndexPtr()[s.col + 1];
    bridge_entry_.push_back(static_cast<int>(std::lower_bound(begin, end, s.row) - K_.innerIndexPtr()));
    bridge_local_.push_back(s.local);
    bridge_weight_.push_back(s.value);
  }
}

template <int D>
const SparseMatrix& FreeStiffness<D>::operator()(const std::vector<double>& damage) {
  double* values = K_.valuePtr();
  std::fill(values, values + K_.nonZeros(), 0.0);
  for (std::size_t c = 0; c + 1 < first_.size(); ++c) {
    const double intact = 1 - damage[c];  // (3.11): the damage scales every stiffness of the facet
    for (std::size_t k = first_[c]; k < first_[c + 1]; ++k) values[entry_[k]] += intact * share_[k];
  }
  for (std::size_t j = 0; j + 1 < bridge_first_.size(); ++j) {
    const auto Kb = bridges_->contact_stiffness(j);
    constexpr int n2 = 2 * CellAssembly<D>::kDofs;
    for (std::size_t k = bridge_first_[j]; k < bridge_first_[j + 1]; ++k)
      values[bridge_entry_[k]] += Kb(bridge_local_[k] / n2, bridge_local_[k] % n2) * bridge_weight_[k];
  }
  return K_;
}

template class FreeStiffness<2>;
template class FreeStiffness<3>;

}  // namespace mc::rigid_cell
