#include "scene/resume_check.hpp"

#include <array>
#include <map>
#include <utility>

#include "scene/toml_reader.hpp"

namespace mc {

namespace {

// Key paths (and the paths under them) that a resume may change: when to end, what to stop on, how often to
// write, and what `summary` and `report` derive afterwards. None of them is part of the simulated state.
constexpr std::array kMayChange = {"title",
                                   "run.steps",
                                   "run.duration",
                                   "run.stop",
                                   "output.history_every",
                                   "output.frame_every",
                                   "output.frames",
                                   "output.checkpoint_every",
                                   "output.guard_every",
                                   "output.xy_plots",
                                   "summary"};

bool under(const std::string& path, const std::string& key) {
  return path.compare(0, key.size(), key) == 0 &&
         (path.size() == key.size() || path[key.size()] == '.' || path[key.size()] == '[');
}

bool may_change(const std::string& path) {
  for (const char* k : kMayChange)
    if (under(path, k)) return true;
  return false;
}

std::map<std::string, TomlLeaf> leaves_of(const std::string& text, const std::string& name) {
  std::map<std::string, TomlLeaf> m;
  for (auto& leaf : TomlDoc::parse_text(text, name).leaves()) m.emplace(leaf.path, std::move(leaf));
  return m;
}

}  // namespace

std::string keys_a_resume_may_change() {
  std::string list;
  for (const char* k : kMayChange) list += (list.empty() ? "" : ", ") + std::string(k);
  return list;
}

SceneChange compare_for_resume(const std::string& stored, const std::string& now) {
  const auto before = leaves_of(stored, "the scene stored in the output file");
  const auto after = leaves_of(now, "the scene");
  SceneChange c;
  for (const auto& [path, was] : before) {
    const auto it = after.find(path);
    const bool same = it != after.end() && it->second.exact == was.exact;
    if (!same && under(path, "run.stop")) c.stops_changed = true;
    if (same || may_change(path) || !c.refused.empty()) continue;
    c.refused = it == after.end() ? "key '" + path + "' (" + was.shown + ") is gone"
                                  : "key '" + path + "' was " + was.shown + ", now " + it->second.shown;
  }
  for (const auto& [path, is] : after) {
    if (before.count(path)) continue;
    if (under(path, "run.stop")) c.stops_changed = true;
    if (!may_change(path) && c.refused.empty()) c.refused = "key '" + path + "' = " + is.shown + " is new";
  }
  return c;
}

}  // namespace mc
