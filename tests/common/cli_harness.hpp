// Running the real `mesocrack` command (MESOCRACK_CLI) from tests: a private temp folder per test, the command
// as a child process (fork/execve) with stdout and stderr captured to files, a small JSON reader for `summary`,
// and checks shared by the command-line tests (same run bit for bit, refused input, no repeated rows).
// Test-only: everything has internal linkage in each test file that includes it.
#pragma once
#include <doctest/doctest.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "io/h5_file.hpp"
#include "tests/common/temp_dir.hpp"

extern char** environ;

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

const std::string kCli = MESOCRACK_CLI;
const fs::path kScenes = fs::path(MESOCRACK_SOURCE_DIR) / "scenes";

// ---------------------------------------------------------------- files and folders

using mc::test::TempDir;  // captured stdout and stderr go to its .io subfolder (Child makes it)

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_file(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
  REQUIRE_MESSAGE(out.good(), "cannot write ", p.string());
}

// `text` with its single occurrence of `what` replaced (a test scene edit that silently missed would test nothing).
std::string edit(const std::string& text, const std::string& what, const std::string& with) {
  const auto at = text.find(what);
  REQUIRE_MESSAGE(at != std::string::npos, "scene text lacks '", what, "'");
  REQUIRE_MESSAGE(text.find(what, at + 1) == std::string::npos, "scene text has '", what, "' more than once");
  return text.substr(0, at) + with + text.substr(at + what.size());
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// Files directly in a folder (not its subfolders), sorted.
std::vector<std::string> files_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file()) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// The scenes of scenes/ this build can run, sorted: a rigid-cell scene ([rigid_cell]) only when the family is built.
std::vector<fs::path> runnable_scenes() {
  std::vector<fs::path> scenes;
  for (const auto& e : fs::directory_iterator(kScenes))
    if (e.path().extension() == ".toml" && (MESOCRACK_RIGID_CELL_BUILT || !contains(slurp(e.path()), "\n[rigid_cell]")))
      scenes.push_back(e.path());
  std::sort(scenes.begin(), scenes.end());
  return scenes;
}

// What kinds of state a scene's run carries: its keys (section.key, arrays of tables merged), with the values of
// the keys that choose a model, a specimen or a motion. Scenes alike in this (the same test on another material)
// checkpoint the same kinds of state.
std::string state_signature(const fs::path& scene) {
  std::vector<std::string> keys;
  std::string section;
  std::istringstream in(slurp(scene));
  for (std::string line; std::getline(in, line);) {
    line = line.substr(0, line.find('#'));
    line.erase(0, line.find_first_not_of(" \t"));
    line.erase(line.find_last_not_of(" \t\r") + 1);
    if (line.empty()) continue;
    if (line.front() == '[') {
      section = line.substr(line.find_first_not_of('['), line.find(']') - line.find_first_not_of('['));
      continue;
    }
    const auto eq = line.find('=');
    if (eq == std::string::npos) continue;
    std::string key = line.substr(0, line.find_first_of(" =")), value = line.substr(eq + 1);
    value.erase(0, value.find_first_not_of(' '));
    const bool chooses =
        key == "model" || key == "kind" || key == "motion" || key == "control" || key == "dimension" || key == "energy";
    keys.push_back(section + "." + key + (chooses ? "=" + value : ""));
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  std::string sig;
  for (const auto& k : keys) sig += k + "\n";
  return sig;
}

// Of the runnable scenes, the first (by name) of each state signature.
std::vector<fs::path> scenes_one_per_kind_of_state() {
  std::vector<fs::path> picked;
  std::vector<std::string> seen;
  for (const auto& s : runnable_scenes()) {
    const std::string sig = state_signature(s);
    if (std::find(seen.begin(), seen.end(), sig) != seen.end()) continue;
    seen.push_back(sig);
    picked.push_back(s);
  }
  return picked;
}

// ---------------------------------------------------------------- the command as a child process

struct Result {
  int code = -1000;  // exit status, or minus the signal that ended it
  std::string out, err;
  double seconds = 0;
  std::string describe() const {
    return "exit " + std::to_string(code) + ", stderr: " + err + ", stdout: " + out.substr(0, 2000);
  }
};

class Child {
 public:
  // Starts `mesocrack args...` in `cwd`. extra_env: "NAME=value" entries added to the environment; launcher: a
  // command that starts mesocrack (mpirun -np 2), its full path first; program: another program than mesocrack.
  Child(const std::vector<std::string>& args, const fs::path& cwd, const std::vector<std::string>& extra_env = {},
        const std::vector<std::string>& launcher = {}, const std::string& program = kCli) {
    static int serial = 0;
    const fs::path io = cwd / ".io";
    fs::create_directories(io);
    out_ = io / ("out" + std::to_string(serial));
    err_ = io / ("err" + std::to_string(serial++));
    // Everything the child needs is prepared before fork: after it, only async-signal-safe calls.
    std::vector<std::string> argv_s = launcher;
    argv_s.push_back(program);
    argv_s.insert(argv_s.end(), args.begin(), args.end());
    std::vector<std::string> env_s;
    for (char** e = environ; *e; ++e) {
      const std::string kv = *e;
      bool replaced = false;
      for (const auto& x : extra_env) replaced |= kv.substr(0, kv.find('=') + 1) == x.substr(0, x.find('=') + 1);
      if (!replaced) env_s.push_back(kv);
    }
    env_s.insert(env_s.end(), extra_env.begin(), extra_env.end());
    std::vector<char*> argv, envp;
    for (auto& a : argv_s) argv.push_back(a.data());
    argv.push_back(nullptr);
    for (auto& e : env_s) envp.push_back(e.data());
    envp.push_back(nullptr);
    const std::string dir = cwd.string(), out = out_.string(), err = err_.string();
    start_ = Clock::now();
    pid_ = fork();
    REQUIRE_MESSAGE(pid_ >= 0, "fork failed: ", std::strerror(errno));
    if (pid_ == 0) {
      const int o = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      const int e = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      const int in = open("/dev/null", O_RDONLY);
      if (o < 0 || e < 0 || in < 0 || chdir(dir.c_str()) != 0) _exit(126);
      dup2(in, 0), dup2(o, 1), dup2(e, 2);
      execve(argv[0], argv.data(), envp.data());
      _exit(127);
    }
  }
  ~Child() {
    if (pid_ > 0) {  // a test that failed before waiting: do not leave the run behind
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;

  pid_t pid() const { return pid_; }
  // True once the child has ended (then wait() returns at once).
  bool ended() {
    if (pid_ <= 0) return true;
    int st = 0;
    const pid_t r = waitpid(pid_, &st, WNOHANG);
    if (r == pid_) reap(st);
    return pid_ <= 0;
  }
  void kill_now() { send(SIGKILL); }
  void send(int sig) {
    if (pid_ > 0) kill(pid_, sig);
  }
  // Waits for the end (killing the child after `limit`, which fails the test).
  Result wait(std::chrono::seconds limit = std::chrono::seconds(180)) {
    while (!ended()) {
      if (Clock::now() - start_ > limit) {
        FAIL_CHECK("mesocrack did not end within ", limit.count(), " s; killed");
        kill_now();
        int st = 0;
        waitpid(pid_, &st, 0);
        reap(st);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    result_.out = slurp(out_);
    result_.err = slurp(err_);
    return result_;
  }

 private:
  void reap(int st) {
    result_.code = WIFEXITED(st) ? WEXITSTATUS(st) : WIFSIGNALED(st) ? -WTERMSIG(st) : -1000;
    result_.seconds = std::chrono::duration<double>(Clock::now() - start_).count();
    pid_ = -1;
  }
  pid_t pid_ = -1;
  fs::path out_, err_;
  Clock::time_point start_;
  Result result_;
};

Result mesocrack(const std::vector<std::string>& args, const fs::path& cwd, const std::vector<std::string>& env = {}) {
  return Child(args, cwd, env).wait();
}

// ---------------------------------------------------------------- a minimal JSON reader (for `summary`)

struct Json {
  enum class Kind { Null, Bool, Number, String, Array, Object } kind = Kind::Null;
  bool boolean = false;
  double number = 0;
  std::string text;  // a string's value, or a number exactly as printed
  std::vector<Json> items;
  std::vector<std::pair<std::string, Json>> members;  // in file order

  bool has(const std::string& key) const {
    return std::any_of(members.begin(), members.end(), [&](const auto& m) { return m.first == key; });
  }
  const Json& operator[](const std::string& key) const {
    for (const auto& m : members)
      if (m.first == key) return m.second;
    throw std::runtime_error("JSON object has no member '" + key + "'");
  }
};

class JsonParser {
 public:
  explicit JsonParser(const std::string& s) : s_(s) {}
  Json parse() {
    Json v = value();
    space();
    if (i_ != s_.size()) fail("trailing characters");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("invalid JSON at offset " + std::to_string(i_) + ": " + what);
  }
  void space() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  bool eat(char c) {
    space();
    if (i_ < s_.size() && s_[i_] == c) return ++i_, true;
    return false;
  }
  void expect(char c) {
    if (!eat(c)) fail(std::string("expected '") + c + "'");
  }
  bool word(const std::string& w) {
    if (s_.compare(i_, w.size(), w) != 0) return false;
    i_ += w.size();
    return true;
  }
  std::string string() {
    expect('"');
    std::string o;
    while (true) {
      if (i_ >= s_.size()) fail("unterminated string");
      const char c = s_[i_++];
      if (c == '"') return o;
      if (static_cast<unsigned char>(c) < 0x20) fail("control character in a string");
      if (c != '\\') {
        o += c;
        continue;
      }
      if (i_ >= s_.size()) fail("unterminated escape");
      const char e = s_[i_++];
      switch (e) {
        case '"':
        case '\\':
        case '/': o += e; break;
        case 'n': o += '\n'; break;
        case 't': o += '\t'; break;
        case 'r': o += '\r'; break;
        case 'b': o += '\b'; break;
        case 'f': o += '\f'; break;
        case 'u':
          if (i_ + 4 > s_.size()) fail("short \\u escape");
          o += '?', i_ += 4;
          break;
        default: fail("bad escape");
      }
    }
  }
  Json value() {
    space();
    if (i_ >= s_.size()) fail("unexpected end");
    Json v;
    const char c = s_[i_];
    if (c == '{') {
      v.kind = Json::Kind::Object;
      ++i_;
      if (eat('}')) return v;
      do {
        space();
        std::string k = string();
        expect(':');
        v.members.emplace_back(std::move(k), value());
      } while (eat(','));
      expect('}');
    } else if (c == '[') {
      v.kind = Json::Kind::Array;
      ++i_;
      if (eat(']')) return v;
      do v.items.push_back(value());
      while (eat(','));
      expect(']');
    } else if (c == '"') {
      v.kind = Json::Kind::String;
      v.text = string();
    } else if (word("null")) {
      v.kind = Json::Kind::Null;
    } else if (word("true") || word("false")) {
      v.kind = Json::Kind::Bool;
      v.boolean = s_[i_ - 1] == 'e' && s_[i_ - 2] == 'u';
    } else {
      static const std::string number_chars = "+-0123456789.eE";
      const std::size_t from = i_;
      while (i_ < s_.size() && number_chars.find(s_[i_]) != std::string::npos) ++i_;
      v.kind = Json::Kind::Number;
      v.text = s_.substr(from, i_ - from);
      char* end = nullptr;
      v.number = std::strtod(v.text.c_str(), &end);
      if (v.text.empty() || end != v.text.c_str() + v.text.size()) fail("bad value '" + v.text + "'");
    }
    return v;
  }
  const std::string& s_;
  std::size_t i_ = 0;
};

Json parse_json(const std::string& s) { return JsonParser(s).parse(); }

// A number as `summary` prints it ("%.10g"; non-finite as null).
std::string json_number(double x) {
  if (!std::isfinite(x)) return "null";
  char b[32];
  std::snprintf(b, sizeof b, "%.10g", x);
  return b;
}

// `mesocrack summary FILE` in `cwd`, parsed; fails the test when it does not exit 0 with valid JSON.
Json summary_of(const std::string& file, const fs::path& cwd) {
  const Result r = mesocrack({"summary", file}, cwd);
  REQUIRE_MESSAGE(r.code == 0, "summary ", file, ": ", r.describe());
  try {
    return parse_json(r.out);
  } catch (const std::exception& e) {
    FAIL("summary ", file, " printed invalid JSON (", e.what(), "):\n", r.out);
  }
  return {};
}

// ---------------------------------------------------------------- output files

std::vector<std::string> history_names(const mc::H5File& f) { return f.list("/history"); }

// Equal bit for bit (NaN equals NaN, 0 differs from -0).
bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

// Index of the first differing value (for messages), or -1.
long first_difference(const std::vector<double>& a, const std::vector<double>& b) {
  for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k)
    if (std::memcmp(&a[k], &b[k], sizeof(double)) != 0) return static_cast<long>(k);
  return a.size() == b.size() ? -1 : static_cast<long>(std::min(a.size(), b.size()));
}

// The steps of the history rows and of the frames rise strictly: nothing is written twice.
void check_no_repeated_rows(const fs::path& file) {
  CAPTURE(file.string());
  const mc::H5File f(file.string(), mc::H5File::Mode::ReadOnly);
  const auto hs = f.read_doubles("/history/step");
  const auto fsteps = f.read_ints("/frames/step");
  CHECK(hs.size() >= 2);
  CHECK(fsteps.size() >= 2);
  for (std::size_t k = 1; k < hs.size(); ++k)
    CHECK_MESSAGE(hs[k] > hs[k - 1], "history row ", k, " repeats step ", hs[k]);
  for (std::size_t k = 1; k < fsteps.size(); ++k)
    CHECK_MESSAGE(fsteps[k] > fsteps[k - 1], "frame ", k, " repeats step ", fsteps[k]);
}

// Two output files hold the same run bit for bit: status, every history series, every frame (the last frame,
// the final state, named separately in the messages).
void check_same_run(const fs::path& a, const fs::path& b) {
  CAPTURE(a.string());
  CAPTURE(b.string());
  const mc::H5File fa(a.string(), mc::H5File::Mode::ReadOnly);
  const mc::H5File fb(b.string(), mc::H5File::Mode::ReadOnly);
  CHECK(fb.attr_string("/", "status") == fa.attr_string("/", "status"));
  CHECK(fb.attr_string("/", "status_message") == fa.attr_string("/", "status_message"));
  CHECK(fb.attr_string("/history", "order") == fa.attr_string("/history", "order"));
  const auto names = history_names(fa);
  REQUIRE(names == history_names(fb));
  REQUIRE(names.size() >= 4);
  for (const auto& n : names) {
    const auto ya = fa.read_doubles("/history/" + n), yb = fb.read_doubles("/history/" + n);
    CHECK_MESSAGE(same_bits(ya, yb), "/history/", n, ": ", ya.size(), " vs ", yb.size(),
                  " rows, first difference at row ", first_difference(ya, yb));
  }
  CHECK(fa.read_ints("/frames/step") == fb.read_ints("/frames/step"));
  // Every table of the frames: time, x, v, force, and a specimen of cells' corners and damage.
  REQUIRE(fa.list("/frames") == fb.list("/frames"));
  for (const auto& name : fa.list("/frames")) {
    const std::string ds = "/frames/" + name;
    std::vector<hsize_t> da, db;
    const auto xa = fa.read_doubles(ds, &da), xb = fb.read_doubles(ds, &db);
    CHECK_MESSAGE(da == db, ds);
    CHECK_MESSAGE(same_bits(xa, xb), ds, ": first difference at value ", first_difference(xa, xb));
  }
  // The frames' contacts, every table.
  REQUIRE(fa.exists("/contacts") == fb.exists("/contacts"));
  if (fa.exists("/contacts")) {
    REQUIRE(fa.list("/contacts") == fb.list("/contacts"));
    for (const auto& name : fa.list("/contacts")) {
      const std::string ds = "/contacts/" + name;
      std::vector<hsize_t> da, db;
      const auto xa = fa.read_doubles(ds, &da), xb = fb.read_doubles(ds, &db);
      CHECK_MESSAGE(da == db, ds);
      CHECK_MESSAGE(same_bits(xa, xb), ds, ": first difference at value ", first_difference(xa, xb));
    }
  }
  // The last frame: the final positions.
  std::vector<hsize_t> dims;
  const auto xa = fa.read_doubles("/frames/x", &dims);
  const auto xb = fb.read_doubles("/frames/x");
  REQUIRE(dims.size() == 2);
  REQUIRE(xa.size() >= dims[1]);
  REQUIRE(xb.size() >= dims[1]);
  const std::vector<double> last_a(xa.end() - static_cast<std::ptrdiff_t>(dims[1]), xa.end());
  const std::vector<double> last_b(xb.end() - static_cast<std::ptrdiff_t>(dims[1]), xb.end());
  CHECK_MESSAGE(same_bits(last_a, last_b), "final positions differ at value ", first_difference(last_a, last_b));
  // The crack log, when there is one.
  REQUIRE(fa.exists("/cracks") == fb.exists("/cracks"));
  if (fa.exists("/cracks"))
    for (const auto& n : fa.list("/cracks")) {
      const auto ca = fa.read_doubles("/cracks/" + n), cb = fb.read_doubles("/cracks/" + n);
      CHECK_MESSAGE(same_bits(ca, cb), "/cracks/", n, ": ", ca.size(), " vs ", cb.size(),
                    " values, first difference at ", first_difference(ca, cb));
    }
}

// The error cases below each run against this folder's `scene.toml` and `-o out.h5`, unless told otherwise.
void check_refused(const fs::path& dir, std::vector<std::string> args, int code, const std::vector<std::string>& parts,
                   const std::string& output = "out.h5") {
  args.insert(args.end(), {"-o", output});
  const Result r = mesocrack(args, dir);
  CHECK_MESSAGE(r.code == code, r.describe());
  // One line: "error: <message>\n".
  CHECK_MESSAGE(r.err.rfind("error: ", 0) == 0, r.err);
  CHECK_MESSAGE(std::count(r.err.begin(), r.err.end(), '\n') == 1, r.err);
  CHECK_MESSAGE((!r.err.empty() && r.err.back() == '\n'), r.err);
  for (const auto& part : parts) CHECK_MESSAGE(contains(r.err, part), "stderr '", r.err, "' lacks '", part, "'");
  CHECK_MESSAGE(r.out.empty(), r.out);
  // Nothing written: no output file, no sidecars, nothing else in the folder beyond what the test put there.
  const fs::path stem = fs::path(output).replace_extension();
  for (const std::string suffix : {".h5", ".xdmf", "_history.csv", ".xdmf.tmp", "_history.csv.tmp"})
    CHECK_MESSAGE(!fs::exists(dir / (stem.string() + suffix)), (stem.string() + suffix), " was left behind");
  for (const auto& name : files_in(dir))
    CHECK_MESSAGE((name.ends_with(".toml") || name.ends_with(".spheres")), "unexpected file ", name);
}

// An edit of a scene's text (the first `what` becomes `with`) and what its refusal must name.
struct SceneEdit {
  std::string what, with;
  std::vector<std::string> parts;
};

// Each edit of `text`, written as this folder's scene.toml, is refused by `run` with exit 2 naming its parts and
// the file, and writes nothing.
void check_edits_refused(const fs::path& dir, const std::string& text, const std::vector<SceneEdit>& edits) {
  for (const SceneEdit& c : edits) {
    CAPTURE(c.with);
    write_file(dir / "scene.toml", edit(text, c.what, c.with));
    std::vector<std::string> parts = c.parts;
    parts.push_back("scene.toml");
    check_refused(dir, {"run", "scene.toml"}, 2, parts);
  }
}

// 1-based line of the first occurrence of `what` in `text`.
int line_of(const std::string& text, const std::string& what) {
  const auto at = text.find(what);
  REQUIRE(at != std::string::npos);
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
}

}  // namespace
