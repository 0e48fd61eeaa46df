// The scene reader's promise: every bad input fails with one line naming the file, the key, the value and
// what is allowed; units convert exactly; --set overrides land where they say and are validated like the file.
#include <doctest/doctest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "engine/errors.hpp"
#include "scene/toml_reader.hpp"
#include "tests/common/errors.hpp"

using mc::InputError;
using mc::Range;
using mc::TomlDoc;
using mc::Unit;

namespace {

using mc::test::error_of;

const std::string kFile = "scenes/a.toml";

TomlDoc doc(const std::string& text, const std::vector<std::string>& overrides = {}) {
  return TomlDoc::parse_text(text, kFile, overrides);
}

void check_names(const std::string& message, const std::vector<std::string>& parts) {
  for (const auto& part : parts) CHECK_MESSAGE(message.find(part) != std::string::npos, message, " lacks ", part);
}

double number_of(const std::string& text, Unit u) { return doc("x = " + text).root().number("x", u, Range::any()); }

}  // namespace

TEST_CASE("scene input: a missing key names the key and what it takes") {
  const auto d = doc("[material]\nE = 3e10\n");
  CHECK(error_of([&] { d.root().table("material").number("density", Unit::Density, Range::positive()); }) ==
        "scenes/a.toml: missing key 'material.density' (a number in kg/m3, e.g. 2600 or \"2.6 g/cm3\")");
  check_names(error_of([&] { d.root().table("contact"); }), {kFile, "'contact'", "a table"});
  check_names(error_of([&] {
                d.root().table("material").choice("model", {"a", "b"});
              }),
              {kFile, "'material.model'", "one of: a, b"});
}

TEST_CASE("scene input: an out-of-range value names the range, never clamps") {
  CHECK(error_of([] {
          doc("[damping]\nlocal = 1.5\n").root().table("damping").number("local", Unit::None, Range::open_fraction());
        }) == "scenes/a.toml: key 'damping.local' = 1.5 is out of range: allowed 0 <= value < 1");
  // A quantity is checked in SI, and the message shows both what was written and its SI value.
  CHECK(error_of([] { doc("E = \"-30 GPa\"").root().number("E", Unit::Pressure, Range::positive()); }) ==
        "scenes/a.toml: key 'E' = \"-30 GPa\" (-3e+10 Pa) is out of range: allowed value > 0 Pa");
  check_names(error_of([] { doc("n = -2").root().integer("n", Range::at_least(1)); }),
              {kFile, "'n' = -2", "value >= 1"});
  check_names(error_of([] { doc("r = 0.0").root().number("r", Unit::Length, Range::closed(0.001, 0.01)); }),
              {kFile, "'r' = 0.0", "0.001 m <= value <= 0.01 m"});
}

TEST_CASE("scene input: non-finite numbers are refused") {
  check_names(error_of([] { number_of("nan", Unit::None); }), {kFile, "'x' = nan", "finite"});
  check_names(error_of([] { number_of("-inf", Unit::Length); }), {kFile, "'x' = -inf", "finite number in m"});
  check_names(error_of([] { number_of("\"1e400 Pa\"", Unit::Pressure); }), {kFile, "\"1e400 Pa\"", "finite"});
}

TEST_CASE("scene input: a value of the wrong type names the expected type") {
  const auto d = doc("[[walls]]\nvelocity = 0.0\n[[walls]]\nvelocity = \"abc\"\n");
  CHECK(error_of([&] { d.root().tables("walls").at(1).number("velocity", Unit::Velocity, Range::any()); }) ==
        "scenes/a.toml: key 'walls[1].velocity' = \"abc\": expected a number in m/s (or a string with a unit such as "
        "\"5 mm/s\")");
  check_names(error_of([] { doc("x = true").root().number("x", Unit::None, Range::any()); }),
              {kFile, "'x' = true", "expected a number"});
  check_names(error_of([] { doc("n = 2.5").root().integer("n", Range::any()); }),
              {kFile, "'n' = 2.5", "expected an integer"});
  check_names(error_of([] { doc("b = 1").root().boolean("b"); }), {kFile, "'b' = 1", "expected true or false"});
  check_names(error_of([] { doc("s = [1, 2]").root().string("s"); }), {kFile, "'s' = [1, 2]", "expected a string"});
  check_names(error_of([] { doc("material = 5").root().table("material"); }),
              {kFile, "'material' = 5", "expected a table"});
  check_names(error_of([] { doc("walls = 5").root().tables("walls"); }), {kFile, "'walls' = 5", "[[walls]]"});
}

TEST_CASE("scene input: arrays of numbers check their length and each element") {
  const auto root = doc("g = [0, 0]\nh = [0, \"1 m/s2\", \"x\"]\nk = 3\n").root();
  check_names(error_of([&] { root.numbers("g", Unit::Acceleration, Range::any(), 3); }),
              {kFile, "'g' = [0, 0]", "expected an array of 3 numbers in m/s2, got 2"});
  check_names(error_of([&] { root.numbers("h", Unit::Acceleration, Range::any(), 3); }),
              {kFile, "'h[2]' = \"x\"", "expected a number in m/s2"});
  check_names(error_of([&] { root.numbers("k", Unit::None, Range::any(), 0); }),
              {kFile, "'k' = 3", "an array of numbers"});
  CHECK(doc("g = [1, \"2 mm\", 3.5]").root().numbers("g", Unit::Length, Range::any(), 0) ==
        std::vector<double>{1.0, 0.002, 3.5});
}

TEST_CASE("scene input: unknown keys are errors that list what is allowed") {
  const auto d = doc("[contact]\nkn = 1e6\nkn_ratoi = 2.0\n");
  const auto contact = d.root().table("contact");
  contact.number("kn", Unit::Stiffness, Range::positive());
  contact.number("kn_ks_ratio", Unit::None, Range::positive(), 2.5);
  contact.number("friction", Unit::None, Range::non_negative(), 0.5);
  contact.choice("model", {"linear", "hertz_mindlin"}, "linear");
  CHECK(error_of([&] { contact.finish(); }) ==
        "scenes/a.toml: unknown key 'contact.kn_ratoi'; allowed here: kn, kn_ks_ratio, friction, model");
  CHECK(error_of([&] { d.finish_all(); }) ==
        "scenes/a.toml: unknown key 'contact.kn_ratoi'; allowed here: kn, kn_ks_ratio, friction, model");

  // A whole table nobody read is an unknown key of its parent.
  const auto e = doc("[material]\ndensity = 2600\n[outptu]\nevery = 10\n");
  e.root().table("material").number("density", Unit::Density, Range::positive());
  e.root().optional_table("output");
  CHECK(error_of([&] { e.finish_all(); }) ==
        "scenes/a.toml: unknown key 'outptu': a misspelling of 'output'?; allowed here: material, output");

  const auto set = doc("x = 1\n", {"y=2"});
  set.root().integer("x", Range::any());
  CHECK(error_of([&] { set.finish_all(); }) == "scenes/a.toml: unknown key 'y' (from --set); allowed here: x");

  const auto w = doc("[[walls]]\nvelocity = 1\n[[walls]]\nveloctiy = 1\n");
  for (const auto& wall : w.root().tables("walls")) wall.number("velocity", Unit::Velocity, Range::any(), 0.0);
  CHECK(error_of([&] { w.finish_all(); }) ==
        "scenes/a.toml: unknown key 'walls[1].veloctiy': a misspelling of 'velocity'?; allowed here: velocity");
}

TEST_CASE("scene input: a unit of the wrong kind lists the units allowed") {
  CHECK(error_of([] {
          doc("[material]\nE = \"30 GPa/s\"\n").root().table("material").number("E", Unit::Pressure, Range::positive());
        }) ==
        "scenes/a.toml: key 'material.E' = \"30 GPa/s\": unit 'GPa/s' is not a pressure; use Pa, kPa, MPa or GPa");
  CHECK(error_of([] { number_of("\"5 mm\"", Unit::Velocity); }) ==
        "scenes/a.toml: key 'x' = \"5 mm\": unit 'mm' is a length, not a velocity; use m/s, mm/s, mm/min or um/s");
  check_names(error_of([] { number_of("\"3 m\"", Unit::None); }), {kFile, "'x' = \"3 m\"", "a plain number or %"});
  check_names(error_of([] { number_of("\"mm\"", Unit::Length); }), {kFile, "'x' = \"mm\"", "expected a number in m"});
}

TEST_CASE("scene input: an unknown choice lists the choices") {
  CHECK(error_of([] {
          doc("[contact]\nmodel = \"lineer\"\n").root().table("contact").choice("model", {"linear", "hertz_mindlin"});
        }) == "scenes/a.toml: key 'contact.model' = \"lineer\": allowed: linear, hertz_mindlin");
  check_names(error_of([] { doc("model = 1").root().choice("model", {"linear"}); }),
              {kFile, "'model' = 1", "one of: linear"});
}

TEST_CASE("scene input: a TOML syntax error names the file, the line and toml11's message on one line") {
  const auto message = error_of([] { doc("a = 1\nb = = 2\n"); });
  CHECK(message.rfind("scenes/a.toml:2: TOML syntax error: ", 0) == 0);
  check_names(message, {"b = = 2"});
  CHECK(message.find('\n') == std::string::npos);
  check_names(error_of([] { doc("a = 1\na = 2\n"); }), {"scenes/a.toml:2:", "already exists", "a = 2"});
}

TEST_CASE("scene input: an unreadable file is a file error naming the file and the reason") {
  CHECK(error_of<mc::IoError>([] { TomlDoc::load("/nonexistent/x.toml"); }) ==
        "cannot read scene file '/nonexistent/x.toml': No such file or directory");
  const auto dir = std::filesystem::temp_directory_path().string();
  check_names(error_of<mc::IoError>([&] { TomlDoc::load(dir); }),
              {"cannot read scene file '" + dir + "'", "directory"});
}

TEST_CASE("scene input: a bad --set names the override and why") {
  const std::string walls = "[[walls]]\nvelocity = 0\n[[walls]]\nvelocity = 0\n[material]\ndensity = 2600\n";
  check_names(error_of([&] { doc(walls, {"walls[5].velocity=1"}); }),
              {kFile, "--set 'walls[5].velocity=1'", "past the end of 'walls'", "has 2 entries"});
  check_names(error_of([&] { doc(walls, {"walls..velocity=1"}); }),
              {kFile, "--set 'walls..velocity=1'", "not a key path"});
  check_names(error_of([&] { doc(walls, {"walls.velocity"}); }), {kFile, "--set 'walls.velocity'", "key=value"});
  check_names(error_of([&] { doc(walls, {"material.density.x=1"}); }), {kFile, "'material.density' is not a table"});
  check_names(error_of([&] { doc(walls, {"material[0].density=1"}); }), {kFile, "'material' is not an array"});
  // An overridden value is validated like any other, and the message says where it came from.
  CHECK(error_of([&] {
          doc(walls, {"material.density=-1"})
              .root()
              .table("material")
              .number("density", Unit::Density, Range::positive());
        }) == "scenes/a.toml: key 'material.density' (from --set) = -1 is out of range: allowed value > 0 kg/m3");
}

TEST_CASE("scene input: fail() reports a check across keys on the key's value") {
  const auto root = doc("lo = 2.0\nhi = 1.0\n").root();
  CHECK(error_of([&] { root.fail("hi", "must exceed lo = 2"); }) ==
        "scenes/a.toml: key 'hi' = 1.0: must exceed lo = 2");
}

TEST_CASE("scene input: unit strings convert to SI exactly") {
  CHECK(number_of("\"30 GPa\"", Unit::Pressure) == 30e9);
  CHECK(number_of("\"250 kPa\"", Unit::Pressure) == 250e3);
  CHECK(number_of("\"2.6 g/cm3\"", Unit::Density) == 2600.0);
  CHECK(number_of("\"2.6 t/m3\"", Unit::Density) == 2600.0);
  CHECK(number_of("\"5 mm/s\"", Unit::Velocity) == 0.005);
  CHECK(number_of("\"0.01 mm/s\"", Unit::Velocity) == 1e-5);
  CHECK(number_of("\"3 mm/min\"", Unit::Velocity) == 0.003 / 60.0);
  CHECK(number_of("\"7 um/s\"", Unit::Velocity) == 7e-6);
  CHECK(number_of("\"1e-7 s\"", Unit::Time) == 1e-7);
  CHECK(number_of("\"2 h\"", Unit::Time) == 7200.0);
  CHECK(number_of("\"1.5 min\"", Unit::Time) == 90.0);
  CHECK(number_of("\"20 us\"", Unit::Time) == 20e-6);
  CHECK(number_of("\"45 deg\"", Unit::Angle) == 45.0 * std::numbers::pi / 180.0);
  CHECK(number_of("\"0.1 /s\"", Unit::Rate) == 0.1);
  CHECK(number_of("\"0.1 1/s\"", Unit::Rate) == 0.1);
  CHECK(number_of("\"1 MN/m\"", Unit::Stiffness) == 1e6);
  CHECK(number_of("\"3 N/mm\"", Unit::Stiffness) == 3000.0);
  CHECK(number_of("\"2 cm\"", Unit::Length) == 0.02);
  CHECK(number_of("\"12 um\"", Unit::Length) == 12e-6);
  CHECK(number_of("\"+4e+2 mm\"", Unit::Length) == 0.4);
  CHECK(number_of("\"500 g\"", Unit::Mass) == 0.5);
  CHECK(number_of("\"2t\"", Unit::Mass) == 2000.0);
  CHECK(number_of("\"1.5 kN\"", Unit::Force) == 1500.0);
  CHECK(number_of("\"1.5 kN m\"", Unit::Moment) == 1500.0);
  CHECK(number_of("\"3 N*m\"", Unit::Energy) == 3.0);
  CHECK(number_of("\"3 mJ\"", Unit::Energy) == 0.003);
  CHECK(number_of("\"9.81 m/s2\"", Unit::Acceleration) == 9.81);
  CHECK(number_of("\"2 kHz\"", Unit::Frequency) == 2000.0);
  CHECK(number_of("\"50 %\"", Unit::None) == 0.5);
  CHECK(number_of("\"1.5e-3 GPa\"", Unit::Pressure) == 1.5e6);
  // Plain TOML numbers are SI, integers included; a unitless string is SI too.
  CHECK(number_of("2600", Unit::Density) == 2600.0);
  CHECK(number_of("2.5e9", Unit::Pressure) == 2.5e9);
  CHECK(number_of("\"0.25\"", Unit::Length) == 0.25);
}

TEST_CASE("scene input: optional keys fall back, present ones are read") {
  const auto root = doc("n = 4\nflag = true\nname = \"mesh.vtk\"\n").root();
  CHECK(root.integer("n", Range::at_least(1), 1) == 4);
  CHECK(root.integer("m", Range::at_least(1), 7) == 7);
  CHECK(root.boolean("flag", false));
  CHECK(root.string("name") == "mesh.vtk");
  CHECK(root.string("other", "x") == "x");
  CHECK(root.number("r", Unit::Length, Range::positive(), 0.5) == 0.5);
  CHECK_FALSE(root.optional_table("none").has_value());
  CHECK(root.tables("none").empty());
}

TEST_CASE("scene input: --set overrides scalars, array-of-table entries and missing keys") {
  const std::string text =
      "# a scene\n\n[material]\ndensity = 2600 # rock\nE = \"30 GPa\"\n[contact]\nmodel = \"linear\"\n"
      "[[walls]]\nvelocity = 0.1\n[[walls]]\nvelocity = 0.0\n";
  const std::vector<std::string> overrides = {"material.density=2.7e3",       "contact.model=hertz_mindlin",
                                              "walls[1].velocity=\"5 mm/s\"", "output.every=100",
                                              "gravity=[0, 0, -9.81]",        "material.E=40 GPa"};
  const auto d = doc(text, overrides);
  const auto check_values = [](const TomlDoc& x) {
    const auto root = x.root();
    const auto material = root.table("material");
    CHECK(material.number("density", Unit::Density, Range::positive()) == 2700.0);
    CHECK(material.number("E", Unit::Pressure, Range::positive()) == 40e9);
    CHECK(root.table("contact").choice("model", {"linear", "hertz_mindlin"}) == "hertz_mindlin");
    const auto walls = root.tables("walls");
    REQUIRE(walls.size() == 2);
    CHECK(walls[0].number("velocity", Unit::Velocity, Range::any()) == 0.1);
    CHECK(walls[1].number("velocity", Unit::Velocity, Range::any()) == 0.005);
    CHECK(root.table("output").integer("every", Range::at_least(1)) == 100);
    CHECK(root.numbers("gravity", Unit::Acceleration, Range::any(), 3) == std::vector<double>{0.0, 0.0, -9.81});
    CHECK_NOTHROW(x.finish_all());
  };
  check_values(d);

  // text() is what goes into the output file: it re-parses to the same values, lists the overrides,
  // keeps the file's comments and prints floats as written.
  check_values(TomlDoc::parse_text(d.text(), "stored"));
  check_names(d.text(), {"walls[1].velocity=\"5 mm/s\"", "# rock", "velocity = 0.1\n"});
  CHECK(d.text().find("0.10000000000000001") == std::string::npos);
  // A float that needs all 17 digits keeps them.
  const auto precise = doc("x = 0.30000000000000004\n", {"y=1"});
  CHECK(TomlDoc::parse_text(precise.text(), "stored").root().number("x", Unit::None, Range::any()) == 0.1 + 0.2);
  // Without overrides the text is the file itself, byte for byte.
  CHECK(doc(text).text() == text);
}

TEST_CASE("scene input: a complete scene read completely passes finish_all") {
  const std::string text =
      "title = \"slab\"\nseed = 7\ngravity = [0, 0, \"-9.81 m/s2\"]\n"
      "[material]\ndensity = \"2.6 g/cm3\"\nE = \"30 GPa\"\npoisson = 0.2\n"
      "[contact]\nmodel = \"hertz_mindlin\"\nfriction = 0.5\n"
      "[damping]\nlocal = \"70 %\"\n"
      "[[walls]]\nvelocity = \"1 mm/s\"\n[[walls]]\nvelocity = 0\nfixed = true\n";
  const auto d = doc(text);
  const auto root = d.root();
  CHECK(root.keys() == std::vector<std::string>{"title", "seed", "gravity", "material", "contact", "damping", "walls"});
  CHECK(root.string("title") == "slab");
  CHECK(root.integer("seed", Range::non_negative()) == 7);
  CHECK(root.numbers("gravity", Unit::Acceleration, Range::any(), 3)[2] == -9.81);
  const auto material = root.table("material");
  CHECK(material.path() == "material");
  CHECK(material.number("density", Unit::Density, Range::positive()) == 2600.0);
  CHECK(material.number("E", Unit::Pressure, Range::positive()) == 30e9);
  CHECK(material.number("poisson", Unit::None, Range::closed(0.0, 0.5)) == 0.2);
  const auto contact = root.table("contact");
  CHECK(contact.choice("model", {"linear", "hertz_mindlin"}) == "hertz_mindlin");
  CHECK(contact.number("friction", Unit::None, Range::non_negative()) == 0.5);
  CHECK(root.table("damping").number("local", Unit::None, Range::open_fraction()) == 0.7);
  const auto walls = root.tables("walls");
  REQUIRE(walls.size() == 2);
  CHECK(walls[1].path() == "walls[1]");
  for (const auto& wall : walls) {
    wall.number("velocity", Unit::Velocity, Range::any());
    wall.boolean("fixed", false);
  }
  CHECK_NOTHROW(d.finish_all());
}

TEST_CASE("scene input: load reads a file, applies overrides and names the file in errors") {
  const auto path = (std::filesystem::temp_directory_path() / "mesocrack_scene_input_test.toml").string();
  std::ofstream(path) << "[material]\ndensity = 2600\n";
  const auto d = TomlDoc::load(path, {"material.density=2.5 g/cm3"});
  CHECK(d.root().table("material").number("density", Unit::Density, Range::positive()) == 2500.0);
  check_names(error_of([&] { d.root().table("material").number("E", Unit::Pressure, Range::positive()); }),
              {path + ": missing key 'material.E'"});
  std::remove(path.c_str());
}
