// The cpm model's scene keys: read with their units and defaults, a bad value fails naming the file, the key, the
// value and what is allowed, and a 2D scene naming cpm is refused (the law and its calibration are for spheres).
#include <doctest/doctest.h>

#include <string>

#include "engine/errors.hpp"
#include "scene/scene.hpp"
#include "scene/toml_reader.hpp"
#include "tests/common/errors.hpp"

using namespace mc;

namespace {

std::string scene(int dim, const std::string& extra) {
  return "dimension = " + std::to_string(dim) + R"(
[[phases]]
name = "c"
density = "4800 kg/m3"
[[contacts]]
phase_a = "c"
model = "cpm"
modulus = "24 GPa"
crack_onset_strain = 1e-4
relative_ductility = 30
cohesion = "3.5 MPa"
friction_angle = "38.66 deg"
)" + extra +
         R"(
[specimen]
kind = "particles"
[[specimen.particles]]
x = [0, 0, 0]
radius = "1 mm"
[bonds]
[run]
steps = 1
)";
}

// The message of reading a scene that must be refused.
std::string refusal(const std::string& text) {
  return test::error_of([&] { read_scene(TomlDoc::parse_text(text, "s.toml"), "s.toml"); });
}

}  // namespace

TEST_CASE("cpm scene keys: read with their defaults, bad values and 2D refused with the key named") {
  const Scene s = read_scene(TomlDoc::parse_text(scene(3, ""), "s.toml"), "s.toml");
  REQUIRE(s.contacts.size() == 1);
  CHECK(s.contacts[0].model.name == "cpm");
  CHECK(s.contacts[0].model.bonds);
  CHECK(s.contacts[0].model.yields);
  // A friction angle of 90° or more has no tangent: the range is named.
  const std::string a = refusal(scene(3, "").replace(scene(3, "").find("38.66 deg"), 9, "95 deg"));
  MESSAGE(a);
  CHECK(a.find("s.toml") != std::string::npos);
  CHECK(a.find("friction_angle") != std::string::npos);
  // The confinement is compressive (≤ 0).
  const std::string b = refusal(scene(3, "confinement = \"2 MPa\""));
  MESSAGE(b);
  CHECK(b.find("confinement") != std::string::npos);
  const std::string c = refusal(scene(3, "compression_yield = \"parabolic\""));
  MESSAGE(c);
  CHECK(c.find("logarithmic") != std::string::npos);
  CHECK(refusal(scene(3, "interaction_radius = 0.9")).find("interaction_radius") != std::string::npos);
  CHECK(refusal(scene(3, "break_damage = 0")).find("break_damage") != std::string::npos);
  CHECK(refusal(scene(3, "bond_normal_strength = \"1 N\"")).find("bond_normal_strength") != std::string::npos);
  // 2D: refused, naming the model key and the 2D models to use instead.
  const std::string d = refusal(scene(2, "").replace(scene(2, "").find("x = [0, 0, 0]"), 13, "x = [0, 0]"));
  MESSAGE(d);
  CHECK(d.find("model") != std::string::npos);
  CHECK(d.find("dimension = 3") != std::string::npos);
}
