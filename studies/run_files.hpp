// The files of a run: the scene an output file stores, the files a run writes beside it, and the refusal of outputs
// that would replace an input or a special file.
#pragma once
#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace mc {

// The scene an output file stores (as it was run, with its --set overrides), with `overrides` applied on top; its
// paths resolve from the folder of the scene file it was read from. IoError when the file is not a run's output.
Scene stored_scene(const std::string& output, const std::vector<std::string>& overrides);

// Before anything runs: InputError, naming both, when one of `outputs` is the same file (by file-system identity,
// whatever the spelling of its path) as an input of the scene: the scene file or the specimen file it loads (also
// when --set names it); IoError when one exists and is not a regular file (a device, a fifo, a socket, a folder, or a
// link to one), which the rename of its partial file over it would replace, or when its folder does not exist.
void refuse_unsafe_outputs(const Scene& scene, const std::vector<std::string>& outputs);
// The files a run writing `output` creates or replaces (the file, its sidecars, temporaries).
std::vector<std::string> run_files(const std::string& output);

}  // namespace mc
