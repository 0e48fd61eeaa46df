#include "engine/measure.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/parallel.hpp"

namespace mc {

namespace {

// Σ_{i<n} term(i) in fixed blocks of kBlock particles, the block sums added in order: the same bits whatever
// the thread count (parallel.hpp).
template <class T, class F>
T block_sum(int n, const T& zero, F&& term) {
  std::vector<T> part(block_count(n), zero);
#pragma omp parallel for schedule(static) if (n > kParallelMin)
  for (int b = 0; b < static_cast<int>(part.size()); ++b) {
    const int end = std::min(n, (b + 1) * kBlock);
    for (int i = b * kBlock; i < end; ++i) part[b] += term(i);
  }
  T sum = zero;
  for (const T& p : part) sum += p;
  return sum;
}

template <int D>
struct StressSum {
  Tensor<D> s = Tensor<D>::Zero();  // Σ_Np Σ_Nc (x^c − x^p)_i F^c_j
  double volume = 0;                // Σ_Np V^p
  StressSum& operator+=(const StressSum& o) {
    s += o.s;
    volume += o.volume;
    return *this;
  }
};

struct Count {
  double contacts = 0, particles = 0;
  Count& operator+=(const Count& o) {
    contacts += o.contacts;
    particles += o.particles;
    return *this;
  }
};

template <int D>
struct Moments {
  double n = 0;
  Vec<D> x = Vec<D>::Zero(), v = Vec<D>::Zero();             // Σ x^p, Σ V^p
  Tensor<D> xx = Tensor<D>::Zero(), vx = Tensor<D>::Zero();  // Σ x̃ x̃ᵀ, Σ Ṽ x̃ᵀ
  Moments& operator+=(const Moments& o) {
    n += o.n, x += o.x, v += o.v, xx += o.xx, vx += o.vx;
    return *this;
  }
};

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
  const double solid = block_sum(p.size(), 0.0, [&](int i) {
    return lens_volume<D>(region.radius, p.radius[i], (p.x[i] - region.centre).norm());
  });
  return 1.0 - solid / region.volume();
}

template <int D>
Tensor<D> average_stress(const World<D>& world, const Region<D>& region) {
  const auto& p = world.particles;
  const auto sum = block_sum(p.size(), StressSum<D>{}, [&](int i) {
    StressSum<D> t;
    if (!region.contains(p.x[i])) return t;
    t.volume = Dim<D>::volume(p.radius[i]);
    world.for_each_contact_of(i,
                              [&](std::size_t, const Vec<D>& f, const Vec<D>& lever) { t.s += lever * f.transpose(); });
    return t;
  });
  if (sum.volume == 0) return Tensor<D>::Constant(kNaN);
  // Tang (3.63) without its leading minus: with F^c the force ON the particle, a compressed particle receives
  // inward forces at outward levers, so the plain sum is already negative in compression (tension positive).
  // The factor (1 − n)/Σ V^p, (3.59)–(3.62), scales the particles whose centre is inside to the solid actually
  // inside the region, assuming the particles straddling its boundary are stressed like those inside.
  return (1.0 - porosity(world, region)) / sum.volume * sum.s;
}

template <int D>
double coordination_number(const World<D>& world, const Region<D>& region) {
  const auto& p = world.particles;
  const Count c = block_sum(p.size(), Count{}, [&](int i) {
    Count t;
    if (!region.contains(p.x[i])) return t;
    t.particles = 1;
    world.for_each_contact_of(i, [&](std::size_t, const Vec<D>& f, const Vec<D>&) {
      if (f.squaredNorm() > 0) t.contacts += 1;  // candidate pairs not (or no longer) touching carry no force
    });
    return t;
  });
  return c.particles > 0 ? c.contacts / c.particles : kNaN;
}

template <int D>
Tensor<D> best_fit_velocity_gradient(const World<D>& world, const Region<D>& region) {
  const auto& p = world.particles;
  const Tensor<D> undetermined = Tensor<D>::Constant(kNaN);
  // Means first, Tang (3.68), then the sums about them (3.69)–(3.70): centring before multiplying keeps the
  // normal equations free of the cancellation that Σ x xᵀ − N x̄ x̄ᵀ would suffer far from the origin.
  const Moments<D> m0 = block_sum(p.size(), Moments<D>{}, [&](int i) {
    Moments<D> t;
    if (region.contains(p.x[i])) t.n = 1, t.x = p.x[i], t.v = p.v[i];
    return t;
  });
  if (m0.n < D + 1) return undetermined;
  const Vec<D> xm = m0.x / m0.n, vm = m0.v / m0.n;
  const Moments<D> m = block_sum(p.size(), Moments<D>{}, [&](int i) {
    Moments<D> t;
    if (!region.contains(p.x[i])) return t;
    const Vec<D> xt = p.x[i] - xm, vt = p.v[i] - vm;
    t.xx = xt * xt.transpose();
    t.vx = vt * xt.transpose();
    return t;
  });
  // (3.71)–(3.73): minimising Σ |α̇ x̃ − Ṽ|² gives α̇ (Σ x̃ x̃ᵀ) = Σ Ṽ x̃ᵀ; Σ x̃ x̃ᵀ is symmetric, so
  // α̇ᵀ = (Σ x̃ x̃ᵀ)⁻¹ (Σ Ṽ x̃ᵀ)ᵀ.
  const Eigen::FullPivLU<Tensor<D>> lu(m.xx);
  if (!lu.isInvertible()) return undetermined;
  return lu.solve(Tensor<D>(m.vx.transpose())).transpose();
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
