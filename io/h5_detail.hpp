// What the HDF5 wrapper's files share (io/h5_file.cpp, io/h5_file_open.cpp): an owning id, HDF5's error text
// made readable, and whether a failure came from HDF5 or the system (the file must then not be flushed again).
// Internal to io/.
#pragma once
#include <hdf5.h>

#include <string>
#include <utility>

#include "engine/errors.hpp"

namespace mc::h5 {

// Owns one HDF5 id and closes it with the matching H5?close.
class Id {
 public:
  Id(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Id() {
    if (id_ >= 0) close_(id_);
  }
  Id(Id&& other) noexcept : id_(std::exchange(other.id_, H5I_INVALID_HID)), close_(other.close_) {}
  Id(const Id&) = delete;
  Id& operator=(const Id&) = delete;
  operator hid_t() const { return id_; }
  bool ok() const { return id_ >= 0; }
  // Closes now, returning HDF5's status: closing a dataset writes its cached chunks, and that write can fail.
  herr_t close() { return id_ >= 0 ? close_(std::exchange(id_, H5I_INVALID_HID)) : 0; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

inline void quiet_this_thread() {
  // The library is built thread-safe, which makes the error-printing switch per thread.
  thread_local bool quiet = false;
  if (!quiet) quiet = H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr) >= 0;
}

// A failed system call as HDF5 reports it ("file write failed: time = …, filename = …, errno = 28, error message =
// 'No space left on device', buf = …") shortened to what it means: "file write failed: No space left on device".
inline std::string shortened(const std::string& desc) {
  const std::string key = "error message = '";
  const auto at = desc.find(key), colon = desc.find(':');
  if (at == std::string::npos || colon == std::string::npos || colon > at) return desc;
  const auto from = at + key.size(), to = desc.find('\'', from);
  return desc.substr(0, colon) + ": " + desc.substr(from, to == std::string::npos ? std::string::npos : to - from);
}

// Set when a call into HDF5 or the system failed (rather than a check of ours, such as a missing dataset or a value
// type that does not match the table): such a failure may leave HDF5's state ahead of the file, which then must not
// be flushed.
inline thread_local bool g_call_failed = false;

// The innermost message of HDF5's error stack: the most specific cause.
inline std::string hdf5_reason() {
  g_call_failed = true;
  std::string reason;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_UPWARD,
      [](unsigned n, const H5E_error2_t* e, void* out) -> herr_t {
        if (n == 0) *static_cast<std::string*>(out) = e->desc;
        return 0;
      },
      &reason);
  return reason.empty() ? "HDF5 error" : shortened(reason);
}

// What every helper needs: the file id, and the file path for messages.
struct File {
  hid_t id;
  const std::string& path;

  [[noreturn]] void fail(const std::string& what, const std::string& obj, const std::string& reason) const {
    throw IoError(path + ": cannot " + what + (obj.empty() ? "" : " '" + obj + "'") + ": " + reason);
  }
};

}  // namespace mc::h5
