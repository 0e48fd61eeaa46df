// Rigid cells in implicit dynamics (Květoň ch. 8, [rigid_cell.dynamics]) through the real `mesocrack` command: the
// discrete cantilever swings at its first natural frequency, a wave runs along an elastic bar at the bar speed, the
// trapezoidal rule keeps the energy, a resumed run is the same run, and a step that does not converge stops the
// run with exit 4.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "tests/common/cli_harness.hpp"
#include "tests/common/relative.hpp"

namespace {

std::vector<double> series(const mc::H5File& f, const std::string& name) { return f.read_doubles("/history/" + name); }

// The times at which `y` falls through `level`, linearly interpolated between samples.
std::vector<double> downward_crossings(const std::vector<double>& t, const std::vector<double>& y, double level) {
  std::vector<double> at;
  for (std::size_t i = 1; i < y.size(); ++i)
    if (y[i - 1] > level && y[i] <= level)
      at.push_back(t[i - 1] + (level - y[i - 1]) / (y[i] - y[i - 1]) * (t[i] - t[i - 1]));
  return at;
}

// Work of the supports and loads against the energy stored and moving: what the run dissipated, relative to the work.
double dissipated_share(const mc::H5File& f) {
  return std::abs(series(f, "energy.dissipated").back()) / series(f, "energy.boundary_work").back();
}

}  // namespace

TEST_CASE("rigid_cell_cantilever_swings_at_the_euler_bernoulli_first_frequency_about_its_static_deflection") {
  const TempDir d;
  const Result r = mesocrack({"run", (kScenes / "cantilever_dynamic_kveton.toml").string(), "-o", "beam.h5"}, d.dir);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  const mc::H5File f((d / "beam.h5").string(), mc::H5File::Mode::ReadOnly);
  const auto t = series(f, "time"), y = series(f, "group.end.disp_y");
  // Květoň (3.8): E = E₀ (2 + 3α)/(4 + α) of the facets' E₀ 48 GPa, α 0.29; beam 200 × 20 × 20 mm, ρ 2400.
  const double E = 48e9 * (2 + 3 * 0.29) / (4 + 0.29), L = 0.2, h = 0.02, I = h * h * h * h / 12, rho = 2400;
  const double omega = 1.8751 * 1.8751 * std::sqrt(E * I / (rho * h * h * L * L * L * L));  // (8.14)
  const double lowest = *std::min_element(y.begin(), y.end());
  // The end swings about its static deflection: three downward passes through it in 11 ms.
  const auto passes = downward_crossings(t, y, 0.5 * lowest);
  REQUIRE(passes.size() >= 3);
  const double period = (passes.back() - passes.front()) / static_cast<double>(passes.size() - 1);
  // 5 % as the issue asks: measured 294.4 Hz against 295.4 Hz. Euler–Bernoulli leaves out shear and the section's
  // rotary inertia (about −1.5 % at L/h = 10) and the cells' statics are 3.4 % stiffer than beam theory
  // (rigid_cell_elasticity.cpp); the trapezoidal rule lengthens the period by Ω²/12 = 0.07 % at 68 steps per period.
  CHECK(2 * std::numbers::pi / period == mc::test::relative(omega, 0.05));
  // (8.13): the swing reaches twice the static deflection F L³/3EI, shear included (κ, G of ν): within the 5 % the
  // statics hold.
  const double nu = (1 - 0.29) / (4 + 0.29), G = E / (2 * (1 + nu)), kappa = 10 * (1 + nu) / (12 + 11 * nu);
  const double deflection = L * L * L / (3 * E * I) + L / (kappa * G * h * h);
  CHECK(-0.5 * lowest == mc::test::relative(deflection, 0.05));
  // The trapezoidal rule (β ¼, γ ½) conserves the energy of a linear system exactly: the load's work is the stored
  // plus the kinetic energy to round-off.
  CHECK(dissipated_share(f) < 1e-9);
}

TEST_CASE("rigid_cell_rayleigh_mass_damping_decays_the_cantilever_swing_at_its_damping_ratio") {
  const TempDir d;
  // C = a_M M damps the first mode at ζ = a_M/(2ω₁): a_M = 74 /s gives ζ = 0.0199 at the Euler–Bernoulli ω₁
  // (295.4 Hz). The trapezoidal rule adds no damping of its own, so the swing (from a trough to the next crest)
  // shrinks by exp(−2πζ/√(1 − ζ²)) = 0.882 per period.
  const Result r = mesocrack({"run", (kScenes / "cantilever_dynamic_kveton.toml").string(), "-o", "damped.h5", "--set",
                              "rigid_cell.dynamics.mass_damping=74"},
                             d.dir);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  const mc::H5File f((d / "damped.h5").string(), mc::H5File::Mode::ReadOnly);
  const auto y = series(f, "group.end.disp_y");
  const double middle = 0.5 * (*std::min_element(y.begin(), y.end()) + *std::max_element(y.begin(), y.end()));
  std::vector<double> troughs, crests;  // the turning points of the first mode, a micrometre off the middle
  for (std::size_t i = 1; i + 1 < y.size(); ++i)
    if ((y[i] - y[i - 1]) * (y[i + 1] - y[i]) < 0 && std::abs(y[i] - middle) > 1e-6)
      (y[i] < middle ? troughs : crests).push_back(y[i]);
  REQUIRE(troughs.size() >= 2);
  REQUIRE(crests.size() >= 2);
  const double omega = 2 * std::numbers::pi * 295.4, zeta = 74 / (2 * omega);
  const double expected = std::exp(-2 * std::numbers::pi * zeta / std::sqrt(1 - zeta * zeta));
  // Measured 0.882 and 0.881. 2 %: the sampled turning points (68 steps per period) and the higher modes' share
  // of the swing each move it by well under 1 %; the frequency the test takes is 0.4 % off the cells' own.
  CHECK((crests[1] - troughs[1]) / (crests[0] - troughs[0]) == mc::test::relative(expected, 0.02));
  // The damping takes its share of the load's work, positive.
  CHECK(series(f, "energy.dissipated").back() > 0.1 * series(f, "energy.boundary_work").back());
}

TEST_CASE("rigid_cell_bar_carries_an_elastic_wave_at_the_bar_speed") {
  const TempDir d;
  const fs::path scene = kScenes / "rigid_cell_wave_2d.toml";
  const Result r = mesocrack({"run", scene.string(), "-o", "bar.h5"}, d.dir);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  const mc::H5File f((d / "bar.h5").string(), mc::H5File::Mode::ReadOnly);
  const auto t = series(f, "time"), x = series(f, "group.free_end.disp_x");
  const double E0 = 30e9, rho = 2400, v = 0.1, height = 0.02, rise = 20e-6;
  const double c = std::sqrt(E0 / rho);  // α = 1: E = E₀, ν = 0, so no lateral coupling
  // The free end moves at twice the particle speed once the front has passed; it reaches half of that (the
  // struck end's speed) a half rise time after the front's middle arrives. Its speed by central differences.
  double arrival = 0;
  for (std::size_t i = 1; i + 1 < t.size(); ++i) {
    const double speed = (x[i + 1] - x[i - 1]) / (t[i + 1] - t[i - 1]);
    if (speed >= v) {
      const double before = (x[i] - x[i - 2]) / (t[i] - t[i - 2]);
      arrival = t[i - 1] + (v - before) / (speed - before) * (t[i] - t[i - 1]) - rise / 2;
      break;
    }
  }
  REQUIRE(arrival > 0);
  // From the struck plate's box centre (1 mm) to the free one's (399 mm); the plates' reference points, their cells'
  // centroids, lie within about a millimetre of these (0.3 % of the run). 2 % as the issue asks: measured −0.45 %.
  CHECK(0.398 / arrival == mc::test::relative(c, 0.02));
  // The struck end pushes with σ = ρ c v over the bar's height (the impedance of a bar): measured to 0.01 %.
  const auto push = series(f, "group.struck.reaction_x");
  CHECK(push[100] == mc::test::relative(rho * c * v * height, 0.01));
  // γ = 0.55 damps (8.5): a little of the work is lost to the scheme, none is created.
  const double lost = series(f, "energy.dissipated").back() / series(f, "energy.boundary_work").back();
  CHECK(lost > 0);
  CHECK(lost < 0.01);
  // The trapezoidal rule on the same bar: nothing lost, to round-off.
  const Result exact = mesocrack({"run", scene.string(), "-o", "trapezoidal.h5", "--set",
                                  "rigid_cell.dynamics.beta=0.25", "--set", "rigid_cell.dynamics.gamma=0.5"},
                                 d.dir);
  REQUIRE_MESSAGE(exact.code == 0, exact.describe());
  CHECK(dissipated_share(mc::H5File((d / "trapezoidal.h5").string(), mc::H5File::Mode::ReadOnly)) < 1e-9);
}

TEST_CASE("rigid_cell_stress_wave_pulse_throws_the_free_rear_face_at_twice_the_particle_speed") {
  const TempDir d;
  // Květoň (9.5) on an elastic bar (α = 1: E = E₀, ν = 0), under the trapezoidal rule, which neither damps nor
  // creates energy: β 0.3, γ 0.55 (the scene's) lose 3 % of the pulse on its way (rear face 0.2308 m/s).
  const Result r = mesocrack({"run", (kScenes / "stress_wave_bar_2d.toml").string(), "-o", "wave.h5", "--set",
                              "rigid_cell.dynamics.beta=0.25", "--set", "rigid_cell.dynamics.gamma=0.5"},
                             d.dir);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  const mc::H5File f((d / "wave.h5").string(), mc::H5File::Mode::ReadOnly);
  const auto t = series(f, "time"), x = series(f, "group.rear.disp_x");
  const double rho = 2400, c = std::sqrt(30e9 / rho), sigma = 1e6, pulse = 40e-6, height = 0.02, L = 0.399;
  double peak = 0, at = 0;
  for (std::size_t i = 1; i + 1 < t.size(); ++i) {
    const double v = (x[i + 1] - x[i - 1]) / (t[i + 1] - t[i - 1]);
    if (v > peak) peak = v, at = t[i];
  }
  // A free end moves at twice the particle speed σ/(ρc) of the wave arriving: 0.2357 m/s at the pulse's peak, when
  // it has run from the loaded face to the rear plate's reference point (its cells' centroid, about 399 mm) and
  // half the pulse has passed. Measured 0.2347 m/s (−0.4 %) at 133.0 µs (132.9 µs); 2 % as for the bar's front.
  CHECK(peak == mc::test::relative(2 * sigma / (rho * c), 0.02));
  CHECK(at == mc::test::relative(L / c + pulse / 2, 0.02));
  // The pulse's work on the loaded face, σ ⋅ σ/(ρc) over the face and the pulse: H σ² (3/8) t_P / (ρc) (the mean of
  // ¼(1 − cos)² is 3/8). Measured −0.27 %: 1 %.
  CHECK(series(f, "energy.boundary_work").back() ==
        mc::test::relative(height * sigma * sigma * 0.375 * pulse / (rho * c), 0.01));
  CHECK(dissipated_share(f) < 1e-9);
}

TEST_CASE("rigid_cell_plate_set_moving_at_once_pushes_the_bar_with_its_impedance_without_ringing") {
  const TempDir d;
  // The bar's struck end at 0.1 m/s from the first instant (no rise). The plate moves as it is told, so its
  // reaction is the bar's answer, ρcvH = 16 971 N/m, with the few per cent of the first cells' ringing (measured
  // between 0.968 and 1.032 of it over steps 20-200, mean 0.995); were its acceleration inferred by (8.2) from its
  // displacements, the plate's own mass would add ±v/(βΔt) every step, 24 times the push.
  const Result r = mesocrack(
      {"run", (kScenes / "rigid_cell_wave_2d.toml").string(), "-o", "jump.h5", "--set", "groups[0].ramp_time=0 s"},
      d.dir);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  const mc::H5File f((d / "jump.h5").string(), mc::H5File::Mode::ReadOnly);
  const auto push = series(f, "group.struck.reaction_x");
  const double impedance_push = 2400 * std::sqrt(30e9 / 2400) * 0.1 * 0.02;
  double sum = 0;
  for (std::size_t i = 20; i <= 200; ++i) {
    CHECK(push[i] == mc::test::relative(impedance_push, 0.05));
    sum += push[i];
  }
  CHECK(sum / 181 == mc::test::relative(impedance_push, 0.01));
  CHECK(push[1] > 0);
  CHECK(series(f, "group.struck.velocity_x")[1] == mc::test::relative(0.1, 1e-5));
}

TEST_CASE("rigid_cell_piecewise_linear_wave_does_its_work_and_a_section_reads_the_pulse_passing") {
  const TempDir d;
  // The elastic bar of §9.5.1 under the trapezoidal rule, loaded by a trapezoid of pressure (1 MPa, 15 µs up, 10 µs
  // held, 15 µs down) instead of the cosine, with a section plane at mid-length.
  const std::string text =
      edit(slurp(kScenes / "stress_wave_bar_2d.toml"), "pressure = \"1 MPa\"\nduration = \"40 us\"\n",
           "times = [0, \"15 us\", \"25 us\", \"40 us\"]\npressures = [0, \"1 MPa\", \"1 MPa\", 0]\n\n"
           "[rigid_cell.sections]\naxis = \"x\"\nat = [\"200 mm\"]\n");
  write_file(d / "scene.toml", text);
  const Result r = mesocrack({"run", "scene.toml", "-o", "wave.h5", "--set", "rigid_cell.dynamics.beta=0.25", "--set",
                              "rigid_cell.dynamics.gamma=0.5"},
                             d.dir);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  const mc::H5File f((d / "wave.h5").string(), mc::H5File::Mode::ReadOnly);
  const double rho = 2400, c = std::sqrt(30e9 / rho), H = 0.02;
  // Its work, H ∫σ² dt / (ρc) = H (1 MPa)² (2 · 15/3 + 10) µs / (ρc): measured −0.15 %; 1 %.
  CHECK(series(f, "energy.boundary_work").back() == mc::test::relative(H * 1e12 * 20e-6 / (rho * c), 0.01));
  // The section at 200 mm feels the full pressure as the held part passes (measured −1.03 MPa: the ramps' kinks
  // ring by a few per cent on 2 mm cells), and the rear face is thrown at 2σ/(ρc) (measured +2.9 %): 5 %.
  const auto sigma = series(f, "section.x_200mm"), v = series(f, "group.rear.velocity_x");
  CHECK(*std::min_element(sigma.begin(), sigma.end()) == mc::test::relative(-1e6, 0.05));
  CHECK(*std::max_element(v.begin(), v.end()) == mc::test::relative(2e6 / (rho * c), 0.05));
  // A wave that ends off zero, or whose times do not rise, is refused naming the key.
  const TempDir refused;
  check_edits_refused(refused.dir, text,
                      {{"pressures = [0, \"1 MPa\", \"1 MPa\", 0]",
                        "pressures = [0, \"1 MPa\", \"1 MPa\", \"1 MPa\"]",
                        {"rigid_cell.stress_wave.pressures", "returns to 0"}},
                       {"times = [0, \"15 us\", \"25 us\", \"40 us\"]",
                        "times = [0, \"15 us\", \"15 us\", \"40 us\"]",
                        {"rigid_cell.stress_wave.times", "must increase"}},
                       {"at = [\"200 mm\"]", "at = [\"500 mm\"]", {"section plane", "cuts no cell"}}});
}

TEST_CASE("rigid_cell_dynamic_run_resumed_halfway_gives_the_same_bits") {
  const TempDir d;
  const std::string scene = (kScenes / "rigid_cell_wave_2d.toml").string();
  const Result whole = mesocrack({"run", scene, "-o", "whole.h5"}, d.dir);
  REQUIRE_MESSAGE(whole.code == 0, whole.describe());
  // Stopped at step 160, with the front halfway along the bar: the velocities and accelerations go on from there.
  const Result first = mesocrack(
      {"run", scene, "-o", "parts.h5", "--set", "run.steps=160", "--set", "output.checkpoint_every=160"}, d.dir);
  REQUIRE_MESSAGE(first.code == 0, first.describe());
  const Result rest = mesocrack({"run", scene, "--resume", "parts.h5", "--set", "output.checkpoint_every=160"}, d.dir);
  REQUIRE_MESSAGE(rest.code == 0, rest.describe());
  check_same_run(d / "whole.h5", d / "parts.h5");
}

TEST_CASE("rigid_cell_newmark_step_that_does_not_converge_stops_with_exit_4_naming_the_step_and_residual") {
  const TempDir d;
  // The bar pulled instead of pushed, its facets made weak enough (f_t 0.5 MPa) that the tensile wave's 0.85 MPa
  // damages them, with one secant iteration allowed per step (ten when it is done again with damage monotone) and
  // a tolerance on the damage no ten iterations reach.
  const Result r = mesocrack({"run", (kScenes / "rigid_cell_wave_2d.toml").string(), "-o", "weak.h5", "--set",
                              "groups[0].velocity=[\"-0.1 m/s\", 0]", "--set", "contacts[0].tensile_strength=0.5 MPa",
                              "--set", "contacts[0].fracture_energy=10 N/m", "--set", "rigid_cell.max_iterations=1",
                              "--set", "rigid_cell.damage_tolerance=1e-15"},
                             d.dir);
  CHECK(r.code == 4);
  CHECK_MESSAGE(contains(r.err, "Newmark step"), r.err);
  CHECK_MESSAGE(contains(r.err, "out-of-balance ratio"), r.err);
  // What ran is kept, with no NaN in it.
  const mc::H5File f((d / "weak.h5").string(), mc::H5File::Mode::ReadOnly);
  for (double x : series(f, "group.struck.reaction_x")) REQUIRE(std::isfinite(x));
}

TEST_CASE("rigid_cell_rate_dependent_facets_hold_more_of_a_tensile_wave") {
  const TempDir d;
  // The bar pulled (a tensile wave of ρcv = 0.85 MPa) with facets of f_t 0.6 MPa: rate-independent they damage all
  // along the bar behind the front; with Tab. 8.1's set 1 (c₀ 1e-5 /s, c₁ 0.05) the front's strain rate (about
  // 1 /s) raises their limit by F ≈ 1.6 while it passes, and they damage less (measured: 827 facets to D 0.98
  // without, 407 to D 0.41 with).
  const std::vector<std::string> pulled = {"--set", "groups[0].velocity=[\"-0.1 m/s\", 0]",
                                           "--set", "contacts[0].tensile_strength=0.6 MPa",
                                           "--set", "contacts[0].fracture_energy=10 N/m"};
  auto run = [&](const std::string& out, std::vector<std::string> extra) {
    std::vector<std::string> args{"run", (kScenes / "rigid_cell_wave_2d.toml").string(), "-o", out};
    args.insert(args.end(), pulled.begin(), pulled.end());
    args.insert(args.end(), extra.begin(), extra.end());
    const Result r = mesocrack(args, d.dir);
    REQUIRE_MESSAGE(r.code == 0, r.describe());
    return mc::H5File((d / out).string(), mc::H5File::Mode::ReadOnly);
  };
  const mc::H5File plain = run("plain.h5", {});
  const mc::H5File rated = run("rated.h5", {"--set", "contacts[0].rate_c0=1e-5", "--set", "contacts[0].rate_c1=0.05"});
  CHECK(series(rated, "damage.max").back() < 0.5 * series(plain, "damage.max").back());
  CHECK(series(rated, "facets.damaged").back() < series(plain, "facets.damaged").back());
  // A rate dependence in a static scene is refused: it acts on velocities.
  const Result quasi = mesocrack({"run", (kScenes / "rigid_cell_tension_2d.toml").string(), "-o", "static.h5", "--set",
                                  "contacts[0].tensile_strength=3 MPa", "--set", "contacts[0].fracture_energy=60 N/m",
                                  "--set", "contacts[0].rate_c0=1e-5", "--set", "contacts[0].rate_c1=0.05"},
                                 d.dir);
  CHECK(quasi.code == 2);
  CHECK_MESSAGE(contains(quasi.err, "[rigid_cell.dynamics]"), quasi.err);
  CHECK_FALSE(fs::exists(d / "static.h5"));
}

TEST_CASE("rigid_cell_dynamics_bad_input_names_the_key") {
  const TempDir d;
  const std::string scene = (kScenes / "rigid_cell_wave_2d.toml").string();
  const Result unstable = mesocrack(
      {"run", scene, "-o", "a.h5", "--set", "rigid_cell.dynamics.beta=0.2", "--set", "rigid_cell.dynamics.gamma=0.5"},
      d.dir);
  CHECK(unstable.code == 2);
  CHECK_MESSAGE(contains(unstable.err, "rigid_cell.dynamics.beta"), unstable.err);
  CHECK_MESSAGE(contains(unstable.err, "(8.5)"), unstable.err);
  CHECK_FALSE(fs::exists(d / "a.h5"));
  // A stress wave needs dynamics, and a face in its box.
  const std::string wave = (kScenes / "stress_wave_bar_2d.toml").string();
  const Result missed =
      mesocrack({"run", wave, "-o", "c.h5", "--set", "rigid_cell.stress_wave.box_lo=[\"1 mm\", \"1 mm\"]", "--set",
                 "rigid_cell.stress_wave.box_hi=[\"2 mm\", \"2 mm\"]"},
                d.dir);
  CHECK(missed.code == 2);
  CHECK_MESSAGE(contains(missed.err, "holds the centroid of no surface facet"), missed.err);
  CHECK_FALSE(fs::exists(d / "c.h5"));
  // A load on a held degree of freedom would go straight into the support.
  const Result held = mesocrack({"run", scene, "-o", "b.h5", "--set", "groups[0].force=[\"1 N\", 0]"}, d.dir);
  CHECK(held.code == 2);
  CHECK_MESSAGE(contains(held.err, "groups[0].force"), held.err);
  CHECK_MESSAGE(contains(held.err, "which it holds"), held.err);
  CHECK_FALSE(fs::exists(d / "b.h5"));
}
