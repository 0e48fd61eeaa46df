#include "engine/measure.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "engine/exact_sum.hpp"
#include "engine/parallel.hpp"

namespace mc {

namespace {

// Σ over the particles this process owns of K terms (terms(i, sums) adds particle i's), each sum exact
// (engine/exact_sum.hpp) and made the whole world's: the same bits on any thread count and for any split of the
// world across processes, whose processes call it together.
template <int K, int D, class F>
std::array<double, K> exact_sums(const World<D>& world, F&& terms) {
  const auto& p = world.particles;
  const int n = p.size();
  std::vector<std::array<ExactSum, K>> part(block_count(n));
#pragma omp parallel for schedule(static) if (n > kParallelMin)
  for (int b = 0; b < static_cast<int>(part.size()); ++b) {
    const int end = std::min(n, (b + 1) * kBlock);
    for (int i = b * kBlock; i < end; ++i)
      if (!p.is_ghost(i)) terms(i, part[b]);
  }
  std::vector<ExactSum> total(K);
  for (const auto& block : part)
    for (int k = 0; k < K; ++k) total[k] += block[k];
  world.agree_sums(total);
  std::array<double, K> out;
  for (int k = 0; k < K; ++k) out[k] = total[k].value();
  return out;
}

// A D×D tensor's entries into sums [first, first + D²), and back.
template <int D, std::size_t K>
void add_tensor(std::array<ExactSum, K>& sums, int first, const Tensor<D>& t) {
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) sums[first + i * D + j].add(t(i, j));
}
template <int D, std::size_t K>
Tensor<D> tensor_at(const std::array<double, K>& sums, int first) {
  Tensor<D> t;
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) t(i, j) = sums[first + i * D + j];
  return t;
}

}  // namespace

template <int D>
double lens_volume(double R, double r, double d) {
  if (d >= R + r) return 0;
  if (d <= std::abs(R - r)) return Dim<D>::volume(std::min(R, r));  // one inside the other
  if constexpr (D == 2) {
    // Two circular segments, one cut from each disc by the common chord.
    const double a = std::acos(std::clamp((d * d + r * r - R * R) / (2 * d * r), -1.0, 1.0));
    const double b = std::acos(std::clamp((d * d + R * R - r * r) / (2 * d * R), -1.0, 1.0));
    const double k = (-d + r + R) * (d + r - R) * (d - r + R) * (d + r + R);
    return r * r * a + R * R * b - 0.5 * std::sqrt(std::max(k, 0.0));
  } else {
    // Two spherical caps on the common circle.
    return M_PI * (R + r - d) * (R + r - d) * (d * d + 2 * d * r - 3 * r * r + 2 * d * R + 6 * r * R - 3 * R * R) /
           (12 * d);
  }
}

template <int D>
double porosity(const World<D>& world, const Region<D>& region) {
  const auto& p = world.particles;
  const auto solid = exact_sums<1>(world, [&](int i, std::array<ExactSum, 1>& s) {
    s[0].add(lens_volume<D>(region.radius, p.radius[i], (p.x[i] - region.centre).norm()));
  });
  return 1.0 - solid[0] / region.volume();
}

template <int D>
Tensor<D> average_stress(const World<D>& world, const Region<D>& region) {
  const auto& p = world.particles;
  // Σ_Np Σ_Nc (x^c − x^p)_i F^c_j, then Σ_Np V^p.
  constexpr int K = D * D + 1;
  const auto sum = exact_sums<K>(world, [&](int i, std::array<ExactSum, K>& s) {
    if (!region.contains(p.x[i])) return;
    s[D * D].add(Dim<D>::volume(p.radius[i]));
    world.for_each_contact_of(
        i, [&](const Vec<D>& f, const Vec<D>& lever) { add_tensor<D>(s, 0, lever * f.transpose()); });
  });
  const double volume = sum[D * D];
  if (volume == 0) return Tensor<D>::Constant(kNaN);
  // Tang (3.63) without its leading minus: with F^c the force ON the particle, a compressed particle receives
  // inward forces at outward levers, so the plain sum is already negative in compression (tension positive).
  // The factor (1 − n)/Σ V^p, (3.59)–(3.62), scales the particles whose centre is inside to the solid actually
  // inside the region, assuming the particles straddling its boundary are stressed like those inside.
  return (1.0 - porosity(world, region)) / volume * tensor_at<D>(sum, 0);
}

template <int D>
double coordination_number(const World<D>& world, const Region<D>& region) {
  const auto& p = world.particles;
  const auto c = exact_sums<2>(world, [&](int i, std::array<ExactSum, 2>& s) {
    if (!region.contains(p.x[i])) return;
    double contacts = 0;
    world.for_each_contact_of(i, [&](const Vec<D>& f, const Vec<D>&) {
      if (f.squaredNorm() > 0) contacts += 1;  // candidate pairs not (or no longer) touching carry no force
    });
    s[0].add(contacts), s[1].add(1);
  });
  return c[1] > 0 ? c[0] / c[1] : kNaN;
}

template <int D>
Tensor<D> best_fit_velocity_gradient(const World<D>& world, const Region<D>& region) {
  const auto& p = world.particles;
  const Tensor<D> undetermined = Tensor<D>::Constant(kNaN);
  // Means first, Tang (3.68), then the sums about them (3.69)–(3.70): centring before multiplying keeps the
  // normal equations free of the cancellation that Σ x xᵀ − N x̄ x̄ᵀ would suffer far from the origin.
  // Count, Σ x^p, Σ V^p.
  constexpr int K0 = 1 + 2 * D;
  const auto m0 = exact_sums<K0>(world, [&](int i, std::array<ExactSum, K0>& s) {
    if (!region.contains(p.x[i])) return;
    s[0].add(1);
    for (int k = 0; k < D; ++k) s[1 + k].add(p.x[i][k]), s[1 + D + k].add(p.v[i][k]);
  });
  if (m0[0] < D + 1) return undetermined;
  Vec<D> xm, vm;
  for (int k = 0; k < D; ++k) xm[k] = m0[1 + k] / m0[0], vm[k] = m0[1 + D + k] / m0[0];
  // Σ x̃ x̃ᵀ, Σ Ṽ x̃ᵀ.
  constexpr int K1 = 2 * D * D;
  const auto m1 = exact_sums<K1>(world, [&](int i, std::array<ExactSum, K1>& s) {
    if (!region.contains(p.x[i])) return;
    const Vec<D> xt = p.x[i] - xm, vt = p.v[i] - vm;
    add_tensor<D>(s, 0, xt * xt.transpose());
    add_tensor<D>(s, D * D, vt * xt.transpose());
  });
  const Tensor<D> xx = tensor_at<D>(m1, 0), vx = tensor_at<D>(m1, D * D);
  // (3.71)–(3.73): minimising Σ |α̇ x̃ − Ṽ|² gives α̇ (Σ x̃ x̃ᵀ) = Σ Ṽ x̃ᵀ; Σ x̃ x̃ᵀ is symmetric, so
  // α̇ᵀ = (Σ x̃ x̃ᵀ)⁻¹ (Σ Ṽ x̃ᵀ)ᵀ.
  const Eigen::FullPivLU<Tensor<D>> lu(xx);
  if (!lu.isInvertible()) return undetermined;
  return lu.solve(Tensor<D>(vx.transpose())).transpose();
}

template double lens_volume<2>(double, double, double);
template double lens_volume<3>(double, double, double);
template double porosity<2>(const World<2>&, const Region<2>&);
template double porosity<3>(const World<3>&, const Region<3>&);
template Tensor<2> average_stress<2>(const World<2>&, const Region<2>&);
template Tensor<3> average_stress<3>(const World<3>&, const Region<3>&);
template double coordination_number<2>(const World<2>&, const Region<2>&);
template double coordination_number<3>(const World<3>&, const Region<3>&);
template Tensor<2> best_fit_velocity_gradient<2>(const World<2>&, const Region<2>&);
template Tensor<3> best_fit_velocity_gradient<3>(const World<3>&, const Region<3>&);

}  // namespace mc
