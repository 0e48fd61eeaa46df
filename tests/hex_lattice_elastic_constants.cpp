// The bonded hexagonal lattice as an elastic plate (Tang 2013 §8.1.1): discs joined at every contact by a
// normal spring K^n and a shear spring K^s chosen by (8.3) (plane stress) or (8.2) (plane strain) must show the
// E and ν they were chosen for in a virtual tension test; and the regular packings behind it must have exactly
// the contacts of the lattice.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>

#include "contact_models/contact_bond.hpp"
#include "engine/errors.hpp"
#include "engine/measure.hpp"
#include "preprocess/regular_packing.hpp"
#include "tests/common/errors.hpp"
#include "tests/common/relative.hpp"
#include "tests/common/test_worlds.hpp"

using namespace mc;

namespace {

constexpr double kR = 1e-3;        // disc radius [m]
constexpr double kDensity = 2500;  // [kg/m³]

// What the virtual tension test measured: the in-plane (2D) constants of the lattice plate, and checks.
struct Tension {
  double young_2d = 0, poisson_2d = 0;
  double region_stress = 0;  // σ_yy of the measurement circle (Tang 3.63), beside the force over the width
  double whole_strain = 0;   // top-row displacement / height, beside the central fit
  double unbalanced = 0;     // mean unbalanced force / mean contact force at the end
  std::int64_t steps = 0;
};

// A hexagonal lattice of `per_row` × `rows` discs (rows along x), every
// touching pair bonded with the contact bond: k_n = modulus (two balls of 2·t·E_c in series), k_s = k_n /
// kn_ks_ratio, strengths out of reach and no friction, so the lattice stays linear elastic. Uniaxial tension
// along y:
// - bottom row held in y, free in x (a lubricated platen); its middle disc is held in x too, which only
//   removes the rigid sliding of the specimen;
// - top row held in y, free in x, moved up by strain·H over `ramp` steps, then held there;
// - the bonds within the bottom and top rows have half the stiffness of the others. Across a vertical cut an
//   infinite lattice has one horizontal and one inclined bond per row, whose x forces cancel under σ_xx = 0;
//   a specimen of M rows has M horizontal but only M − 1 inclined ones, so with full end-row bonds the two
//   end rows act as a stiff band along the platens that holds back the lateral contraction (measured: ν read
//   1 % low on this 40 × 40 lattice, 4 % on 40 × 20, 0.1 % on 40 × 80). Half-stiffness end rows are the
//   lattice's own lubricated platen: the homogeneous state is then exact there.
// - rotations are free everywhere. Under a homogeneous strain ε an interior disc feels no moment: the six
//   bonds give Σ n × (ε n) = ε_xy Σ(n_x² − n_y²) + (ε_yy − ε_xx) Σ n_x n_y = 0 over the hexagon, so its
//   rotation stays zero and the shear springs see exactly the relative translations that (8.2)/(8.3) assume.
//   Only the discs along the free sides rotate (by up to ≈ ε), as in any bonded-particle specimen.
// Local damping 0.7 then brings the lattice to rest. Stress: the force on the top row over the width it
// stands for. Between two rows there are 2N − 1 inclined bonds (the offset rows make the sides ragged), each
// carrying the load of a width R of the lattice (two per disc cell 2R wide), so the width is (2N − 1) R, not
// N · 2R (with 2NR, E read 1.4 % low on 40 × 40). Strain: the best-fit displacement gradient over a central
// circle reaching to 10 disc diameters from the free sides and the end rows.
Tension virtual_tension(const LatticeStiffness& k, int per_row, int rows, double strain, int ramp) {
  ContactBondParams p;
  p.contact.modulus = k.normal;
  p.contact.kn_ks_ratio = k.normal / k.shear;
  p.contact.friction = 0;
  p.bond_normal_strength.mean = p.bond_shear_strength.mean = 1e30;
  auto w = test::single_model_world<2, ContactBond>(p);
  ContactBondParams end_row = p;  // phase 1: the bottom and top rows; their bonds with each other at half stiffness
  end_row.contact.modulus *= 0.5;
  w.sets.push_back(std::make_unique<ContactSet<ContactBond, 2>>(end_row));
  w.model_of = {{0, 0}, {0, 1}};
  const double width = (2 * per_row + 1) * kR, height = 2 * kR + (rows - 1) * std::sqrt(3.0) * kR;
  const Packing<2> pk = hexagonal_packing(Vec<2>(0, 0), Vec<2>(width, height), kR);
  const int n = static_cast<int>(pk.x.size()), top0 = (rows - 1) * per_row;
  REQUIRE(n == per_row * rows);
  for (int i = 0; i < n; ++i) w.particles.add(pk.x[i], pk.radius[i], kDensity, i < per_row || i >= top0 ? 1 : 0);
  w.local_damping = 0.7;
  w.init();
  // Horizontal bonds (N − 1 per row) and 2N − 1 between each pair of neighbouring rows.
  REQUIRE(w.install_bonds(1e-6, 1) == static_cast<std::size_t>(rows * (per_row - 1) + (rows - 1) * (2 * per_row - 1)));
  REQUIRE(w.sets[1]->pairs().size() == static_cast<std::size_t>(2 * (per_row - 1)));
  auto& P = w.particles;
  const double H = pk.x[top0][1] - pk.x[0][1];
  for (int i = 0; i < per_row; ++i) P.fix[i] = 0b010;  // bottom row: y
  P.fix[per_row / 2] = 0b011;                          // … and one disc in x
  const double v = strain * H / (ramp * w.dt);
  for (int i = top0; i < n; ++i) P.fix[i] = 0b010, P.v[i][1] = v;  // top row: y, moving up

  Tension out;
  auto unbalanced = [&] {
    double f_res = 0, f_con = 0;
    int n_res = 0, n_con = 0;
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < 2; ++c)
        if (!(P.fix[i] & (1u << c))) f_res += std::abs(P.f[i][c]), ++n_res;
    w.for_each_contact_force([&](const Vec<2>& force) {
      if (const double f = force.norm(); f > 0) f_con += f, ++n_con;
    });
    return (f_res / n_res) / (f_con / std::max(n_con, 1));
  };
  for (int s = 0; s < ramp; ++s) w.step();
  for (int i = top0; i < n; ++i) P.v[i][1] = 0;
  // At rest: the mean unbalanced force below 1e-6 of the mean contact force. (1e-8, at twice the steps,
  // changed E and ν by < 1e-4 relative.)
  const std::int64_t max_steps = 100000;
  for (out.unbalanced = unbalanced(); out.unbalanced > 1e-6 && w.step_count < max_steps;) {
    for (int s = 0; s < 50; ++s) w.step();
    out.unbalanced = unbalanced();
  }
  out.steps = w.step_count;
  REQUIRE(out.unbalanced <= 1e-6);

  // Force on the rows held in y: the contacts pull the top row down and the bottom row up by the same amount.
  double f_top = 0, f_bottom = 0;
  for (int i = 0; i < per_row; ++i) f_bottom += P.f[i][1], f_top += P.f[top0 + i][1];
  CHECK(f_bottom == mc::test::relative(-f_top, 1e-4));
  const double stress = 0.5 * (f_bottom - f_top) / ((2 * per_row - 1) * kR);

  // Displacement gradient: the engine's best-fit velocity gradient (Tang 3.68–3.73) applied to a copy whose
  // positions are the initial ones and whose velocities are the displacements.
  World<2> probe;
  probe.particles = P;
  for (int i = 0; i < n; ++i) probe.particles.x[i] = pk.x[i], probe.particles.v[i] = P.x[i] - pk.x[i];
  const Region<2> region{Vec<2>(0.5 * width, 0.5 * height), 0.5 * std::min(width, height) - 20 * kR};
  const Tensor<2> grad = best_fit_velocity_gradient(probe, region);
  const double e_yy = grad(1, 1), e_xx = grad(0, 0);
  out.young_2d = stress / e_yy;
  out.poisson_2d = -e_xx / e_yy;
  out.whole_strain = (P.x[top0][1] - pk.x[top0][1]) / H;
  out.region_stress = average_stress(w, region)(1, 1);
  int inside = 0;
  for (int i = 0; i < n; ++i) inside += region.contains(pk.x[i]);
  MESSAGE(n << " discs, " << out.steps << " steps (ramp " << ramp << "), unbalanced " << out.unbalanced
            << "; σ_yy: top-row force / (2N − 1)R " << stress << " Pa, measurement circle " << out.region_stress
            << " Pa; ε_yy: central fit (" << inside << " discs) " << e_yy << ", whole height " << out.whole_strain
            << "; central ε_xy " << 0.5 * (grad(0, 1) + grad(1, 0)));
  return out;
}

// The lattice's own 2D constants from its springs (the derivation behind 8.2/8.3).
double lattice_poisson_2d(const LatticeStiffness& k) { return (k.normal - k.shear) / (3 * k.normal + k.shear); }

// 40 × 40 discs (80 mm × 69 mm), ε = 1e-4 applied over 1000 steps (≈ 10 times the time a wave takes to cross
// the height), then 1300–2700 steps of damped relaxation: ≈ 0.5–0.8 s per run on one core. Ramps of 250 to
// 2000 steps gave the same E and ν to 1e-5.
constexpr int kPerRow = 40, kRows = 40, kRamp = 1000;
constexpr double kStrain = 1e-4;

}  // namespace

// Measured on 40 × 40: E and ν within 0.2 % of the targets (2 % is asserted: the free sides cost up to 0.2 %,
// and smaller lattices for faster tests up to 1 %). What is left:
// - the free sides: their ragged discs miss bonds, so they shift and rotate a little (up to ≈ ε rad) off the
//   homogeneous state; this takes 0.05–0.2 % off E and adds 0.03–0.2 % to ν. With every rotation held
//   instead, ν comes within 0.02 % and E within 0.1 %;
// - the dynamic remainder: none measurable (a tenfold stricter rest criterion, or 8 times slower loading,
//   changed E and ν by < 1e-4);
// - geometric nonlinearity, of order the strain, 1e-4.
// Without the two corrections of virtual_tension (width 2NR, full-stiffness end rows) the same lattice reads
// E 1.4 % and ν 1 % low: inside 2 % still, but only just, and from the specimen's edges, not from (8.3).
TEST_CASE("hex_lattice_virtual_tension_gives_plane_stress_E_and_nu_of_tang_8_3") {
  const double E = 30e9;
  for (const double nu : {0.2, 0.1}) {
    const LatticeStiffness k = hex_lattice_stiffness_plane_stress(E, nu);
    CHECK(lattice_poisson_2d(k) == mc::test::relative(nu, 1e-12));  // ν₂D = ν in plane stress
    const Tension t = virtual_tension(k, kPerRow, kRows, kStrain, kRamp);
    MESSAGE("plane stress, target E = " << E << " Pa, ν = " << nu << ": measured E = " << t.young_2d << " Pa (ratio "
                                        << t.young_2d / E << "), ν = " << t.poisson_2d << " (ratio "
                                        << t.poisson_2d / nu << ")");
    CHECK(t.young_2d == mc::test::relative(E, 0.02));
    CHECK(t.poisson_2d == mc::test::relative(nu, 0.02));
  }
}

TEST_CASE("hex_lattice_virtual_tension_gives_plane_strain_E_and_nu_of_tang_8_2") {
  const double E = 30e9;
  for (const double nu : {0.2, 0.1}) {
    const LatticeStiffness k = hex_lattice_stiffness_plane_strain(E, nu);
    CHECK(lattice_poisson_2d(k) == mc::test::relative(nu / (1 - nu), 1e-12));  // ν₂D = ν/(1 − ν)
    const Tension t = virtual_tension(k, kPerRow, kRows, kStrain, kRamp);
    // The plate measured in-plane is the plane-strain body seen through ν₂D = ν/(1−ν), E₂D = E/(1−ν²).
    const double nu_ps = t.poisson_2d / (1 + t.poisson_2d), E_ps = t.young_2d * (1 - nu_ps * nu_ps);
    MESSAGE("plane strain, target E = " << E << " Pa, ν = " << nu << ": measured E = " << E_ps << " Pa (ratio "
                                        << E_ps / E << "), ν = " << nu_ps << " (ratio " << nu_ps / nu << ")");
    CHECK(E_ps == mc::test::relative(E, 0.02));
    CHECK(nu_ps == mc::test::relative(nu, 0.02));
  }
}

namespace {

// Touching neighbours (centres 2R apart to 1e-9 R) of every particle, by testing all pairs; and the smallest
// distance between centres that are not touching.
template <int D>
std::vector<int> touching(const Packing<D>& pk, double R, double& next_nearest) {
  const int n = static_cast<int>(pk.x.size());
  std::vector<int> count(n, 0);
  next_nearest = kInf;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      const double d = (pk.x[j] - pk.x[i]).norm();
      if (std::abs(d - 2 * R) <= 1e-9 * R)
        ++count[i], ++count[j];
      else
        next_nearest = std::min(next_nearest, d);
    }
  return count;
}

}  // namespace

TEST_CASE("regular_packings_have_the_expected_contacts") {
  const double R = 1e-3;
  SUBCASE("hexagonal") {
    // (2N + 1) R wide: N discs in every row; 2R + (M − 1)√3 R high: M rows.
    const int N = 12, M = 9;
    const Vec<2> lo(-0.05, 0.3);
    const Packing<2> pk = hexagonal_packing(lo, lo + Vec<2>((2 * N + 1) * R, 2 * R + (M - 1) * std::sqrt(3.0) * R), R);
    REQUIRE(static_cast<int>(pk.x.size()) == N * M);
    for (int j = 0; j < M; ++j)
      for (int i = 0; i < N; ++i) {  // row by row, left to right, odd rows offset by R
        const Vec<2>& x = pk.x[j * N + i];
        CHECK(x[0] == mc::test::relative(lo[0] + R + (j % 2) * R + 2 * R * i, 1e-14));
        CHECK(x[1] == mc::test::relative(lo[1] + R + std::sqrt(3.0) * R * j, 1e-14));
        CHECK(pk.radius[j * N + i] == R);
      }
    double next = 0;
    const std::vector<int> count = touching(pk, R, next);
    int interior = 0, pairs = 0;
    for (int j = 0; j < M; ++j)
      for (int i = 0; i < N; ++i) {
        const int c = count[j * N + i];
        pairs += c;
        CHECK(c <= 6);
        // Interior: neither the first nor the last row, nor the first or last disc of a row. Along the ragged
        // sides a disc standing out (first of an even row, last of an odd one) keeps 3 neighbours, one set back 5.
        if (j > 0 && j < M - 1 && i > 0 && i < N - 1) {
          CHECK(c == 6);
          ++interior;
        }
        if (j > 0 && j < M - 1 && (i == 0 || i == N - 1)) CHECK(c == ((i == 0) == (j % 2 == 0) ? 3 : 5));
      }
    CHECK(interior == (M - 2) * (N - 2));
    CHECK(pairs / 2 == M * (N - 1) + (M - 1) * (2 * N - 1));
    // The next shell of the hexagonal lattice lies at 2√3 R: no near misses that a bond tolerance could catch.
    CHECK(next == mc::test::relative(2 * std::sqrt(3.0) * R, 1e-12));
    // A box a hair too narrow for the last disc of the odd rows leaves it out; one too low drops the top row.
    CHECK(hexagonal_packing(lo, lo + Vec<2>((2 * N + 0.9) * R, 2 * R + (M - 1) * std::sqrt(3.0) * R), R).x.size() ==
          static_cast<std::size_t>(N * M - M / 2));
    CHECK(hexagonal_packing(lo, lo + Vec<2>((2 * N + 1) * R, 1.9 * R + (M - 1) * std::sqrt(3.0) * R), R).x.size() ==
          static_cast<std::size_t>(N * (M - 1)));
  }
  SUBCASE("face-centred cubic") {
    // Box 2R + 2m·(a/2) per side: sites i, j, k = 0 … 2m, those with i + j + k even: ((2m + 1)³ + 1) / 2.
    const int m = 3, s = 2 * m + 1;
    const double half = std::sqrt(2.0) * R;
    const Vec<3> lo(0.1, -0.2, 0.0);
    const Packing<3> pk = fcc_packing(lo, lo + Vec<3>::Constant(2 * R + 2 * m * half), R);
    REQUIRE(static_cast<int>(pk.x.size()) == (s * s * s + 1) / 2);
    double next = 0;
    const std::vector<int> count = touching(pk, R, next);
    int interior = 0, pairs = 0;
    for (std::size_t p = 0; p < pk.x.size(); ++p) {
      int idx[3];
      for (int k = 0; k < 3; ++k) {
        const double f = (pk.x[p][k] - lo[k] - R) / half;
        idx[k] = static_cast<int>(std::lround(f));
        CHECK(f == doctest::Approx(idx[k]).epsilon(1e-12));  // on the lattice: an index, of order 1
      }
      CHECK((idx[0] + idx[1] + idx[2]) % 2 == 0);
      if (p > 0) {  // layer by layer (z), then row (y), then x
        const Vec<3>& a = pk.x[p - 1];
        const Vec<3>& b = pk.x[p];
        CHECK((a[2] < b[2] || (a[2] == b[2] && (a[1] < b[1] || (a[1] == b[1] && a[0] < b[0])))));
      }
      pairs += count[p];
      CHECK(count[p] <= 12);
      bool inner = true;
      for (int k = 0; k < 3; ++k) inner = inner && idx[k] > 0 && idx[k] < 2 * m;
      if (inner) {
        CHECK(count[p] == 12);
        ++interior;
      }
    }
    // Sites with every index in 1 … 2m − 1 (m odd and m − 1 even values each) and an even sum: ((2m − 1)³ − 1) / 2.
    CHECK(interior == ((s - 2) * (s - 2) * (s - 2) - 1) / 2);
    // Each pair of sites differing by ±1 in two indices and 0 in the third touches: per plane (xy, yz, zx)
    // of index pairs, 2 diagonal directions × (s − 1)² offsets × s values of the third index, half with an
    // even sum.
    CHECK(pairs / 2 == 3 * 2 * (s - 1) * (s - 1) * s / 2);
    // The next shell of the FCC lattice lies at the cube edge a = 2√2 R.
    CHECK(next == mc::test::relative(2 * std::sqrt(2.0) * R, 1e-12));
  }
}

TEST_CASE("closed_form_lattice_stiffness_rejects_poisson_ratios_without_a_shear_spring") {
  const double E = 30e9, s3 = std::sqrt(3.0);
  // Known values: ν = 0 gives K^n = K^s = E/√3 in both; plane stress ν = 0.2: K^n = E/(0.8√3), K^s = 0.4 E/(0.96√3).
  for (const auto& k : {hex_lattice_stiffness_plane_stress(E, 0), hex_lattice_stiffness_plane_strain(E, 0)}) {
    CHECK(k.normal == mc::test::relative(E / s3, 1e-14));
    CHECK(k.shear == mc::test::relative(E / s3, 1e-14));
  }
  const LatticeStiffness ps = hex_lattice_stiffness_plane_stress(E, 0.2);
  CHECK(ps.normal == mc::test::relative(E / (0.8 * s3), 1e-14));
  CHECK(ps.shear == mc::test::relative(0.4 * E / (0.96 * s3), 1e-14));
  // Plane strain ν = 0.2: (1 + ν)(1 − 2ν) = 0.72, 1 − 4ν = 0.2.
  const LatticeStiffness pe = hex_lattice_stiffness_plane_strain(E, 0.2);
  CHECK(pe.normal == mc::test::relative(E / (0.72 * s3), 1e-14));
  CHECK(pe.shear == mc::test::relative(0.2 * E / (0.72 * s3), 1e-14));
  // Just below the limits K^s is small but positive; at and beyond them there is no shear spring to give.
  CHECK(hex_lattice_stiffness_plane_strain(E, 0.2499).shear > 0);
  CHECK(hex_lattice_stiffness_plane_stress(E, 0.3333).shear > 0);
  for (const double nu : {0.25, 0.3, 0.49, -1.0, -2.0, kNaN}) {
    const std::string m = test::error_of([&] { hex_lattice_stiffness_plane_strain(E, nu); });
    CHECK_MESSAGE(m.find("plane strain") != std::string::npos, "nu = " << nu << ": " << m);
    CHECK(m.find("1/4") != std::string::npos);
  }
  for (const double nu : {1.0 / 3.0, 0.4, -1.0, kNaN}) {
    const std::string m = test::error_of([&] { hex_lattice_stiffness_plane_stress(E, nu); });
    CHECK_MESSAGE(m.find("plane stress") != std::string::npos, "nu = " << nu << ": " << m);
    CHECK(m.find("1/3") != std::string::npos);
  }
  CHECK(test::error_of([&] { hex_lattice_stiffness_plane_stress(0, 0.2); }).find("Young") != std::string::npos);
  CHECK(test::error_of([&] { hex_lattice_stiffness_plane_strain(-E, 0.2); }).find("Young") != std::string::npos);
  CHECK_THROWS_AS(hexagonal_packing(Vec<2>(0, 0), Vec<2>(1.5e-3, 1), 1e-3), InputError);
  CHECK_THROWS_AS(fcc_packing(Vec<3>(0, 0, 0), Vec<3>(1, 1, 1), 0.0), InputError);
}
