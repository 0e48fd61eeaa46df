// What the HDF5 wrapper's files share (io/h5_file*.cpp): an owning id, HDF5's error text
// made readable, and whether a failure came from HDF5 or the system (the file must then not be flushed again).
// Internal to io/.
#pragma once
#include <hdf5.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

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

// H5I_DATASET, H5I_GROUP, or H5I_BADID when the object (or one of its parents) is missing.
inline H5I_type_t kind(File f, const std::string& obj) {
  const Id o(H5Oopen(f.id, obj.c_str(), H5P_DEFAULT), H5Oclose);
  return o.ok() ? H5Iget_type(o) : H5I_BADID;
}

inline Id open_dataset(File f, const std::string& ds, const std::string& what) {
  if (kind(f, ds) == H5I_BADID) f.fail(what, ds, "no such dataset");
  Id d(H5Dopen2(f.id, ds.c_str(), H5P_DEFAULT), H5Dclose);
  if (!d.ok()) f.fail(what, ds, hdf5_reason());
  return d;
}

inline Id open_object(File f, const std::string& obj, const std::string& what) {
  Id o(H5Oopen(f.id, obj.c_str(), H5P_DEFAULT), H5Oclose);
  if (!o.ok()) f.fail(what, obj, "no such group or dataset");
  return o;
}

// Makes room for a new dataset: an old dataset goes, a group is never silently dropped.
inline void clear_for_dataset(File f, const std::string& ds, const std::string& what) {
  const H5I_type_t k = kind(f, ds);
  if (k == H5I_GROUP) f.fail(what, ds, "a group has that path");
  if (k != H5I_BADID && H5Ldelete(f.id, ds.c_str(), H5P_DEFAULT) < 0) f.fail(what, ds, hdf5_reason());
}

// Kept in a named variable by callers: closing it clears HDF5's error stack, which must outlive the failure report.
inline Id parents_created() {
  Id lcpl(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
  H5Pset_create_intermediate_group(lcpl, 1);
  return lcpl;
}

inline std::vector<hsize_t> dims_of(hid_t space) {
  std::vector<hsize_t> dims(std::max(H5Sget_simple_extent_ndims(space), 0));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  return dims;
}

inline std::vector<hsize_t> dataset_dims(hid_t ds) {
  const Id space(H5Dget_space(ds), H5Sclose);
  return dims_of(space);
}

// The names of the attributes of the open object `o` (the object `obj` of `f`), sorted.
inline std::vector<std::string> attr_names(File f, hid_t o, const std::string& obj, const std::string& what) {
  std::vector<std::string> names;
  auto collect = [](hid_t, const char* name, const H5A_info_t*, void* out) -> herr_t {
    static_cast<std::vector<std::string>*>(out)->push_back(name);
    return 0;
  };
  hsize_t next = 0;
  if (H5Aiterate2(o, H5_INDEX_NAME, H5_ITER_INC, &next, collect, &names) < 0) f.fail(what, obj, hdf5_reason());
  return names;
}

}  // namespace mc::h5
