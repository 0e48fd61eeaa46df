// Geometry that has no meaning is refused when the scene is read or built, naming the file and the key (exit 2
// on the command line), instead of running into NaN forces, particles through walls or 0/0 histories.
#include <doctest/doctest.h>

#include <string>

#include "engine/errors.hpp"
#include "scene/make_system.hpp"
#include "scene/scene.hpp"
#include "scene/toml_reader.hpp"
#include "tests/common/errors.hpp"
#include "tests/common/scene_text.hpp"

namespace {

const std::string kFile = "tests/degenerate.toml";

// Two discs between a floor and a roof, observed by a wall strain and two probes: each case edits one thing.
const std::string kScene2d = mc::test::linear_grains(2) + R"([specimen]
kind = "particles"
[[specimen.particles]]
x = ["2 mm", "2 mm"]
radius = "1 mm"
[[specimen.particles]]
x = ["4.5 mm", "2 mm"]
radius = "1 mm"
[[walls]]
name = "floor"
shape = "segment"
a = [0, 0]
b = ["10 mm", 0]
inside = ["5 mm", "5 mm"]
kn = "1e7 N/m"
[[walls]]
name = "roof"
shape = "segment"
a = [0, "10 mm"]
b = ["10 mm", "10 mm"]
inside = ["5 mm", "5 mm"]
kn = "1e7 N/m"
[[wall_strains]]
name = "vertical"
walls = "floor roof"
[[probes]]
name = "gap"
kind = "gap"
particles = [0, 1]
[[groups]]
name = "left"
box_lo = [0, 0]
box_hi = ["3 mm", "10 mm"]
[run]
steps = 10
)";

const std::string kScene3d = mc::test::linear_grains(3) + R"([specimen]
kind = "particles"
[[specimen.particles]]
x = ["2 mm", "2 mm", "2 mm"]
radius = "1 mm"
[[walls]]
name = "floor"
shape = "rectangle"
centre = ["2 mm", "2 mm", 0]
normal = [0, 0, 1]
axis = [1, 0, 0]
size = ["10 mm", "10 mm"]
kn = "1e7 N/m"
[run]
steps = 10
)";

// `text` with its one occurrence of `what` replaced (an edit that silently missed would test nothing).
std::string edit(std::string text, const std::string& what, const std::string& with) {
  const auto at = text.find(what);
  REQUIRE_MESSAGE(at != std::string::npos, "the base scene lacks '", what, "'");
  REQUIRE_MESSAGE(text.find(what, at + 1) == std::string::npos, "the base scene has '", what, "' twice");
  return text.replace(at, what.size(), with);
}

// Reading and building the scene: the message of the InputError it throws.
std::string refusal(const std::string& text) {
  return mc::test::error_of([&] {
    const mc::Scene s = mc::read_scene(mc::TomlDoc::parse_text(text, kFile, {}), kFile);
    mc::make_system(s);
  });
}

void check_names(const std::string& message, std::initializer_list<std::string> parts) {
  CHECK_MESSAGE(message.find(kFile) != std::string::npos, message, " lacks the file");
  for (const auto& p : parts) CHECK_MESSAGE(message.find(p) != std::string::npos, message, " lacks ", p);
}

}  // namespace

TEST_CASE("the unedited geometry cases build, so each refusal below is the edit's") {
  CHECK_NOTHROW(mc::make_system(mc::read_scene(mc::TomlDoc::parse_text(kScene2d, kFile, {}), kFile)));
  CHECK_NOTHROW(mc::make_system(mc::read_scene(mc::TomlDoc::parse_text(kScene3d, kFile, {}), kFile)));
}

TEST_CASE("a zero-length segment wall is refused: its normal would be 0/0") {
  check_names(refusal(edit(kScene2d, "b = [\"10 mm\", 0]", "b = [0, 0]")), {"walls[0].b", "same point"});
}

TEST_CASE("a segment wall whose inside point lies on its line is refused: the particles' side is undecidable") {
  check_names(refusal(edit(kScene2d, "inside = [\"5 mm\", \"5 mm\"]\nkn = \"1e7 N/m\"\n[[walls]]",
                           "inside = [\"20 mm\", 0]\nkn = \"1e7 N/m\"\n[[walls]]")),
              {"walls[0].inside", "on the segment's line"});
}

TEST_CASE("a rectangle wall whose axis is parallel to its normal is refused: it has no edge directions") {
  check_names(refusal(edit(kScene3d, "axis = [1, 0, 0]", "axis = [0, 0, -2]")), {"walls[0].axis", "parallel"});
  check_names(refusal(edit(kScene3d, "axis = [1, 0, 0]", "axis = [0, 0, 0]")), {"walls[0].axis", "zero"});
}

TEST_CASE("a domain whose low corner is not below its high corner is refused, naming the direction") {
  const std::string physics = "[physics]\ndomain_lo = [0, 0]\ndomain_hi = [\"10 mm\", \"10 mm\"]\n";
  CHECK_NOTHROW(mc::read_scene(mc::TomlDoc::parse_text(kScene2d + physics, kFile, {}), kFile));
  check_names(refusal(kScene2d + edit(physics, "domain_hi = [\"10 mm\", \"10 mm\"]", "domain_hi = [\"10 mm\", 0]")),
              {"physics.domain_hi", "its y"});
  check_names(refusal(kScene2d + "[physics]\ndomain_lo = [0, 0]\n"), {"physics.domain_lo", "go together"});
}

TEST_CASE("a domain that leaves a particle outside at the start is refused naming the particle") {
  check_names(refusal(kScene2d + "[physics]\ndomain_lo = [0, 0]\ndomain_hi = [\"3 mm\", \"10 mm\"]\n"),
              {"domain", "particle 1", "outside"});
}

TEST_CASE("a group box with its high corner below its low corner is refused naming the direction") {
  check_names(refusal(edit(kScene2d, "box_hi = [\"3 mm\", \"10 mm\"]", "box_hi = [\"3 mm\", \"-1 mm\"]")),
              {"groups[0].box_hi", "its y"});
}

TEST_CASE("a wall strain between a wall and itself, or walls not facing each other, is refused: its gap is 0") {
  check_names(refusal(edit(kScene2d, "walls = \"floor roof\"", "walls = \"floor floor\"")),
              {"wall_strains[0].walls", "twice"});
  // The roof moved below the floor: the gap along the floor's normal is negative.
  const std::string below = edit(edit(kScene2d, "a = [0, \"10 mm\"]", "a = [0, \"-10 mm\"]"),
                                 "b = [\"10 mm\", \"10 mm\"]", "b = [\"10 mm\", \"-10 mm\"]");
  check_names(refusal(below), {"wall_strains 'vertical'", "roof", "face each other"});
}

TEST_CASE("a two-particle probe naming one particle twice is refused: its line of centres is 0/0") {
  check_names(refusal(edit(kScene2d, "particles = [0, 1]", "particles = [1, 1]")), {"probes[0].particles", "twice"});
}

TEST_CASE("particle ids and tags that are not whole numbers are refused, never truncated") {
  check_names(refusal(edit(kScene2d, "particles = [0, 1]", "particles = [0, 1.5]")),
              {"probes[0].particles", "1.5", "whole numbers"});
}

TEST_CASE("coincident particle centres are refused at build time naming both ids") {
  check_names(refusal(edit(kScene2d, "x = [\"4.5 mm\", \"2 mm\"]", "x = [\"2 mm\", \"2 mm\"]")),
              {"particles 0 and 1", "same centre"});
}

TEST_CASE("a particle of a huge radius beside a small one is refused as the overlap it is, not as a shared centre") {
  // 2.5 mm apart, one of them 1e300 m in radius: the small one lies deep inside it (it was "the same centre").
  const std::string huge =
      edit(kScene2d, "x = [\"4.5 mm\", \"2 mm\"]\nradius = \"1 mm\"", "x = [\"4.5 mm\", \"2 mm\"]\nradius = 1e300");
  check_names(refusal(huge), {"particles 0 and 1", "overlap by"});
}
