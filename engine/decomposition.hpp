// Where each part of a specimen split across processes lies: recursive coordinate bisection (as LAMMPS' and
// Zoltan's RCB). Each cut splits a region's particles along its longest extent, in proportion to the ranks on
// either side, so every rank starts with nearly the same count; regions are boxes, unbounded at the outside.
#pragma once
#include <vector>

#include "engine/dim.hpp"

namespace mc {

template <int D>
class Decomposition {
 public:
  Decomposition() = default;
  // The regions of `ranks` parts for these positions.
  static Decomposition bisect(const std::vector<Vec<D>>& x, int ranks);
  int size() const { return static_cast<int>(lo_.size()); }
  // The rank whose region holds x (a point on a cut belongs to the upper side).
  int owner(const Vec<D>& x) const;
  // Whether x lies within `reach` of rank r's region (inside it included).
  bool near(int r, const Vec<D>& x, double reach) const;
  // The other ranks whose regions come within `reach` of rank r's: the only ones its particles can be ghosts of.
  std::vector<int> neighbours(int r, double reach) const;
  const Vec<D>& lo(int r) const { return lo_[r]; }
  const Vec<D>& hi(int r) const { return hi_[r]; }

 private:
  struct Cut {
    int axis;
    double at;
    int below, above;  // the next cut's index, or −1 − rank for a region
  };
  int split(std::vector<int>& items, const std::vector<Vec<D>>& x, int first_rank, int ranks, const Vec<D>& lo,
            const Vec<D>& hi);
  std::vector<Cut> cuts_;
  std::vector<Vec<D>> lo_, hi_;
};

extern template class Decomposition<2>;
extern template class Decomposition<3>;

}  // namespace mc
