// A small CPM specimen for tests that run `calibrate`: a 1:1:2 packing of about 250 spheres of the shipped scenes'
// radius (the shipped 2007-sphere specimen takes about 50 s per tension run), strained in tension as
// scenes/cpm_uniax_tension.toml strains its own, or in compression the other way.
#pragma once
#include <string>

namespace small_cpm {

// PFC genesis of a 25 × 25 × 50 mm cuboid, as scenes/specimens/cpm_1x1x2.toml makes the shipped one (seed 2:
// seed 1's genesis ends 4 % off the settling stress at this size, which `generate` refuses).
inline const char* kPacking = R"(title = "small CPM specimen"
dimension = 3
seed = 2
[[phases]]
name = "concrete"
density = "4800 kg/m3"
[[contacts]]
phase_a = "concrete"
model = "linear"
modulus = "24 GPa"
[specimen]
kind = "packing"
lo = [0, 0, 0]
hi = ["25 mm", "25 mm", "50 mm"]
radius_min = "2.67 mm"
radius_ratio = 1.0
porosity = 0.36
stress = "0.1 MPa"
modulus = "24 GPa"
[run]
steps = 1
)";

// scenes/cpm_uniax_tension.toml on that specimen: the end layers (centres within 3 r of the end faces) move
// apart at 0.05 /s, free in x and y; stopped at half the peak on the way down (f_t is all the test reads).
inline const char* kTension = R"(title = "small CPM uniaxial tension"
dimension = 3
seed = 1
[[phases]]
name = "concrete"
density = "4800 kg/m3"
[[contacts]]
phase_a = "concrete"
model = "cpm"
modulus = "24 GPa"
kt_kn_ratio = 0.2
crack_onset_strain = 1e-4
relative_ductility = 30
cohesion = "3.5 MPa"
friction_angle = 0.6747409422
interaction_radius = 1.5
[specimen]
kind = "output"
file = "packing.h5"
[bonds]
crack_log = true
[[groups]]
name = "bottom"
box_lo = ["-1 mm", "-1 mm", "-1 mm"]
box_hi = ["26 mm", "26 mm", "8.01 mm"]
fix = "z"
velocity = [0, 0, "-1.25 mm/s"]
[[groups]]
name = "top"
box_lo = ["-1 mm", "-1 mm", "41.99 mm"]
box_hi = ["26 mm", "26 mm", "51 mm"]
fix = "z"
velocity = [0, 0, "1.25 mm/s"]
[physics]
local_damping = 0.4
[uniaxial]
loading = "tension"
supports = "bottom top"
axis = "z"
[run]
duration = "20 ms"
[[run.stop]]
quantity = "uniaxial.stress"
post_peak_fraction = 0.5
)";

// The tension scene strained the other way: the supports move together.
inline std::string compression() {
  std::string s = kTension;
  auto swap = [&](const std::string& from, const std::string& to) { s.replace(s.find(from), from.size(), to); };
  swap("velocity = [0, 0, \"-1.25 mm/s\"]", "velocity = [0, 0, \"bottom\"]");
  swap("velocity = [0, 0, \"1.25 mm/s\"]", "velocity = [0, 0, \"-1.25 mm/s\"]");
  swap("velocity = [0, 0, \"bottom\"]", "velocity = [0, 0, \"1.25 mm/s\"]");
  swap("loading = \"tension\"", "loading = \"compression\"");
  return s;
}

}  // namespace small_cpm
