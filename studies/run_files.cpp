#include "studies/run_files.hpp"

#include <filesystem>

#include "engine/errors.hpp"
#include "io/h5_file.hpp"
#include "io/run_output.hpp"
#include "scene/toml_reader.hpp"

namespace mc {

namespace {

// What a file that is not a regular one is, in a message.
std::string kind_of(std::filesystem::file_type t) {
  using T = std::filesystem::file_type;
  switch (t) {
    case T::directory: return "a folder";
    case T::character: return "a character device";
    case T::block: return "a block device";
    case T::fifo: return "a fifo";
    case T::socket: return "a socket";
    default: return "not a regular file";
  }
}

// A run writes <output>.partial and renames it over <output> (run_output.hpp): only a regular file may be replaced
// so; a rename over /dev/null as root turns the device into a file for every other program.
void refuse_special_output(const std::string& out) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status target = fs::status(out, ec);  // through links: a link to a device is the device
  if (fs::exists(target) && !fs::is_regular_file(target))
    throw IoError("output file " + out + " exists and is " + kind_of(target.type()) +
                  ": a run replaces only a regular file (it writes beside it and renames over it); name a regular "
                  "file or a new one");
  const fs::path folder = fs::path(out).parent_path();
  if (!folder.empty() && !fs::is_directory(folder, ec))
    throw IoError("output file " + out + ": its folder " + folder.string() + " does not exist; create it first");
}
}  // namespace

void refuse_unsafe_outputs(const Scene& scene, const std::vector<std::string>& outputs) {
  for (const auto& out : outputs) refuse_special_output(out);
  std::vector<std::pair<std::string, std::string>> inputs{{scene.file, "the scene file"}};
  const auto kind = scene.specimen.kind;
  if (kind == SpecimenSpec::Kind::SphereList || kind == SpecimenSpec::Kind::Output)
    inputs.push_back({scene.specimen.file, "the specimen file the scene loads (specimen.file)"});
  for (const auto& out : outputs)
    for (const auto& [in, what] : inputs) {
      std::error_code ec;  // false, not an error, when either file does not exist
      if (std::filesystem::equivalent(out, in, ec))
        throw InputError("output file " + out + " is " + in + ", " + what +
                         ": the run would overwrite its own input; name another output file");
    }
}

Scene stored_scene(const std::string& output, const std::vector<std::string>& overrides) {
  const std::string text = RunOutput::stored_scene(output);
  const std::string file = H5File(output, H5File::Mode::ReadOnly).attr_string("/", "scene_file");
  try {
    return read_scene(TomlDoc::parse_text(text, output + ":/scene", overrides), file);
  } catch (const InputError& e) {
    throw InputError(std::string(e.what()) + " (the scene " + output + " stores, first read from " + file + ")");
  }
}

std::vector<std::string> run_files(const std::string& output) { return RunOutput::files_written(output); }


}  // namespace mc
