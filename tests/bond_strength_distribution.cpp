// Bond strengths drawn per bond at installation (Tang Table 5.1 normal; Tang 8.4 Weibull): over the ~5 300
// bonds of a hexagonal lattice the sample mean and variance match the distribution's, within sampling error,
// and the draws depend only on the seed and the pair.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "contact_models/parallel_bond.hpp"
#include "preprocess/regular_packing.hpp"
#include "tests/common/relative.hpp"
#include "tests/common/test_worlds.hpp"

using namespace mc;

namespace {

// Each bond's drawn tensile strength, or (moduli = true) its drawn modulus Ē_c.
std::vector<double> drawn_tensile_strengths(const ParallelBondParams& p, std::uint64_t seed, bool moduli = false) {
  auto w = test::single_model_world<2, ParallelBond>(p);
  const Packing<2> pk = hexagonal_packing(Vec<2>(0, 0), Vec<2>(40e-3, 40e-3), 0.5e-3);
  for (std::size_t i = 0; i < pk.x.size(); ++i) w.particles.add(pk.x[i], pk.radius[i], 2400, 0);
  w.init();
  w.install_bonds(1e-6, seed);
  std::vector<double> s;
  const auto& set = static_cast<const ContactSet<ParallelBond, 2>&>(*w.sets[0]);
  for (std::size_t c = 0; c < set.pairs().size(); ++c)
    if (const auto st = set.state(c); ParallelBond::bonded<2>(st))
      s.push_back(moduli ? st.stiffness * p.bond_modulus.mean : st.tensile);
  return s;
}

ParallelBondParams params() {
  ParallelBondParams p;
  p.contact.modulus = 20e9;
  p.bond_modulus.mean = 20e9;
  p.bond_shear_strength.mean = 1e9;
  return p;
}

}  // namespace

TEST_CASE("weibull_bond_strengths_have_the_mean_and_variance_of_tang_8_4") {
  auto p = params();
  const double lambda = 10e6, k = 5;  // scale and shape
  p.bond_tensile_strength.mean = lambda, p.bond_tensile_strength.weibull_shape = k;
  const auto s = drawn_tensile_strengths(p, 17);
  REQUIRE(s.size() > 4000);
  const double g1 = std::tgamma(1 + 1 / k), g2 = std::tgamma(1 + 2 / k);
  test::check_sample_moments(s, lambda * g1, lambda * lambda * (g2 - g1 * g1), "bonds");
  CHECK(drawn_tensile_strengths(p, 17) == s);  // by seed and pair alone
  CHECK(drawn_tensile_strengths(p, 18) != s);
}

TEST_CASE("normal_bond_strengths_have_the_mean_and_variance_of_table_5_1") {
  auto p = params();
  p.bond_tensile_strength.mean = 18e6, p.bond_tensile_strength.std = 2e6;  // Tang Table 5.1 (2D): 9 std from zero, truncation negligible
  const auto s = drawn_tensile_strengths(p, 3);
  test::check_sample_moments(s, 18e6, 4e12, "bonds");
}

// Tang §8.1.2: moduli as well as strengths are drawn per bond. The drawn moduli have the Weibull moments, and a
// bond's axial force grows with its own modulus: after one step of stretching at speed v, F̄_n = Ē_c,bond A v Δt
// / (R_A + R_B).
TEST_CASE("weibull_bond_moduli_have_the_moments_of_tang_8_4_and_set_each_bonds_stiffness") {
  auto p = params();
  p.bond_tensile_strength.mean = 1e9;
  const double lambda = 20e9, k = 8;
  p.bond_modulus.mean = lambda, p.bond_modulus.weibull_shape = k;
  const auto e = drawn_tensile_strengths(p, 23, true);
  const double g1 = std::tgamma(1 + 1 / k), g2 = std::tgamma(1 + 2 / k);
  test::check_sample_moments(e, lambda * g1, lambda * lambda * (g2 - g1 * g1), "bonds");

  const double r = 1e-3, v = 1e-3;
  auto w = test::held_bonded_pair<2, ParallelBond>(p, r, r, 0.0);
  w.particles.v[1][0] = v;
  w.step();
  const auto st = static_cast<const ContactSet<ParallelBond, 2>&>(*w.sets[0]).state(0);
  const double area = 2 * r;                    // 2D, λ̄ = 1, Tang (3.39)
  CHECK(st.stiffness != mc::test::relative(1.0, 1e-5));  // this bond drew its own modulus
  CHECK(-st.bond_fn == mc::test::relative(st.stiffness * lambda / (2 * r) * area * v * w.dt, 1e-12));
}
