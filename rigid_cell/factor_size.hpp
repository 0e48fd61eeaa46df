// How large a stiffness factor this build's CHOLMOD takes, and the least a 3D specimen's factor holds: the bounds
// the solver (static_solver.cpp, after CHOLMOD's analysis) and the scene's size check (before any node is placed)
// refuse a specimen by.
#pragma once
#include <cmath>

namespace mc::rigid_cell {

// Debian's CHOLMOD, on int indices, dies of SIGSEGV in a supernodal factorisation well below 2³¹ values: measured
// on 3D discs (70 × 30 mm), 1.31·10⁹ values (l_min 0.9 mm) factorised, 1.86·10⁹ (0.8 mm) crashed with 4.8 of
// 24 GiB in use; the bound lies between.
inline constexpr double kMostFactorValues = 1.5e9;

// A 3D specimen of n cells: its factor's fill grows as n^{4/3} (nested dissection on a 3D mesh); measured 90 to
// 367 n^{4/3} values from 370 to 4.6·10⁵ cells (prisms and discs), the least taken.
inline double least_factor_values_3d(double cells) { return 90 * std::pow(cells, 4.0 / 3.0); }

}  // namespace mc::rigid_cell
