// Three-point bending through the real `mesocrack` command ([bending], Tang §7.1): an elastic hexagonal-lattice
// beam has the stiffness of Timoshenko's beam with shear; the opening servo (CMOD control) holds its rate through
// the peak of the notched beam of scenes/bending_small_2d.toml and resumes bit for bit; bad [bending] keys and
// opening-control keys are refused naming them.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "engine/wall.hpp"
#include "preprocess/regular_packing.hpp"
#include "tests/common/cli_harness.hpp"
#include "tests/common/relative.hpp"

namespace {

const std::string kBeam = (kScenes / "bending_small_2d.toml").string();

std::vector<double> history(const fs::path& file, const std::string& name) {
  const mc::H5File f(file.string(), mc::H5File::Mode::ReadOnly);
  return f.read_doubles("/history/" + name);
}

// Least-squares slope of y on x over the rows [from, to).
double slope(const std::vector<double>& x, const std::vector<double>& y, std::size_t from, std::size_t to) {
  double mx = 0, my = 0;
  const double n = static_cast<double>(to - from);
  for (std::size_t k = from; k < to; ++k) mx += x[k] / n, my += y[k] / n;
  double sxy = 0, sxx = 0;
  for (std::size_t k = from; k < to; ++k) sxy += (x[k] - mx) * (y[k] - my), sxx += (x[k] - mx) * (x[k] - mx);
  return sxy / sxx;
}

}  // namespace

// An unnotched beam of 20 rows × 80 discs (R = 1 mm), every touching pair joined by an unbreakable contact bond
// with K^n, K^s of Tang (8.3) for E = 30 GPa, ν = 0.2 in plane stress (the lattice's own constants, checked by
// hex_lattice_virtual_tension_gives_plane_stress_E_and_nu_of_tang_8_3 to 2 %), on two frictionless supports
// 140 mm apart, loaded at mid-span by a wall moving down. Beam theory with shear (Timoshenko):
// k = 1/(L³/(48EI) + L/(4κGA)), plane stress, unit thickness, I = h³/12, A = h, G = E/(2(1 + ν)), κ = 5/6, with
// h = 20 √3 R, the depth the rows stand for (as (2N − 1) R is the width in the tension test). The deflection is
// read by a yoke on the neutral axis (groups at mid-depth above the supports and at mid-span), as RILEM's
// measurement excludes the indentation under the load and the supports. What beam theory leaves out is the
// local stress field under the load (Timoshenko & Goodier's 2D solution adds −0.84 (h/L)³ to the 1 + 2.9 (h/L)²
// of bending plus shear: 1 % at L/h = 4) and the lattice's discreteness (2 % on E): 5 % holds both.
TEST_CASE("elastic_lattice_beam_in_three_point_bending_has_timoshenko_stiffness_with_shear") {
  const TempDir d;
  const double E = 30e9, nu = 0.2, R = 1e-3;
  const mc::LatticeStiffness k = mc::hex_lattice_stiffness_plane_stress(E, nu);
  auto num = [](double x) {
    std::ostringstream s;
    s.precision(17);
    s << x;
    return s.str();
  };
  const double top = R + 19 * std::sqrt(3.0) * R + R;  // the top row's upper surface
  const std::string scene = R"(dimension = 2
[[phases]]
name = "c"
density = 2400
[[contacts]]
phase_a = "c"
model = "contact_bond"
modulus = )" + num(k.normal) +
                            R"(
kn_ks_ratio = )" + num(k.normal / k.shear) +
                            R"(
bond_normal_strength = 1e12
bond_shear_strength = 1e12
[bonds]
gap_tolerance = 1e-6
[specimen]
kind = "lattice"
lo = [0, 0]
hi = ["160 mm", "35 mm"]
radius = "1 mm"
[[groups]]
name = "mid"
box_lo = ["77.5 mm", "15.5 mm"]
box_hi = ["82.5 mm", "19.5 mm"]
[[groups]]
name = "above_left"
box_lo = ["7.5 mm", "15.5 mm"]
box_hi = ["12.5 mm", "19.5 mm"]
[[groups]]
name = "above_right"
box_lo = ["147.5 mm", "15.5 mm"]
box_hi = ["152.5 mm", "19.5 mm"]
[[walls]]
name = "left"
shape = "segment"
a = ["8 mm", 0]
b = ["12 mm", 0]
inside = ["10 mm", "10 mm"]
kn = 1e11
[[walls]]
name = "right"
shape = "segment"
a = ["148 mm", 0]
b = ["152 mm", 0]
inside = ["150 mm", "10 mm"]
kn = 1e11
[[walls]]
name = "load"
shape = "segment"
a = ["77 mm", )" + num(top) +
                            R"(]
b = ["83 mm", )" + num(top) +
                            R"(]
inside = ["80 mm", "10 mm"]
kn = 1e11
motion = "velocity"
velocity = [0, "-2 mm/s"]
ramp_time = "1 ms"
[[groups]]
name = "mouth_left"
box_lo = ["76.5 mm", 0]
box_hi = ["79.5 mm", "3 mm"]
[[groups]]
name = "mouth_right"
box_lo = ["80.5 mm", 0]
box_hi = ["83.5 mm", "3 mm"]
[[probes]]
name = "cmod"
kind = "opening"
groups = "mouth_left mouth_right"
[physics]
local_damping = 0.7
[bending]
load_wall = "load"
supports = "left right"
deflection_groups = "mid above_left above_right"
cmod = "cmod"
span = "140 mm"
depth = )" + num(20 * std::sqrt(3.0) * R) +
                            R"(
[run]
duration = "3 ms"
[output]
history_every = 20
)";
  write_file(d / "beam.toml", scene);
  const Result r = mesocrack({"run", "beam.toml", "-o", "beam.h5"}, d.dir);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  const Json j = summary_of("beam.h5", d.dir);
  const double L = 0.14, h = 20 * std::sqrt(3.0) * R, I = h * h * h / 12, A = h, G = E / (2 * (1 + nu));
  const double bending = L * L * L / (48 * E * I), shear = L / (4 * (5.0 / 6.0) * G * A);
  const double expected = 1 / (bending + shear);
  const double measured = j["bending"]["stiffness_simulated"].number;
  MESSAGE("Timoshenko k = ", expected, " N/m (shear ", shear / (bending + shear) * 100,
          " % of the compliance), measured ", measured, " N/m (ratio ", measured / expected, "), run ", r.seconds,
          " s");
  CHECK(measured == mc::test::relative(expected, 0.05));
}

// The notched beam under CMOD control, in one run (with energy tracing, which changes no force):
// - the servo: once the ramp is over (twice its length), the crack-mouth opening grows at the prescribed 10 mm/s
//   through the peak and past it. Checked as the least-squares slope of CMOD(t) over each fifth of the stretch
//   from the end of the ramp to where the load has fallen to 60 % of the peak after it, and over the tenth of that
//   stretch centred on the peak: each within 5 % of the rate.
// - the energy balance of the whole test (Tang 3.74–3.80): the loading point's work equals the strain energy plus
//   what bond breakage and softening, friction and local damping dissipated plus the kinetic energy, within 1 % at
//   every recorded row once the work is under way (the summary's worst |residual| / work). Central differences
//   conserve energy to O(Δt²) per step and every dissipation is booked by the law that causes it, so what is left
//   is the dashpot-free integrator's error: far below 1 %. Quasi-static under CMOD control, the work goes mostly
//   into fracture: the bonds' share above half, local damping's below a fifth (measured 75 % and 8 %).
TEST_CASE("notched_beam_under_cmod_control_holds_its_opening_rate_and_closes_its_energy_balance_within_one_percent") {
  const TempDir d;
  const Result r = mesocrack({"run", kBeam, "-o", "beam.h5", "--set", "physics.energy=true"}, d.dir);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  const auto t = history(d / "beam.h5", "time"), cmod = history(d / "beam.h5", "bending.cmod"),
             load = history(d / "beam.h5", "bending.load");
  const Json j = summary_of("beam.h5", d.dir);
  {  // the opening rate through the peak
    const double rate = 10e-3, ramp = 0.5e-3;
    const std::size_t peak = static_cast<std::size_t>(std::max_element(load.begin(), load.end()) - load.begin());
    std::size_t from = 0, to = peak;
    while (t[from] < 2 * ramp) ++from;
    while (to + 1 < load.size() && load[to] > 0.6 * load[peak]) ++to;
    REQUIRE(peak > from + 50);
    REQUIRE(to > peak);
    MESSAGE("peak load ", j["bending"]["peak_load"].number, " N per 100 mm at CMOD ", cmod[peak] * 1e6,
            " um, t = ", t[peak] * 1e3, " ms; G_F = ", j["bending"]["G_F"].number, " N/m; run ", r.seconds, " s");
    const std::size_t fifth = (to - from) / 5;
    for (int k = 0; k < 5; ++k) {
      const double s = slope(t, cmod, from + k * fifth, from + (k + 1) * fifth);
      MESSAGE("CMOD rate over fifth ", k + 1, ": ", s * 1e3, " mm/s");
      CHECK(s == mc::test::relative(rate, 0.05));
    }
    const std::size_t half = (to - from) / 20;
    const double at_peak = slope(t, cmod, peak - half, peak + half);
    MESSAGE("CMOD rate around the peak: ", at_peak * 1e3, " mm/s");
    CHECK(at_peak == mc::test::relative(rate, 0.05));
  }
  {  // the energy balance
    const Json& e = j["bending"]["energy"];
    const double work = e["boundary_work"].number;
    MESSAGE("work ", work, " J: strain ", e["strain"].number, ", bonds ", e["dissipated_bonds"].number, ", friction ",
            e["dissipated_contacts"].number, ", local damping ", e["dissipated_local"].number, ", kinetic ",
            e["kinetic"].number, "; worst |residual|/work ", e["worst_residual_over_work"].number, "; G_F RILEM ",
            j["bending"]["G_F"].number, " N/m, by the bonds ", e["G_F_bonds"].number, " N/m; tortuosity ",
            j["bending"]["crack_path"]["tortuosity"].number);
    CHECK(work > 0);
    CHECK(e["worst_residual_over_work"].number < 0.01);
    CHECK(e["dissipated_bonds"].number > 0.5 * work);
    CHECK(e["dissipated_local"].number < 0.2 * work);
  }
}

// The opening servo's law (wall.hpp): v = clamp(gain (rate·τ(t + Δt) − reading), −retreat_speed, max_speed) along
// the wall's normal, τ the ramped time. Inside the band the wall moves at gain × the gauge's lag; far behind its
// target it advances at max_speed; far ahead (a crack has jumped) it backs off no faster than retreat_speed.
TEST_CASE("opening_servo_is_proportional_inside_its_band_and_backs_off_no_faster_than_its_retreat_speed") {
  mc::Wall<2> w = mc::Wall<2>::segment({-1, 0}, {1, 0}, {0, 1});
  w.control = mc::WallControl::Opening;
  w.opening_rate = 10e-3, w.opening_gain = 8000, w.servo_max_speed = 30e-3, w.retreat_speed = 10e-3;
  const double t = 2e-3, dt = 1e-7, target = w.opening_rate * (t + dt);  // no ramp: τ(t) = t
  w.control_velocity(t, dt, target - 1e-6);                              // 1 µm behind: 8 mm/s
  CHECK(w.velocity.dot(w.normal) == mc::test::relative(8e-3, 1e-9));
  w.control_velocity(t, dt, target + 0.5e-6);  // 0.5 µm ahead: backs off at 4 mm/s, inside the retreat limit
  CHECK(w.velocity.dot(w.normal) == mc::test::relative(-4e-3, 1e-9));
  w.control_velocity(t, dt, target - 1e-3);  // far behind: advances at max_speed
  CHECK(w.velocity.dot(w.normal) == mc::test::relative(30e-3, 1e-12));
  w.control_velocity(t, dt, target + 1e-3);  // far ahead: backs off at retreat_speed only
  CHECK(w.velocity.dot(w.normal) == mc::test::relative(-10e-3, 1e-12));
  CHECK(std::abs(w.velocity.dot(w.axis[0])) < 1e-15);  // along the normal only
}

// A run under opening control stopped and resumed goes on exactly as one never stopped (the opening gauge's
// start and the wall's velocity are in the checkpoint; the controller itself holds no other state), on 1 or 2
// threads.
TEST_CASE("cmod_controlled_beam_resumed_from_a_checkpoint_continues_bit_for_bit") {
  const TempDir d;
  // A frame every 2000 steps: the first half's last frame is one the whole run writes too.
  const std::vector<std::string> frames = {"--set", "output.frame_every=2000"};
  auto args = [&](std::vector<std::string> a) {
    a.insert(a.end(), frames.begin(), frames.end());
    return a;
  };
  const Result whole =
      mesocrack(args({"run", kBeam, "-o", "whole.h5", "--threads", "2", "--set", "run.steps=4000"}), d.dir);
  REQUIRE_MESSAGE(whole.code == 0, whole.describe());
  const Result first = mesocrack(args({"run", kBeam, "-o", "halves.h5", "--set", "run.steps=2000"}), d.dir);
  REQUIRE_MESSAGE(first.code == 0, first.describe());
  const Result rest = mesocrack(args({"run", kBeam, "--resume", "halves.h5", "--set", "run.steps=4000"}), d.dir);
  REQUIRE_MESSAGE(rest.code == 0, rest.describe());
  check_same_run(d / "whole.h5", d / "halves.h5");
}

// Bad [bending] keys, and opening control pointing at what is not an opening probe: exit 2, naming the file,
// the key, the value and what is allowed; nothing written.
TEST_CASE("bad_bending_and_opening_control_keys_are_refused_naming_the_key") {
  const TempDir d;
  const std::vector<SceneEdit> edits = {
      {"load_wall = \"load\"", "load_wall = \"top\"", {"bending.load_wall", "'top' is not the name"}},
      {"supports = \"left right\"", "supports = \"left\"", {"bending.supports", "names of 2 [[walls]]"}},
      {"supports = \"left right\"", "supports = \"left load\"", {"bending.supports", "loading wall"}},
      {"cmod = \"cmod\"\nspan", "cmod = \"mouth\"\nspan", {"bending.cmod", "'mouth'", "opening probe"}},
      {"ligament = \"32.909 mm\"", "ligament = \"50 mm\"", {"bending.ligament", "exceed the depth"}},
      {"span = \"120 mm\"", "span = \"-1 mm\"", {"bending.span", "> 0"}},
      {"thickness = \"100 mm\"", "thickness = \"100 MPa\"", {"bending.thickness", "100 MPa"}},
      {"thickness = \"100 mm\"", "thickness = \"100 mm\"\nnotch = 1", {"bending.notch"}},
      {"probe = \"cmod\"", "probe = \"gauge\"", {"walls[2].probe", "'gauge'", "opening probe", "declared: cmod"}},
      {"gain = \"50000 /s\"", "gain = 0", {"walls[2].gain", "> 0"}},
      {"max_speed = \"500 mm/s\"",
       "max_speed = \"500 mm/s\"\nretreat_speed = \"0 mm/s\"",
       {"walls[2].retreat_speed", "> 0"}},
      {"groups = \"mouth_left mouth_right\"", "groups = \"mouth_left\"", {"probes[0].groups", "two [[groups]]"}},
      // A support 5 mm below the beam (its particles of 1 mm radius rest on y = 0): it gave exit 0 and a peak.
      {"a = [\"138 mm\", 0]\nb = [\"142 mm\", 0]", "a = [\"138 mm\", \"-5 mm\"]\nb = [\"142 mm\", \"-5 mm\"]",
       {"bending.supports", "wall 'right'", "must touch the beam"}},
  };
  check_edits_refused(d.dir, slurp(kBeam), edits);
}
