// The distribution of the random field h(x) of Květoň §3.4: Gaussian with a Weibull left tail grafted on (Bažant &
// Pang 2007): F(x) = 1 − exp(−(x/s₁)^m) up to the grafting point x_gr, where F = P_gr, and
// F(x) = P_gr + r_f [Φ((x − μ_G)/δ_G) − Φ((x_gr − μ_G)/δ_G)] above it, the density continuous at x_gr and r_f
// making the whole integrate to 1. The Weibull tail is what the weakest-link statistics of a quasibrittle material
// require of its low strengths; the Gaussian core what its bulk shows. Its mean is 1 and its standard deviation
// the declared one: the core's μ_G and δ_G are solved for, since the tail shifts both.
#pragma once

namespace mc::rigid_cell {

// Φ, the standard normal distribution function, and its inverse Φ⁻¹ (p in (0, 1), to about 1e-15).
double normal_cdf(double z);
double normal_quantile(double p);

// The left tail. m = 24 is the Weibull modulus of concrete that Bažant & Novák (2000) fitted to the size effect
// on its flexural strength and Bažant & Pang (2007) use; they graft the tail of concrete at a probability of the
// order 10⁻⁴–10⁻³: 10⁻³ here.
struct WeibullTail {
  double modulus = 24;        // m [-]
  double probability = 1e-3;  // P_gr [-]
};

class GraftedWeibullGauss {
 public:
  // Mean 1 and standard deviation `deviation`. Throws InputError when no Gaussian core gives that deviation with
  // this tail (a tail grafted high or shallow spreads the values by itself), naming the deviations it can give.
  GraftedWeibullGauss(double deviation, const WeibullTail& tail);

  double cdf(double x) const;
  // F⁻¹(Φ(g)): the value as probable as g is under the standard normal, accurate in both tails.
  double of_normal(double g) const;
  double graft() const { return graft_; }  // x_gr

 private:
  WeibullTail tail_;
  double mu_ = 0, delta_ = 0;  // the Gaussian core, μ_G and δ_G
  double graft_ = 0;           // x_gr
  double scale_ = 0;           // s₁ of the Weibull tail
  double rf_ = 0;              // r_f, the core's weight
};

}  // namespace mc::rigid_cell
