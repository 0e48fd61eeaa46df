// Opening, creating, abandoning and closing an HDF5 file: the part of H5File that decides what reaches the disk
// when writes fail or the process is killed.
#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <utility>

#include "engine/errors.hpp"
#include "io/h5_detail.hpp"
#include "io/h5_file.hpp"

namespace mc {
namespace {

using namespace h5;

// HDF5 closes the files still open when the process exits, flushing them. An abandoned file must never be flushed
// or closed (H5Fclose of a file whose writes fail leaves HDF5's state half torn down, and the exit-time cleanup then
// crashes), so that cleanup is off: every healthy file is closed by its H5File before the process ends. It must be
// switched off before the library initialises, hence at static initialisation of this file.
[[maybe_unused]] const bool kNoCleanupAtExit = H5dont_atexit() >= 0;

// HDF5 writes dirty metadata whenever its cache evicts, so a writer killed between two flushes can leave
// groups half-updated on disk, losing objects flushed long before. With evictions off, metadata reaches the
// disk only at a flush (or close), and the file keeps the last flushed state. The price: the metadata of the
// objects touched while the file is open stays in memory.
Id crash_safe_writing() {
  Id fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  H5AC_cache_config_t config{};
  config.version = H5AC__CURR_CACHE_CONFIG_VERSION;
  H5Pget_mdc_config(fapl, &config);
  config.evictions_enabled = false;
  config.incr_mode = H5C_incr__off;  // evictions can only be disabled with automatic resizing off
  config.flash_incr_mode = H5C_flash_incr__off;
  config.decr_mode = H5C_decr__off;
  H5Pset_mdc_config(fapl, &config);
  return fapl;
}

// A reader does not take HDF5's file lock: a run's file is open for writing while it runs, and `summary` of it
// would otherwise fail where `report` (h5py, locking off) reads it. What it reads is the last flush's.
Id reading_beside_a_writer() {
  Id fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  H5Pset_file_locking(fapl, false, true);
  return fapl;
}

}  // namespace

H5File::H5File(const std::string& path, Mode mode) : path_(path), writable_(mode != Mode::ReadOnly) {
  quiet_this_thread();
  const Id fapl = mode == Mode::ReadOnly ? reading_beside_a_writer() : crash_safe_writing();
  if (mode == Mode::Create) {
    const std::filesystem::path dir = std::filesystem::path(path).parent_path();
    if (!dir.empty() && !std::filesystem::is_directory(dir))
      throw IoError(path + ": cannot create file: no such directory '" + dir.string() + "'");
    const bool existed = std::filesystem::exists(path);
    file_ = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
    if (file_ < 0) {
      const std::string reason = hdf5_reason();
      if (!existed) std::remove(path.c_str());  // what it created: an empty or torn file
      throw IoError(path + ": cannot create file: " + reason);
    }
    // Until its root group is flushed, a new file is unreadable; a writer killed early leaves an empty file.
    try {
      flush();
    } catch (const IoError& e) {
      if (!existed) std::remove(path.c_str());  // an empty file would pass for a readable one
      const std::string why = e.what(), flushing = path + ": cannot flush file: ";
      throw IoError(path + ": cannot create file: " + (why.starts_with(flushing) ? why.substr(flushing.size()) : why));
    }
    return;
  }
  if (!std::filesystem::exists(path)) throw IoError(path + ": cannot open file: no such file");
  file_ = H5Fopen(path.c_str(), mode == Mode::ReadOnly ? H5F_ACC_RDONLY : H5F_ACC_RDWR, fapl);
  if (file_ < 0) throw IoError(path + ": cannot open file: " + hdf5_reason());
}

H5File::~H5File() { close(); }

void H5File::reopen(Mode mode) {
  fid();  // refuses an abandoned or moved-from file
  close();
  *this = H5File(path_, mode);
}

H5File::H5File(H5File&& other) noexcept
    : path_(std::move(other.path_)),
      file_(std::exchange(other.file_, H5I_INVALID_HID)),
      writable_(other.writable_),
      abandoned_(std::exchange(other.abandoned_, false)) {}

H5File& H5File::operator=(H5File&& other) noexcept {
  if (this != &other) {
    close();
    path_ = std::move(other.path_);
    file_ = std::exchange(other.file_, H5I_INVALID_HID);
    writable_ = other.writable_;
    abandoned_ = std::exchange(other.abandoned_, false);
  }
  return *this;
}

void H5File::close() noexcept {
  if (file_ >= 0 && !abandoned_) H5Fclose(file_);
  file_ = H5I_INVALID_HID;
}

hid_t H5File::fid() const {
  if (file_ < 0) throw IoError(path_ + ": file is not open (the H5File was moved from)");
  if (abandoned_)
    throw IoError(path_ + ": file abandoned after a failed write; it holds what was flushed before the failure");
  quiet_this_thread();
  return file_;
}

// HDF5's descriptor is replaced by one that refuses writes: whatever HDF5 still holds in memory can no longer reach
// the file. The id is never closed (see the header).
void H5File::abandon() noexcept {
  if (file_ < 0 || abandoned_) return;
  abandoned_ = true;
  void* handle = nullptr;
  if (H5Fget_vfd_handle(file_, H5P_DEFAULT, &handle) < 0 || !handle) return;
  const int read_only = open("/dev/null", O_RDONLY | O_CLOEXEC);
  if (read_only < 0) return;
  dup2(read_only, *static_cast<int*>(handle));
  ::close(read_only);
}

void H5File::rename(const std::string& to) {
  fid();
  std::error_code ec;
  std::filesystem::rename(path_, to, ec);
  if (ec) throw IoError(path_ + ": cannot rename to " + to + ": " + ec.message());
  path_ = to;
}

}  // namespace mc
