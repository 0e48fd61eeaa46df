// Mutation fuzzing of the scene reader, shared by the test (tests/robustness/scene_fuzzer.cpp, 10^4 inputs) and
// the benchmark (benchmarks/fuzz_scenes.cpp, 10^6): the shipped scenes as seeds, the mutations, reading one input
// in-process, and the judgement of its outcome. Input k of a run is fully determined by (seed, k), so any input a
// run reports can be rebuilt alone.
//
// The judgement. A crash or a hang is fatal (a signal handler and an alarm name the input, then the process
// dies). Reading ends in one of:
//   accepted  the Scene satisfies the invariants the engine relies on, and its stored text reads again to the same
//             shape (what `--resume` and `summary` do with it);
//   refused   an InputError (or an IoError) whose message places the fault: one line without control characters,
//             at most kMaxMessage
//             characters, starting with the scene's name and a colon, and naming a line (`name:12:`), a key
//             (`key '...'`), an override (`--set '...'`) or a table (`[name]`, `[[name]]`). A user can go from such
//             a message to the text to change; a message without a place, a multi-line one or an essay fails;
//   wrong     any other exception (std::out_of_range, toml::exception, std::bad_alloc, ...), an accepted scene
//             that breaks an invariant, or a message that fails the rule above. A run reports every one of these.
#pragma once
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "engine/errors.hpp"
#include "scene/scene.hpp"
#include "scene/toml_reader.hpp"

namespace mc::fuzz {

// ---------------------------------------------------------------- seeds

struct SeedScene {
  std::string name;  // path below the source folder, e.g. scenes/collision_3d.toml: the name in messages
  std::string text;
};

// Every shipped scene: scenes/ (with its subfolders) and tests/scenes/, sorted by name.
inline std::vector<SeedScene> shipped_scenes(const std::filesystem::path& source_dir) {
  std::vector<SeedScene> seeds;
  for (const char* folder : {"scenes", "tests/scenes"})
    for (const auto& e : std::filesystem::recursive_directory_iterator(source_dir / folder)) {
      if (!e.is_regular_file() || e.path().extension() != ".toml") continue;
      std::ifstream in(e.path(), std::ios::binary);
      std::ostringstream text;
      text << in.rdbuf();
      seeds.push_back({std::filesystem::relative(e.path(), source_dir).string(), text.str()});
    }
  std::sort(seeds.begin(), seeds.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  return seeds;
}

// ---------------------------------------------------------------- mutations

// One mutated input: a seed's text changed by 1 to 4 mutations, perhaps with --set overrides.
struct Mutant {
  std::size_t seed_index = 0;
  std::string text;
  std::vector<std::string> overrides;
  std::vector<std::string> mutations;  // their names, in order, for reports
};

// Values of every TOML type and of the extremes, written as a user (or a slip of the keyboard) would.
inline const std::vector<std::string>& extreme_values() {
  static const std::vector<std::string> v = {"1e308",
                                             "-1e308",
                                             "1.7976931348623157e308",
                                             "4.9e-324",
                                             "1e-320",
                                             "-0",
                                             "-0.0",
                                             "0",
                                             "0.0",
                                             "nan",
                                             "+nan",
                                             "-nan",
                                             "inf",
                                             "+inf",
                                             "-inf",
                                             "1",
                                             "-1",
                                             "2",
                                             "3",
                                             "1000000",
                                             "9223372036854775807",
                                             "-9223372036854775808",
                                             "9223372036854775808",
                                             "0x7fffffff",
                                             "1e15",
                                             "1e16",
                                             "99999999999999999999",
                                             "2.5",
                                             "\"1e308 GPa\"",
                                             "\"nan mm\"",
                                             "\"-0 s\"",
                                             "\"1e999 m\"",
                                             "\"inf kg/m3\"",
                                             "\"-1e-400 m/s\"",
                                             "\"0 mm\"",
                                             "\"9223372036854775807\"",
                                             "\"5\"",
                                             "\"\"",
                                             "\" \"",
                                             "\"abc\"",
                                             "true",
                                             "false",
                                             "1979-05-27",
                                             "1979-05-27T07:32:00Z",
                                             "07:32:00",
                                             "[]",
                                             "[1, 2, 3]",
                                             "[\"a\", 1]",
                                             "[[1], [2]]",
                                             "{}",
                                             "{a = 1}",
                                             "[{}]",
                                             "[0, 0, 0]",
                                             "[1e308, -1e308, nan]"};
  return v;
}

// Units of every kind, and some no kind has, for "5 mm" -> "5 MPa".
inline const std::vector<std::string>& unit_names() {
  static const std::vector<std::string> u = {
      "m",    "mm",     "um",   "s",    "ms",   "us",   "min",     "h",     "kg",    "g",        "t",
      "N",    "kN",     "N*m",  "kN m", "Pa",   "kPa",  "MPa",     "GPa",   "kg/m3", "g/cm3",    "m/s",
      "mm/s", "mm/min", "m/s2", "N/m",  "kN/m", "N/mm", "J",       "mJ",    "rad",   "deg",      "1/s",
      "/s",   "Hz",     "kHz",  "%",    "J/m2", "",     "parsecs", "MPa/s", "mm mm", "\\u00b5m", "m\\n"};
  return u;
}

class Mutator {
 public:
  // Input k of the run with this seed, from the seeds given; the same (seed, k) always gives the same input.
  Mutator(std::uint64_t seed, std::uint64_t k) : rng_(mix(seed, k)) {}

  Mutant mutate(const std::vector<SeedScene>& seeds) {
    Mutant m;
    m.seed_index = pick(seeds.size());
    m.text = seeds[m.seed_index].text;
    const std::size_t n = 1 + pick(4);
    for (std::size_t i = 0; i < n; ++i) apply_one(m);
    return m;
  }

 private:
  static std::uint64_t mix(std::uint64_t seed, std::uint64_t k) {  // splitmix64 of the pair
    std::uint64_t z = seed * 0x9E3779B97F4A7C15ULL + k + 0x632BE59BD9B4E5ULL;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  std::size_t pick(std::size_t n) { return n == 0 ? 0 : std::uniform_int_distribution<std::size_t>(0, n - 1)(rng_); }
  bool chance(double p) { return std::uniform_real_distribution<double>(0, 1)(rng_) < p; }
  template <class T>
  const T& any(const std::vector<T>& v) {
    return v[pick(v.size())];
  }

  void apply_one(Mutant& m) {
    using Step = void (Mutator::*)(Mutant&);
    static const std::array<std::pair<const char*, Step>, 12> kinds = {{
        {"delete_line", &Mutator::delete_line},
        {"duplicate_line", &Mutator::duplicate_line},
        {"swap_lines", &Mutator::swap_lines},
        {"type_swap", &Mutator::type_swap},
        {"unit_swap", &Mutator::unit_swap},
        {"extreme_number", &Mutator::extreme_number},
        {"dimension_flip", &Mutator::dimension_flip},
        {"deep_nesting", &Mutator::deep_nesting},
        {"garbage_bytes", &Mutator::garbage_bytes},
        {"truncate", &Mutator::truncate},
        {"override", &Mutator::add_override},
        {"duplicate_section", &Mutator::duplicate_section},
    }};
    const auto& [name, step] = kinds[pick(kinds.size())];
    m.mutations.push_back(name);
    (this->*step)(m);
  }

  // ---- lines

  static std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    return lines;
  }
  static std::string joined(const std::vector<std::string>& lines) {
    std::string out;
    for (const auto& l : lines) out += l + "\n";
    return out;
  }
  // Indices of "key = value" lines (not headers, comments or blank lines).
  static std::vector<std::size_t> value_lines(const std::vector<std::string>& lines) {
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      const auto first = lines[i].find_first_not_of(" \t");
      if (first == std::string::npos || lines[i][first] == '#' || lines[i][first] == '[') continue;
      if (lines[i].find('=') != std::string::npos) out.push_back(i);
    }
    return out;
  }
  // A "key = value" line with its value replaced.
  static std::string with_value(const std::string& line, const std::string& value) {
    return line.substr(0, line.find('=') + 1) + " " + value;
  }
  static std::string value_of(const std::string& line) {
    std::string v = line.substr(line.find('=') + 1);
    if (const auto hash = v.find(" #"); hash != std::string::npos) v.resize(hash);
    const auto b = v.find_first_not_of(" \t");
    return b == std::string::npos ? "" : v.substr(b, v.find_last_not_of(" \t") - b + 1);
  }

  void delete_line(Mutant& m) {
    auto lines = lines_of(m.text);
    if (lines.empty()) return;
    lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(pick(lines.size())));
    m.text = joined(lines);
  }

  void duplicate_line(Mutant& m) {
    auto lines = lines_of(m.text);
    if (lines.empty()) return;
    const std::string line = lines[pick(lines.size())];
    lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(pick(lines.size() + 1)), line);
    m.text = joined(lines);
  }

  void swap_lines(Mutant& m) {
    auto lines = lines_of(m.text);
    if (lines.size() < 2) return;
    std::swap(lines[pick(lines.size())], lines[pick(lines.size())]);
    m.text = joined(lines);
  }

  // A whole [section] or [[section]] written twice: duplicate tables, phases, contacts, walls.
  void duplicate_section(Mutant& m) {
    const auto lines = lines_of(m.text);
    std::vector<std::size_t> headers;
    for (std::size_t i = 0; i < lines.size(); ++i)
      if (lines[i].rfind("[", 0) == 0) headers.push_back(i);
    if (headers.empty()) return;
    const std::size_t h = pick(headers.size());
    const std::size_t end = h + 1 < headers.size() ? headers[h + 1] : lines.size();
    auto out = lines;
    out.insert(out.end(), lines.begin() + static_cast<std::ptrdiff_t>(headers[h]),
               lines.begin() + static_cast<std::ptrdiff_t>(end));
    m.text = joined(out);
  }

  // ---- values

  // number <-> string <-> array <-> table <-> boolean, or the value wrapped in another type.
  void type_swap(Mutant& m) {
    auto lines = lines_of(m.text);
    const auto candidates = value_lines(lines);
    if (candidates.empty()) return;
    std::string& line = lines[any(candidates)];
    const std::string v = value_of(line);
    std::string quoted_v;
    for (const char c : v) quoted_v += c == '"' || c == '\\' ? std::string("\\") + c : std::string(1, c);
    const std::vector<std::string> swaps = {"\"" + quoted_v + "\"",
                                            "[" + v + "]",
                                            "{x = " + v + "}",
                                            "[" + v + ", " + v + "]",
                                            "42",
                                            "-2.5",
                                            "\"text\"",
                                            "true",
                                            "[]",
                                            "{}",
                                            "[{a = 1}]"};
    line = with_value(line, any(swaps));
    m.text = joined(lines);
  }

  // "5 mm" -> "5 MPa": a unit of another kind, or none, or one no kind has.
  void unit_swap(Mutant& m) {
    std::vector<std::size_t> at;  // positions of '"<number> <unit>"' strings: after a digit and a space
    for (std::size_t i = 1; i + 1 < m.text.size(); ++i)
      if (m.text[i] == ' ' && std::isdigit(static_cast<unsigned char>(m.text[i - 1])) &&
          std::isalpha(static_cast<unsigned char>(m.text[i + 1])))
        at.push_back(i + 1);
    if (at.empty()) return;
    const std::size_t from = any(at);
    const std::size_t to = m.text.find('"', from);
    if (to == std::string::npos) return;
    m.text = m.text.substr(0, from) + any(unit_names()) + m.text.substr(to);
  }

  void extreme_number(Mutant& m) {
    auto lines = lines_of(m.text);
    const auto candidates = value_lines(lines);
    if (candidates.empty()) return;
    std::string& line = lines[any(candidates)];
    line = with_value(line, any(extreme_values()));
    m.text = joined(lines);
  }

  void dimension_flip(Mutant& m) {
    for (const auto& [from, to] :
         {std::pair<std::string, std::string>{"dimension = 3", "dimension = 2"}, {"dimension = 2", "dimension = 3"}})
      if (const auto at = m.text.find(from); at != std::string::npos) {
        m.text.replace(at, from.size(), to);
        return;
      }
  }

  // Arrays, inline tables, dotted keys or a header nested from 1 to 200 deep (rarely 10 000): the limit is 64.
  void deep_nesting(Mutant& m) {
    const std::size_t depth = chance(0.05) ? 10000 : 1 + pick(200);
    auto repeat = [](const std::string& s, std::size_t n) {
      std::string out;
      out.reserve(s.size() * n);
      for (std::size_t i = 0; i < n; ++i) out += s;
      return out;
    };
    std::string deep;
    switch (pick(4)) {
      case 0: deep = "x = " + repeat("[", depth) + "1" + repeat("]", depth); break;
      case 1: deep = "x = " + repeat("{a = ", depth) + "1" + repeat("}", depth); break;
      case 2: deep = "a" + repeat(".a", depth) + " = 1"; break;
      default: deep = "[a" + repeat(".a", depth) + "]\nx = 1"; break;
    }
    auto lines = lines_of(m.text);
    lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(pick(lines.size() + 1)), deep);
    m.text = joined(lines);
  }

  // ---- bytes

  void garbage_bytes(Mutant& m) {
    const std::size_t n = 1 + pick(16);
    const std::size_t at = pick(m.text.size() + 1);
    std::string bytes;
    const std::size_t range = chance(0.5) ? 128 : 256;  // ASCII half the time: past the UTF-8 check, into toml11
    for (std::size_t i = 0; i < n; ++i) bytes += static_cast<char>(pick(range));
    if (chance(0.5))
      m.text.insert(at, bytes);
    else
      m.text.replace(at, std::min(n, m.text.size() - at), bytes);
  }

  void truncate(Mutant& m) { m.text.resize(pick(m.text.size() + 1)); }

  // ---- the command line

  // "--set path=value" for a key the text has (its path from the headers above it), or a broken path.
  void add_override(Mutant& m) {
    const auto lines = lines_of(m.text);
    std::vector<std::string> paths;
    std::string section;
    std::vector<std::pair<std::string, std::size_t>> counts;  // [[name]] headers seen so far
    for (const auto& l : lines) {
      if (l.rfind("[[", 0) == 0 && l.find("]]") != std::string::npos) {
        const std::string name = l.substr(2, l.find("]]") - 2);
        auto it = std::find_if(counts.begin(), counts.end(), [&](const auto& c) { return c.first == name; });
        if (it == counts.end()) it = counts.insert(counts.end(), {name, 0});
        section = name + "[" + std::to_string(it->second++) + "]";
      } else if (l.rfind("[", 0) == 0 && l.find(']') != std::string::npos) {
        section = l.substr(1, l.find(']') - 1);
      } else if (const auto eq = l.find('='); eq != std::string::npos && l.rfind("#", 0) != 0) {
        std::string key = l.substr(0, eq);
        key.erase(key.find_last_not_of(" \t") + 1);
        key.erase(0, key.find_first_not_of(" \t"));
        paths.push_back(section.empty() ? key : section + "." + key);
      }
    }
    static const std::vector<std::string> broken = {"a..b", "x[99].y",  "phases[999].density", ".",          "=",
                                                    "run.", "walls[0]", "phases.density",      "a.b.c.d.e.f"};
    const std::string path = paths.empty() || chance(0.15) ? any(broken) : any(paths);
    m.overrides.push_back(path + "=" + (chance(0.3) ? "\"5 mm\"" : any(extreme_values())));
  }

  std::mt19937_64 rng_;
};

// ---------------------------------------------------------------- reading and judging

enum class Outcome { Accepted, Refused, Wrong };

struct Judgement {
  Outcome outcome = Outcome::Wrong;
  std::string detail;  // the error message, or what is wrong
  double seconds = 0;
};

constexpr std::size_t kMaxMessage = 1000;

// "[uniaxial]" or "[[phases]]" in the text: a table named as its header is written.
inline bool names_table(const std::string& text) {
  for (std::size_t at = text.find('['); at != std::string::npos; at = text.find('[', at + 1)) {
    const std::size_t from = text.find_first_not_of('[', at);
    if (from == std::string::npos) return false;
    const std::size_t to = text.find_first_not_of("abcdefghijklmnopqrstuvwxyz_.", from);
    if (to != std::string::npos && to > from && text[to] == ']') return true;
  }
  return false;
}

// The rule for a refusal's message (see the top of this file); "" when it holds, else what breaks it.
inline std::string message_fault(const std::string& message, const std::string& name) {
  if (message.find('\n') != std::string::npos) return "spans several lines";
  if (std::any_of(message.begin(), message.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20; }))
    return "holds a control character";
  if (message.size() > kMaxMessage) return "is longer than " + std::to_string(kMaxMessage) + " characters";
  if (message.rfind(name + ":", 0) != 0) return "does not start with the scene's name '" + name + ":'";
  const std::string rest = message.substr(name.size() + 1);
  const bool line = !rest.empty() && std::isdigit(static_cast<unsigned char>(rest[0])) &&
                    rest.find_first_not_of("0123456789") != std::string::npos &&
                    rest[rest.find_first_not_of("0123456789")] == ':';
  const bool named =
      rest.find("key '") != std::string::npos || rest.find("--set '") != std::string::npos || names_table(rest);
  return line || named ? "" : "names no line, key, override or table";
}

// What an accepted rigid-cell part must be: facet laws between existing phases with positive moduli, a
// positive node distance, finite shape numbers.
template <class PhaseOk>
std::string rigid_cell_fault(const RigidCellSpec& r, PhaseOk phase_ok) {
  if (r.facets.empty()) return "no facet laws";
  for (const auto& f : r.facets) {
    if (!phase_ok(f.phase_a) || !phase_ok(f.phase_b)) return "facet law phase index out of range";
    const bool given = f.E0 > 0 && f.alpha > 0, macroscopic = f.modulus > 0 && f.poisson_ratio > -1 && f.poisson_ratio < 0.5;
    if (!(given || macroscopic)) return "facet law without positive moduli";
    if (!(f.tensile_strength >= 0) || (f.tensile_strength > 0 && !(f.fracture_energy > 0)))
      return "facet law with a strength but no fracture energy";
  }
  const auto& c = r.specimen;
  if (!(std::isfinite(c.l_min) && c.l_min > 0)) return "l_min " + std::to_string(c.l_min);
  for (double x : c.size)
    if (!(std::isfinite(x) && x > 0)) return "box size not positive";
  if (c.shape == CellSpecimenSpec::Shape::Disc && !(std::isfinite(c.radius) && c.radius > 0)) return "disc radius";
  return "";
}

// What an accepted scene must be for the engine: "" when it is, else the first invariant it breaks.
inline std::string scene_fault(const Scene& s) {
  const auto finite = [](const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
  };
  const auto d = static_cast<std::size_t>(s.dimension);
  if (s.dimension != 2 && s.dimension != 3) return "dimension " + std::to_string(s.dimension);
  const auto phase_ok = [&](int i) { return i >= 0 && static_cast<std::size_t>(i) < s.phases.size(); };
  if (s.rigid_cell) {
    if (std::string f = rigid_cell_fault(*s.rigid_cell, phase_ok); !f.empty()) return f;
  } else if (s.contacts.empty()) {
    return "no contacts";
  }
  if (s.phases.empty()) return "no phases";
  for (const auto& p : s.phases)
    if (!(std::isfinite(p.density) && p.density > 0)) return "phase density " + std::to_string(p.density);
  for (const auto& c : s.contacts)
    if (!phase_ok(c.phase_a) || !phase_ok(c.phase_b)) return "contact phase index out of range";
  for (const auto& p : s.specimen.particles) {
    if (p.x.size() != d || p.v.size() != d || !finite(p.x) || !finite(p.v) || !finite(p.w))
      return "particle position or velocity of the wrong size or not finite";
    if (!(std::isfinite(p.radius) && p.radius > 0)) return "particle radius " + std::to_string(p.radius);
    if (!phase_ok(p.phase)) return "particle phase out of range";
  }
  const auto& sp = s.specimen;
  const bool box = !s.rigid_cell && (sp.kind == SpecimenSpec::Kind::RandomBox ||
                                     sp.kind == SpecimenSpec::Kind::Lattice || sp.kind == SpecimenSpec::Kind::Packing);
  if (box) {
    if (sp.box_lo.size() != d || sp.box_hi.size() != d || !finite(sp.box_lo) || !finite(sp.box_hi))
      return "specimen box of the wrong size or not finite";
    for (std::size_t k = 0; k < d; ++k)
      if (!(sp.box_lo[k] < sp.box_hi[k])) return "specimen box with lo >= hi";
    if (!phase_ok(sp.phase)) return "specimen phase out of range";
  }
  if (s.steps < 0 || !(std::isfinite(s.duration) && s.duration >= 0)) return "negative or non-finite run length";
  if (s.steps == 0 && s.duration == 0 && s.stops.empty()) return "a run without an end";
  if (s.history_every < 1) return "history_every < 1";
  for (const auto& w : s.walls)
    if (!finite(w.point) || !finite(w.normal) || !finite(w.velocity)) return "wall vectors not finite";
  return "";
}

// Reads one input in-process (parse, overrides, every key, finish_all) and judges the outcome.
inline Judgement judge(const Mutant& m, const std::string& name) {
  Judgement j;
  const auto t0 = std::chrono::steady_clock::now();
  try {
    const Scene s = read_scene(TomlDoc::parse_text(m.text, name, m.overrides), name);
    j.detail = scene_fault(s);
    // The text stored with a run (the re-serialised scene, with overrides) reads back to the same scene.
    if (j.detail.empty()) {
      const Scene again = read_scene(TomlDoc::parse_text(s.text, name), name);
      if (again.dimension != s.dimension || again.phases.size() != s.phases.size() ||
          again.specimen.particles.size() != s.specimen.particles.size() || again.steps != s.steps ||
          !(again.duration == s.duration))
        j.detail = "its stored text reads back to a different scene";
    }
    j.outcome = j.detail.empty() ? Outcome::Accepted : Outcome::Wrong;
  } catch (const InputError& e) {
    j.detail = e.what();
    const std::string fault = message_fault(j.detail, name);
    j.outcome = fault.empty() ? Outcome::Refused : Outcome::Wrong;
    if (!fault.empty()) j.detail = "message " + fault + ": " + j.detail.substr(0, 300);
  } catch (const IoError& e) {
    j.outcome = Outcome::Refused;
    j.detail = e.what();
  } catch (const std::exception& e) {
    j.detail = std::string("unexpected exception: ") + e.what();
  }
  j.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return j;
}

// ---------------------------------------------------------------- crashes and hangs

// While an input is read, a crash (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT) or an overrun of the time budget
// (SIGALRM) prints which input it was, before the process dies as it would have: the run is then reproduced
// with that seed and index. The handler runs on its own stack, since a stack overflow is the likeliest crash.
class Watchdog {
 public:
  Watchdog(std::uint64_t seed, unsigned budget_seconds) : budget_(budget_seconds) {
    seed_ = seed;
    static std::vector<char> stack(1 << 16);
    stack_t ss{};
    ss.ss_sp = stack.data();
    ss.ss_size = stack.size();
    sigaltstack(&ss, nullptr);
    struct sigaction sa {};
    sa.sa_handler = &Watchdog::on_signal;
    sa.sa_flags = SA_ONSTACK | SA_RESETHAND;
    for (const int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGALRM}) sigaction(sig, &sa, nullptr);
  }
  ~Watchdog() {
    alarm(0);
    for (const int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGALRM}) signal(sig, SIG_DFL);
  }
  Watchdog(const Watchdog&) = delete;
  Watchdog& operator=(const Watchdog&) = delete;

  void start(std::uint64_t k) {
    index_ = k;
    alarm(budget_);
  }
  void stop() { alarm(0); }

 private:
  // Only async-signal-safe calls: write(2) of text put together by hand.
  static void on_signal(int sig) {
    char buf[200];
    std::size_t n = 0;
    const auto put = [&](const char* s) {
      while (*s && n < sizeof buf) buf[n++] = *s++;
    };
    const auto put_number = [&](std::uint64_t x) {
      char digits[24];
      int k = 0;
      do digits[k++] = static_cast<char>('0' + x % 10);
      while ((x /= 10) > 0 && k < 24);
      while (k > 0 && n < sizeof buf) buf[n++] = digits[--k];
    };
    put("\nscene fuzzer: input ");
    put_number(index_);
    put(" of seed ");
    put_number(seed_);
    put(sig == SIGALRM ? " overran its time budget" : " crashed the reader");
    put("; rebuild it with fuzz_scenes --seed ");
    put_number(seed_);
    put(" --only ");
    put_number(index_);
    put("\n");
    (void)!write(2, buf, n);
    if (sig == SIGALRM) _exit(124);
    raise(sig);  // SA_RESETHAND: the default action now, a core dump where configured
  }
  unsigned budget_;
  static inline volatile std::uint64_t index_ = 0, seed_ = 0;
};

}  // namespace mc::fuzz
