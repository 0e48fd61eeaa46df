// What a resumed run may change in its scene. The checkpoint holds the state of the scene as first run; a
// resume with a different specimen, model or set of histories would continue that state under other rules and
// leave histories of unequal length, so only the run's end, its stop conditions, the output cadences and the
// summaries may change.
#pragma once
#include <string>

namespace mc {

struct SceneChange {
  std::string refused;         // "" when every change is one a resume may make; else the first other, key named
  bool stops_changed = false;  // the [[run.stop]] conditions differ: what they remembered no longer applies
};

// stored: the scene text kept in the output file; now: the scene text of the resuming command.
SceneChange compare_for_resume(const std::string& stored, const std::string& now);

// The keys a resume may change, for messages and the README.
std::string keys_a_resume_may_change();

}  // namespace mc
