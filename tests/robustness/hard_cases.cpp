// Numerically hard scenes through the real command: what can be resolved is, to its closed form; what cannot
// stops with exit 4 (or 2, before anything runs) naming the particles and the cause, never "finished".
#include <array>
#include <numbers>

#include "tests/common/cli_harness.hpp"
#include "tests/common/relative.hpp"
#include "tests/common/scene_text.hpp"

namespace {

const std::string kCollision = (kScenes / "collision_2d.toml").string();

// The collision scene with the discs approaching at ±v (m/s), run until they have parted again.
Result collide(const TempDir& d, double v) {
  const std::string speed = std::to_string(v) + " m/s";
  return mesocrack({"run", kCollision, "-o", "c.h5", "--set", "specimen.particles[0].velocity=[\"" + speed + "\", 0]",
                    "--set", "specimen.particles[1].velocity=[\"-" + speed + "\", 0]", "--set", "run.duration=80 us"},
                   d.dir);
}

// Contact duration of the collision scene's linear contact: π √(m*/k_n), m* = m/2 = 4.084e-3 kg, k_n = 5e7 N/m.
const double kDuration = std::numbers::pi * std::sqrt(2600 * std::numbers::pi * 1e-6 / 2 / 5e7);

std::string status_of(const TempDir& d, const std::string& file) { return summary_of(file, d.dir)["status"].text; }

// One phase of discs at the given positions (2D, radius 1 mm, linear contact of 50 MPa).
std::string discs_scene(const std::vector<std::array<double, 2>>& x_mm) {
  std::ostringstream s;
  s << mc::test::linear_grains(2) << "[specimen]\nkind = \"particles\"\n";
  for (const auto& x : x_mm)
    s << "[[specimen.particles]]\nx = [\"" << x[0] << " mm\", \"" << x[1] << " mm\"]\nradius = \"1 mm\"\n";
  s << "[run]\nsteps = 100\n";
  return s.str();
}

}  // namespace

TEST_CASE("a fast impact within the springs' reach keeps the linear contact's duration and restitution 1") {
  // At ±10 m/s the discs overlap by 0.18 R at most: still a linear spring, whose half period does not depend
  // on the speed. 1 % on the duration: the scene resolves the contact in ~70 steps (±1 step = 1.4 %/2 at the
  // edges of the positive-overlap window).
  const TempDir d;
  const Result r = collide(d, 10.0);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  const Json j = summary_of("c.h5", d.dir);
  CHECK(j["results"]["contact_duration_s"].number == mc::test::relative(kDuration, 0.01));
  CHECK(j["results"]["restitution"].number == mc::test::relative(1.0, 0.01));
}

TEST_CASE("discs too fast for their contact stop naming the pair passing through, never finished") {
  // ±150 m/s: the kinetic energy is 7× what the springs hold at half a radius of overlap; ±1000 m/s: 300×.
  for (const double v : {150.0, 1000.0}) {
    CAPTURE(v);
    const TempDir d;
    const Result r = collide(d, v);
    CHECK_MESSAGE(r.code == 4, r.describe());
    CHECK_MESSAGE(contains(r.err, "particle 0 and particle 1"), r.err);
    CHECK_MESSAGE(contains(r.err, "passing through each other"), r.err);
    CHECK_FALSE(contains(r.err, "gap in the walls"));
    CHECK(status_of(d, "c.h5") == "unstable");
  }
}

TEST_CASE("discs placed deep inside each other are refused before the run, naming the pair") {
  // Centres 0.8 mm apart: an overlap of 1.2 radii, which no contact law resolves; 1.6 mm apart (0.4 R) runs.
  const TempDir d;
  write_file(d / "deep.toml", discs_scene({{0, 0}, {0.8, 0}, {5, 0}}));
  const Result r = mesocrack({"run", "deep.toml", "-o", "deep.h5"}, d.dir);
  CHECK_MESSAGE(r.code == 2, r.describe());
  CHECK_MESSAGE(contains(r.err, "particles 0 and 1"), r.err);
  CHECK_FALSE(fs::exists(d / "deep.h5"));
  write_file(d / "near.toml", discs_scene({{0, 0}, {1.6, 0}, {5, 0}}));
  const Result ok = mesocrack({"run", "near.toml", "-o", "near.h5"}, d.dir);
  CHECK_MESSAGE(ok.code == 0, ok.describe());
}

TEST_CASE("thirty heavily overlapping discs are refused at build, not run for 48 steps") {
  // A 6 × 5 grid at 0.9 mm spacing: every neighbour overlaps by 1.1 radii.
  std::vector<std::array<double, 2>> x;
  for (int i = 0; i < 6; ++i)
    for (int k = 0; k < 5; ++k) x.push_back({0.9 * i, 0.9 * k});
  const TempDir d;
  write_file(d / "pile.toml", discs_scene(x));
  const Result r = mesocrack({"run", "pile.toml", "-o", "pile.h5"}, d.dir);
  CHECK_MESSAGE(r.code == 2, r.describe());
  CHECK_MESSAGE(contains(r.err, "overlap"), r.err);
  CHECK_FALSE(fs::exists(d / "pile.h5"));
}

TEST_CASE("a small disc resting on one 100 times larger settles at the static overlap m g / k_n") {
  // r = 1 mm on R = 100 mm (fixed): the timestep comes from the small disc, the big one only holds it. The
  // contact is linear, k_n = t E_c = 5e7 N/m (disc stiffnesses 2 t E_c in series), so the overlap at rest is
  // m g / k_n = 2600 π (1 mm)² · 9.81 / 5e7 = 1.602e-9 m. Local damping brings it to rest; 0.5 % covers what
  // is left of the oscillation after 20 ms (over 200 periods at damping 0.7).
  const std::string scene = mc::test::linear_grains(2) + R"([specimen]
kind = "particles"
[[specimen.particles]]
x = [0, 0]
radius = "100 mm"
[[specimen.particles]]
x = [0, "101 mm"]
radius = "1 mm"
[[groups]]
name = "base"
ids = [0]
fix = "all"
[physics]
gravity = [0, -9.81]
local_damping = 0.7
[[probes]]
name = "overlap"
kind = "overlap"
particles = [0, 1]
[[summary]]
name = "overlap_at_rest"
of = "overlap"
reduce = "final"
[run]
duration = "20 ms"
)";
  const TempDir d;
  write_file(d / "rest.toml", scene);
  const Result r = mesocrack({"run", "rest.toml", "-o", "rest.h5"}, d.dir);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  const double expected = 2600 * std::numbers::pi * 1e-6 * 9.81 / 5e7;
  CHECK(summary_of("rest.h5", d.dir)["results"]["overlap_at_rest"].number == mc::test::relative(expected, 0.005));
}

TEST_CASE("a chain with a stiffness contrast of 1e6 conserves energy with the stiff contacts' timestep") {
  // Soft discs (50 kPa) between pairs of stiff ones (50 GPa): the timestep is set by the stiff pairs, the motion
  // by the soft contacts. Undamped, the energy residual stays within 1e-3 of the energy put in: with ~100 steps
  // per stiff oscillation, central differences conserve the energy of the linear springs to O((ωΔt)²).
  std::ostringstream s;
  s << R"(dimension = 2
[[phases]]
name = "soft"
density = 2600
[[phases]]
name = "stiff"
density = 2600
[[contacts]]
phase_a = "soft"
model = "linear"
modulus = "50 kPa"
[[contacts]]
phase_a = "soft"
phase_b = "stiff"
model = "linear"
modulus = "50 kPa"
[[contacts]]
phase_a = "stiff"
model = "linear"
modulus = "50 GPa"
[specimen]
kind = "particles"
)";
  const char* phases[] = {"soft", "stiff", "stiff", "soft", "stiff", "stiff", "soft"};
  for (int i = 0; i < 7; ++i)
    s << "[[specimen.particles]]\nx = [\"" << 2 * i << " mm\", 0]\nradius = \"1 mm\"\nphase = \"" << phases[i] << "\"\n"
      << (i == 0 ? "velocity = [\"1 m/s\", 0]\n" : "");
  s << R"([physics]
energy = true
[[probes]]
name = "last_speed"
kind = "velocity"
particles = [6]
component = "x"
[[summary]]
name = "last_speed_max"
of = "last_speed"
reduce = "max"
[[summary]]
name = "residual_max"
of = "energy.residual"
reduce = "max"
[[summary]]
name = "residual_min"
of = "energy.residual"
reduce = "min"
[[summary]]
name = "energy_in"
of = "energy.kinetic"
reduce = "initial"
[run]
duration = "5 ms"
[output]
history_every = 500
)";
  const TempDir d;
  write_file(d / "contrast.toml", s.str());
  const Result r = mesocrack({"run", "contrast.toml", "-o", "contrast.h5"}, d.dir);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  const Json j = summary_of("contrast.h5", d.dir);
  const double e_in = j["results"]["energy_in"].number;
  CHECK(std::abs(j["results"]["residual_max"].number) < 1e-3 * e_in);
  CHECK(std::abs(j["results"]["residual_min"].number) < 1e-3 * e_in);
  // The push crossed the chain: the last soft disc moves off at a good part of the first one's 1 m/s.
  CHECK(j["results"]["last_speed_max"].number > 0.3);
}

TEST_CASE("undamped discs bouncing between walls: resolved impacts keep the energy, unresolved ones are named") {
  // Two discs between two walls, no damping, ~170 impacts in 0.5 s. At timestep safety 0.05 each contact lasts
  // some 60 steps and the total energy stays within 0.5 % (measured 0.997–1.000). At 0.8 a contact lasts ~4
  // steps: each impact opening or closing between steps gains or loses energy, the losses and gains random-walk,
  // and the guard stops the run when the energy has doubled — naming the under-resolved impacts as the cause.
  const std::string scene = mc::test::linear_grains(2) + R"([specimen]
kind = "particles"
[[specimen.particles]]
x = ["3 mm", 0]
radius = "1 mm"
velocity = ["0.5 m/s", 0]
[[specimen.particles]]
x = ["7 mm", 0]
radius = "1 mm"
velocity = ["-0.3 m/s", 0]
[[walls]]
name = "left"
shape = "plane"
point = [0, 0]
normal = [1, 0]
kn = 1e8
[[walls]]
name = "right"
shape = "plane"
point = ["10 mm", 0]
normal = [-1, 0]
kn = 1e8
[physics]
energy = true
[[summary]]
name = "residual_max"
of = "energy.residual"
reduce = "max"
[[summary]]
name = "residual_min"
of = "energy.residual"
reduce = "min"
[run]
duration = "0.5 s"
[output]
history_every = 200
)";
  const TempDir d;
  write_file(d / "bounce.toml", scene);
  const double e0 = 0.5 * 2600 * std::numbers::pi * 1e-6 * (0.25 + 0.09);
  // The residual is the energy put in minus kinetic and strain energy (nothing is dissipated): the drift.
  const Result fine = mesocrack({"run", "bounce.toml", "-o", "fine.h5", "--set", "timestep.safety=0.05"}, d.dir);
  REQUIRE_MESSAGE(fine.code == 0, fine.describe());
  const Json j = summary_of("fine.h5", d.dir);
  CHECK(std::abs(j["results"]["residual_max"].number) < 0.005 * e0);
  CHECK(std::abs(j["results"]["residual_min"].number) < 0.005 * e0);
  const Result coarse = mesocrack({"run", "bounce.toml", "-o", "coarse.h5", "--set", "timestep.safety=0.8", "--set",
                                   "run.duration=4.7 s", "--set", "output.history_every=2000"},
                                  d.dir);
  CHECK_MESSAGE(coarse.code == 4, coarse.describe());
  CHECK_MESSAGE(contains(coarse.err, "impacts resolved in too few steps"), coarse.err);
  CHECK(status_of(d, "coarse.h5") == "unstable");
}

TEST_CASE("a specimen too large for any machine's memory is refused with the estimate before anything is built") {
  // A 0.1 m cube of 1 µm spheres in fcc order: 1.77e14 particles, 315 TB at the measured 1.78 kB per sphere.
  const TempDir d;
  write_file(d / "big.toml", mc::test::linear_grains(3) + R"([specimen]
kind = "lattice"
lo = [0, 0, 0]
hi = ["100 mm", "100 mm", "100 mm"]
radius = "1 um"
[run]
steps = 1
)");
  const Result r = mesocrack({"run", "big.toml", "-o", "big.h5"}, d.dir);
  CHECK_MESSAGE(r.code == 2, r.describe());
  CHECK_MESSAGE(contains(r.err, "'specimen.radius'"), r.err);
  CHECK_MESSAGE(contains(r.err, "1.77e+14 particles"), r.err);
  CHECK_FALSE(fs::exists(d / "big.h5"));
}

TEST_CASE("rigid cells too many for the machine or no room for a node are refused naming l_min before placing any") {
  const TempDir d;
  // A 70 mm disc of l_min 1 µm: random sequential addition saturates at about 0.62 nodes per l_min² (measured), so
  // about 2.3·10⁹ cells, 14 TB at the least 6 kB a 2D cell needs; refused in well under a second.
  const std::string disc = (kScenes / "brazilian_2d.toml").string();
  const Result fine = mesocrack({"run", disc, "-o", "fine.h5", "--set", "specimen.l_min=1e-6"}, d.dir);
  CHECK_MESSAGE(fine.code == 2, fine.describe());
  CHECK_MESSAGE(contains(fine.err, "'specimen.l_min'"), fine.err);
  CHECK_MESSAGE(contains(fine.err, "2.31e+09 cells"), fine.err);
  CHECK_FALSE(fs::exists(d / "fine.h5"));
  // The 3D prism of the fibre scenes at l_min 50 µm: 60 × 20 × 10 mm, about 5.6·10⁷ cells at 40 kB each.
  const std::string prism = (kScenes / "fibre_prism_tension_3d.toml").string();
  const Result fine3 = mesocrack({"run", prism, "-o", "fine3.h5", "--set", "specimen.l_min=5e-5"}, d.dir);
  CHECK_MESSAGE(fine3.code == 2, fine3.describe());
  CHECK_MESSAGE(contains(fine3.err, "'specimen.l_min'"), fine3.err);
  CHECK_MESSAGE(contains(fine3.err, "cells"), fine3.err);
  // Květoň's thin concrete disc (70 × 30 mm) at l_min 0.5 mm: about 5·10⁵ cells, 20 GiB at 40 kB a cell, which
  // this machine may have; but its factor would hold at least 3.9·10⁹ values (90 n^{4/3}), which CHOLMOD's int
  // indices do not take. Placed and tessellated, it took 161 s and 19 GB before the factor's analysis refused it.
  const Result disc3 = mesocrack(
      {"run", (kScenes / "brazilian_concrete_thin.toml").string(), "-o", "disc3.h5", "--set", "specimen.l_min=5e-4"},
      d.dir);
  CHECK_MESSAGE(disc3.code == 2, disc3.describe());
  CHECK_MESSAGE(contains(disc3.err, "'specimen.l_min'"), disc3.err);
  CHECK_MESSAGE(contains(disc3.err, "stiffness factor"), disc3.err);
  CHECK_MESSAGE(disc3.seconds < 10, disc3.seconds, " s");
  // l_min above the specimen's size: each node keeps l_min/2 from the surface, so none fits (it ended in an
  // internal vector range error).
  for (const auto& [scene, l] : {std::pair{disc, "0.08"}, std::pair{prism, "0.011"}}) {
    const Result coarse = mesocrack({"run", scene, "-o", "coarse.h5", "--set", std::string("specimen.l_min=") + l}, d.dir);
    CHECK_MESSAGE(coarse.code == 2, coarse.describe());
    CHECK_MESSAGE(contains(coarse.err, "'specimen.l_min'"), coarse.err);
    CHECK_MESSAGE(contains(coarse.err, "no room"), coarse.err);
  }
}
