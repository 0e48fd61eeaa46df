#include "io/h5_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <numeric>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "engine/errors.hpp"

namespace mc {
namespace {

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

// HDF5 closes the files still open when the process exits, flushing them. An abandoned file must never be flushed
// or closed (H5Fclose of a file whose writes fail leaves HDF5's state half torn down, and the exit-time cleanup then
// crashes), so that cleanup is off: every healthy file is closed by its H5File before the process ends. It must be
// switched off before the library initialises, hence at static initialisation of this file.
[[maybe_unused]] const bool kNoCleanupAtExit = H5dont_atexit() >= 0;

void quiet_this_thread() {
  // The library is built thread-safe, which makes the error-printing switch per thread.
  thread_local bool quiet = false;
  if (!quiet) quiet = H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr) >= 0;
}

// A failed system call as HDF5 reports it ("file write failed: time = …, filename = …, errno = 28, error message =
// 'No space left on device', buf = …") shortened to what it means: "file write failed: No space left on device".
std::string shortened(const std::string& desc) {
  const std::string key = "error message = '";
  const auto at = desc.find(key), colon = desc.find(':');
  if (at == std::string::npos || colon == std::string::npos || colon > at) return desc;
  const auto from = at + key.size(), to = desc.find('\'', from);
  return desc.substr(0, colon) + ": " + desc.substr(from, to == std::string::npos ? std::string::npos : to - from);
}

// Set when a call into HDF5 or the system failed (rather than a check of ours, such as a missing dataset or a value
// type that does not match the table): such a failure may leave HDF5's state ahead of the file, which then must not
// be flushed.
thread_local bool g_call_failed = false;

// The innermost message of HDF5's error stack: the most specific cause.
std::string hdf5_reason() {
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
H5I_type_t kind(File f, const std::string& obj) {
  const Id o(H5Oopen(f.id, obj.c_str(), H5P_DEFAULT), H5Oclose);
  return o.ok() ? H5Iget_type(o) : H5I_BADID;
}

Id open_dataset(File f, const std::string& ds, const std::string& what) {
  if (kind(f, ds) == H5I_BADID) f.fail(what, ds, "no such dataset");
  Id d(H5Dopen2(f.id, ds.c_str(), H5P_DEFAULT), H5Dclose);
  if (!d.ok()) f.fail(what, ds, hdf5_reason());
  return d;
}

Id open_object(File f, const std::string& obj, const std::string& what) {
  Id o(H5Oopen(f.id, obj.c_str(), H5P_DEFAULT), H5Oclose);
  if (!o.ok()) f.fail(what, obj, "no such group or dataset");
  return o;
}

// Makes room for a new dataset: an old dataset goes, a group is never silently dropped.
void clear_for_dataset(File f, const std::string& ds, const std::string& what) {
  const H5I_type_t k = kind(f, ds);
  if (k == H5I_GROUP) f.fail(what, ds, "a group has that path");
  if (k != H5I_BADID && H5Ldelete(f.id, ds.c_str(), H5P_DEFAULT) < 0) f.fail(what, ds, hdf5_reason());
}

// Kept in a named variable by callers: closing it clears HDF5's error stack, which must outlive the failure report.
Id parents_created() {
  Id lcpl(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
  H5Pset_create_intermediate_group(lcpl, 1);
  return lcpl;
}

std::vector<hsize_t> dims_of(hid_t space) {
  std::vector<hsize_t> dims(std::max(H5Sget_simple_extent_ndims(space), 0));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  return dims;
}

std::vector<hsize_t> dataset_dims(hid_t ds) {
  const Id space(H5Dget_space(ds), H5Sclose);
  return dims_of(space);
}

hsize_t product(const std::vector<hsize_t>& dims) {
  return std::accumulate(dims.begin(), dims.end(), hsize_t{1}, std::multiplies<>());
}

Id simple_space(const std::vector<hsize_t>& dims, const hsize_t* maxdims = nullptr) {
  if (dims.empty()) return Id(H5Screate(H5S_SCALAR), H5Sclose);
  return Id(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), maxdims), H5Sclose);
}

// Fixed-length rather than variable-length: no global heap, and the bytes sit in the dataset itself.
Id string_type(std::size_t size) {
  Id type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type, std::max<std::size_t>(size, 1));  // HDF5 has no zero-size strings
  H5Tset_strpad(type, H5T_STR_NULLPAD);
  H5Tset_cset(type, H5T_CSET_UTF8);
  return type;
}

std::string padded(const std::string& text) { return text.empty() ? std::string(1, '\0') : text; }

// Refuses (rather than silently clamps) integers that do not fit the type they are read into.
H5T_conv_ret_t abort_on_overflow(H5T_conv_except_t except, hid_t, hid_t, void*, void*, void* overflowed) {
  if (except != H5T_CONV_EXCEPT_RANGE_HI && except != H5T_CONV_EXCEPT_RANGE_LOW) return H5T_CONV_UNHANDLED;
  *static_cast<bool*>(overflowed) = true;
  return H5T_CONV_ABORT;
}

std::string class_name(H5T_class_t c) {
  switch (c) {
    case H5T_INTEGER: return "integer";
    case H5T_FLOAT: return "floating point";
    case H5T_STRING: return "string";
    default: return "a non-numeric type";
  }
}

// Reads the single string held by a dataset or attribute; `read(mem_type, buffer)` does the transfer.
std::string read_single_string(File f, const std::string& what, const std::string& obj, hid_t type, hid_t space,
                               const std::function<herr_t(hid_t, void*)>& read) {
  if (H5Tget_class(type) != H5T_STRING) f.fail(what, obj, "stored as " + class_name(H5Tget_class(type)));
  if (H5Sget_simple_extent_npoints(space) != 1) f.fail(what, obj, "holds more than one string");
  if (H5Tis_variable_str(type) > 0) {  // written by h5py, say
    const Id mem(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_size(mem, H5T_VARIABLE);
    H5Tset_cset(mem, H5Tget_cset(type));  // HDF5 converts no character set into another
    char* text = nullptr;
    if (read(mem, &text) < 0) f.fail(what, obj, hdf5_reason());
    std::string out = text ? text : "";
    H5free_memory(text);
    return out;
  }
  // One byte more than stored, null-terminated: HDF5 converts any padding to a terminator.
  const Id mem(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(mem, H5Tget_size(type) + 1);
  H5Tset_strpad(mem, H5T_STR_NULLTERM);
  H5Tset_cset(mem, H5Tget_cset(type));
  std::string buf(H5Tget_size(type) + 1, '\0');
  if (read(mem, buf.data()) < 0) f.fail(what, obj, hdf5_reason());
  return buf.c_str();
}

template <class T>
void write_numeric(File f, const std::string& ds, const std::vector<T>& data, const std::vector<hsize_t>& dims,
                   hid_t file_type, hid_t mem_type) {
  if (product(dims) != data.size())
    throw std::invalid_argument(f.path + ": dataset '" + ds + "': shape holds " + std::to_string(product(dims)) +
                                " values but " + std::to_string(data.size()) + " were given");
  const std::string what = "write dataset";
  clear_for_dataset(f, ds, what);
  const Id space = simple_space(dims);
  const Id lcpl = parents_created();
  Id d(H5Dcreate2(f.id, ds.c_str(), file_type, space, lcpl, H5P_DEFAULT, H5P_DEFAULT), H5Dclose);
  if (!d.ok()) f.fail(what, ds, hdf5_reason());
  if (!data.empty() && H5Dwrite(d, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) < 0)
    f.fail(what, ds, hdf5_reason());
  if (d.close() < 0) f.fail(what, ds, hdf5_reason());
}

template <class T>
std::vector<T> read_numeric(File f, const std::string& ds, std::vector<hsize_t>* dims, hid_t mem_type,
                            bool integer_only) {
  const std::string what = "read dataset";
  const Id d = open_dataset(f, ds, what);
  const Id type(H5Dget_type(d), H5Tclose);
  const H5T_class_t c = H5Tget_class(type);
  if (c != H5T_INTEGER && (integer_only || c != H5T_FLOAT))
    f.fail(what, ds, "stored as " + class_name(c) + ", not " + (integer_only ? "integer" : "numeric"));
  const Id space(H5Dget_space(d), H5Sclose);
  std::vector<T> out(static_cast<std::size_t>(std::max<hssize_t>(H5Sget_simple_extent_npoints(space), 0)));
  const Id xfer(H5Pcreate(H5P_DATASET_XFER), H5Pclose);
  bool overflowed = false;
  H5Pset_type_conv_cb(xfer, abort_on_overflow, &overflowed);
  if (!out.empty() && H5Dread(d, mem_type, H5S_ALL, H5S_ALL, xfer, out.data()) < 0) {
    const std::string type_name = (std::is_signed_v<T> ? "int" : "uint") + std::to_string(8 * sizeof(T));
    f.fail(what, ds, overflowed ? "a stored value is out of range for " + type_name : hdf5_reason());
  }
  if (dims) *dims = dims_of(space);
  return out;
}

void append_raw(File f, const std::string& ds, const void* rows, hsize_t nrows, bool integer) {
  const std::string what = "append rows to";
  Id d = open_dataset(f, ds, what);
  const Id type(H5Dget_type(d), H5Tclose);
  if ((H5Tget_class(type) == H5T_INTEGER) != integer)
    f.fail(what, ds, std::string("the table holds ") + (integer ? "doubles" : "integers"));
  std::vector<hsize_t> dims = dataset_dims(d);
  if (dims.empty() || dims.size() > 2) f.fail(what, ds, "not a table (rank " + std::to_string(dims.size()) + ")");
  if (nrows == 0) return;
  std::vector<hsize_t> start(dims.size(), 0), count = dims;
  start[0] = dims[0];
  count[0] = nrows;
  dims[0] += nrows;
  if (H5Dset_extent(d, dims.data()) < 0) f.fail(what, ds, hdf5_reason());
  const Id file_space(H5Dget_space(d), H5Sclose);
  H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr);
  const Id mem_space = simple_space(count);
  const hid_t mem_type = integer ? H5T_NATIVE_INT64 : H5T_NATIVE_DOUBLE;
  if (H5Dwrite(d, mem_type, mem_space, file_space, H5P_DEFAULT, rows) < 0) f.fail(what, ds, hdf5_reason());
  if (d.close() < 0) f.fail(what, ds, hdf5_reason());
}

void set_attr_raw(File f, const std::string& obj, const std::string& name, hid_t file_type, hid_t mem_type,
                  const void* value) {
  const std::string what = "write attribute '" + name + "' of";
  const Id o = open_object(f, obj, what);
  // Deleted, not rewritten: the new value may have another type or string length.
  if (H5Aexists(o, name.c_str()) > 0 && H5Adelete(o, name.c_str()) < 0) f.fail(what, obj, hdf5_reason());
  const Id space(H5Screate(H5S_SCALAR), H5Sclose);
  Id a(H5Acreate2(o, name.c_str(), file_type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  if (!a.ok() || H5Awrite(a, mem_type, value) < 0 || a.close() < 0) f.fail(what, obj, hdf5_reason());
}

Id open_attr(File f, const std::string& obj, const std::string& name, const std::string& what) {
  const Id o = open_object(f, obj, what);
  if (H5Aexists(o, name.c_str()) <= 0) f.fail(what, obj, "no such attribute");
  Id a(H5Aopen(o, name.c_str(), H5P_DEFAULT), H5Aclose);
  if (!a.ok()) f.fail(what, obj, hdf5_reason());
  return a;
}

template <class T>
T read_attr(File f, const std::string& obj, const std::string& name, hid_t mem_type, bool integer_only) {
  const std::string what = "read attribute '" + name + "' of";
  const Id a = open_attr(f, obj, name, what);
  const Id type(H5Aget_type(a), H5Tclose);
  const H5T_class_t c = H5Tget_class(type);
  if (c != H5T_INTEGER && (integer_only || c != H5T_FLOAT))
    f.fail(what, obj, "stored as " + class_name(c) + ", not " + (integer_only ? "integer" : "numeric"));
  const Id space(H5Aget_space(a), H5Sclose);
  if (H5Sget_simple_extent_npoints(space) != 1) f.fail(what, obj, "not a single value");
  T value{};
  if (H5Aread(a, mem_type, &value) < 0) f.fail(what, obj, hdf5_reason());
  return value;
}

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

// The file descriptor HDF5 writes through (the default sec2 driver keeps one).
int descriptor(File f, const std::string& what) {
  void* handle = nullptr;
  if (H5Fget_vfd_handle(f.id, H5P_DEFAULT, &handle) < 0 || !handle) f.fail(what, "", hdf5_reason());
  return *static_cast<int*>(handle);
}

// Allocates the disk blocks between the end of the file as written and the end HDF5 has allocated (its metadata
// not yet written lies there), so that a full disk fails here, before a flush overwrites any flushed metadata.
void reserve_allocated_space(File f) {
  const std::string what = "flush file";
  hsize_t allocated = 0;
  if (H5Fget_filesize(f.id, &allocated) < 0) f.fail(what, "", hdf5_reason());
  const int fd = descriptor(f, what);
  struct stat st {};
  g_call_failed = true;  // whatever fails below
  if (fstat(fd, &st) != 0) f.fail(what, "", std::strerror(errno));
  const int e = static_cast<hsize_t>(st.st_size) >= allocated
                    ? 0
                    : posix_fallocate(fd, st.st_size, static_cast<off_t>(allocated) - st.st_size);
  if (e != 0) f.fail(what, "", std::strerror(e));
  g_call_failed = false;
}

}  // namespace

H5File::H5File(const std::string& path, Mode mode) : path_(path), writable_(mode != Mode::ReadOnly) {
  quiet_this_thread();
  const Id fapl = mode == Mode::ReadOnly ? Id(H5Pcreate(H5P_FILE_ACCESS), H5Pclose) : crash_safe_writing();
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

template <class F>
void H5File::change(F&& f) {
  g_call_failed = false;
  try {
    f();
  } catch (const IoError&) {
    if (writable_ && g_call_failed) abandon();
    throw;
  }
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

void H5File::flush() {
  change([&] {
    const File f{fid(), path_};
    reserve_allocated_space(f);
    if (H5Fflush(f.id, H5F_SCOPE_GLOBAL) < 0) f.fail("flush file", "", hdf5_reason());
  });
}

void H5File::rename(const std::string& to) {
  fid();
  std::error_code ec;
  std::filesystem::rename(path_, to, ec);
  if (ec) throw IoError(path_ + ": cannot rename to " + to + ": " + ec.message());
  path_ = to;
}

bool H5File::exists(const std::string& obj) const { return kind({fid(), path_}, obj) != H5I_BADID; }

std::vector<std::string> H5File::list(const std::string& group) const {
  const File f{fid(), path_};
  const std::string what = "list group";
  if (kind(f, group) != H5I_GROUP) f.fail(what, group, exists(group) ? "not a group" : "no such group");
  std::vector<std::string> names;
  // Iterating by name index in increasing order yields the names sorted. (auto: the link-info type
  // differs between HDF5 1.10 and 1.12.)
  const herr_t status = H5Literate_by_name(
      f.id, group.c_str(), H5_INDEX_NAME, H5_ITER_INC, nullptr,
      [](hid_t, const char* name, const auto*, void* out) -> herr_t {
        static_cast<std::vector<std::string>*>(out)->emplace_back(name);
        return 0;
      },
      &names, H5P_DEFAULT);
  if (status < 0) f.fail(what, group, hdf5_reason());
  return names;
}

void H5File::create_group(const std::string& group) {
  change([&] {
    const File f{fid(), path_};
    const H5I_type_t k = kind(f, group);
    if (k == H5I_GROUP) return;
    if (k != H5I_BADID) f.fail("create group", group, "a dataset has that path");
    const Id lcpl = parents_created();
    const Id g(H5Gcreate2(f.id, group.c_str(), lcpl, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
    if (!g.ok()) f.fail("create group", group, hdf5_reason());
  });
}

void H5File::remove(const std::string& obj) {
  change([&] {
    if (exists(obj) && H5Ldelete(fid(), obj.c_str(), H5P_DEFAULT) < 0)
      File{file_, path_}.fail("remove", obj, hdf5_reason());
  });
}

void H5File::write(const std::string& ds, const std::vector<double>& data, const std::vector<hsize_t>& dims) {
  change([&] { write_numeric({fid(), path_}, ds, data, dims, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE); });
}

void H5File::write(const std::string& ds, const std::vector<std::int64_t>& data, const std::vector<hsize_t>& dims) {
  change([&] { write_numeric({fid(), path_}, ds, data, dims, H5T_STD_I64LE, H5T_NATIVE_INT64); });
}

void H5File::write(const std::string& ds, const std::vector<std::int32_t>& data, const std::vector<hsize_t>& dims) {
  change([&] { write_numeric({fid(), path_}, ds, data, dims, H5T_STD_I32LE, H5T_NATIVE_INT32); });
}

void H5File::write(const std::string& ds, const std::vector<std::uint8_t>& data, const std::vector<hsize_t>& dims) {
  change([&] { write_numeric({fid(), path_}, ds, data, dims, H5T_STD_U8LE, H5T_NATIVE_UINT8); });
}

void H5File::write_string(const std::string& ds, const std::string& text) {
  change([&] {
    const File f{fid(), path_};
    const std::string what = "write dataset";
    clear_for_dataset(f, ds, what);
    const Id type = string_type(text.size());
    const Id space(H5Screate(H5S_SCALAR), H5Sclose);
    const Id lcpl = parents_created();
    Id d(H5Dcreate2(f.id, ds.c_str(), type, space, lcpl, H5P_DEFAULT, H5P_DEFAULT), H5Dclose);
    if (!d.ok() || H5Dwrite(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, padded(text).data()) < 0 || d.close() < 0)
      f.fail(what, ds, hdf5_reason());
  });
}

std::vector<double> H5File::read_doubles(const std::string& ds, std::vector<hsize_t>* dims) const {
  return read_numeric<double>({fid(), path_}, ds, dims, H5T_NATIVE_DOUBLE, false);
}

std::vector<std::int64_t> H5File::read_ints(const std::string& ds, std::vector<hsize_t>* dims) const {
  return read_numeric<std::int64_t>({fid(), path_}, ds, dims, H5T_NATIVE_INT64, true);
}

std::vector<std::uint8_t> H5File::read_bytes(const std::string& ds, std::vector<hsize_t>* dims) const {
  return read_numeric<std::uint8_t>({fid(), path_}, ds, dims, H5T_NATIVE_UINT8, true);
}

std::string H5File::read_string(const std::string& ds) const {
  const File f{fid(), path_};
  const std::string what = "read dataset";
  const Id d = open_dataset(f, ds, what);
  const Id type(H5Dget_type(d), H5Tclose);
  const Id space(H5Dget_space(d), H5Sclose);
  return read_single_string(f, what, ds, type, space,
                            [&](hid_t mem, void* buf) { return H5Dread(d, mem, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf); });
}

std::vector<hsize_t> H5File::shape(const std::string& ds) const {
  return dataset_dims(open_dataset({fid(), path_}, ds, "get the shape of dataset"));
}

void H5File::create_table(const std::string& ds, hsize_t width, bool integer) {
  change([&] {
    const File f{fid(), path_};
    const std::string what = "create table";
    clear_for_dataset(f, ds, what);
    constexpr hsize_t chunk_bytes = 64 * 1024;
    const hsize_t chunk_rows = std::max<hsize_t>(1, chunk_bytes / (8 * std::max<hsize_t>(width, 1)));
    std::vector<hsize_t> dims{0}, maxdims{H5S_UNLIMITED}, chunk{chunk_rows};
    if (width > 0) {
      dims.push_back(width);
      maxdims.push_back(width);
      chunk.push_back(width);
    }
    const Id space = simple_space(dims, maxdims.data());
    const Id dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
    H5Pset_chunk(dcpl, static_cast<int>(chunk.size()), chunk.data());
    const hid_t type = integer ? H5T_STD_I64LE : H5T_IEEE_F64LE;
    const Id lcpl = parents_created();
    Id d(H5Dcreate2(f.id, ds.c_str(), type, space, lcpl, dcpl, H5P_DEFAULT), H5Dclose);
    if (!d.ok() || d.close() < 0) f.fail(what, ds, hdf5_reason());
  });
}

void H5File::append_rows(const std::string& ds, const double* rows, hsize_t nrows) {
  change([&] { append_raw({fid(), path_}, ds, rows, nrows, false); });
}

void H5File::append_rows(const std::string& ds, const std::int64_t* rows, hsize_t nrows) {
  change([&] { append_raw({fid(), path_}, ds, rows, nrows, true); });
}

hsize_t H5File::rows(const std::string& ds) const {
  const std::vector<hsize_t> dims = shape(ds);
  if (dims.empty()) File{file_, path_}.fail("count rows of", ds, "a scalar dataset has no rows");
  return dims[0];
}

void H5File::truncate_rows(const std::string& ds, hsize_t nrows) {
  change([&] {
    const File f{fid(), path_};
    const std::string what = "truncate table";
    Id d = open_dataset(f, ds, what);
    std::vector<hsize_t> dims = dataset_dims(d);
    if (dims.empty()) f.fail(what, ds, "a scalar dataset has no rows");
    if (dims[0] < nrows)
      f.fail(what, ds, "it has " + std::to_string(dims[0]) + " rows, fewer than " + std::to_string(nrows));
    dims[0] = nrows;
    if (H5Dset_extent(d, dims.data()) < 0 || d.close() < 0) f.fail(what, ds, hdf5_reason());
  });
}

void H5File::set_attr(const std::string& obj, const std::string& name, double v) {
  change([&] { set_attr_raw({fid(), path_}, obj, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &v); });
}

void H5File::set_attr(const std::string& obj, const std::string& name, std::int64_t v) {
  change([&] { set_attr_raw({fid(), path_}, obj, name, H5T_STD_I64LE, H5T_NATIVE_INT64, &v); });
}

void H5File::set_attr(const std::string& obj, const std::string& name, const std::string& v) {
  change([&] {
    const Id type = string_type(v.size());
    set_attr_raw({fid(), path_}, obj, name, type, type, padded(v).data());
  });
}

double H5File::attr_double(const std::string& obj, const std::string& name) const {
  return read_attr<double>({fid(), path_}, obj, name, H5T_NATIVE_DOUBLE, false);
}

std::int64_t H5File::attr_int(const std::string& obj, const std::string& name) const {
  return read_attr<std::int64_t>({fid(), path_}, obj, name, H5T_NATIVE_INT64, true);
}

std::string H5File::attr_string(const std::string& obj, const std::string& name) const {
  const File f{fid(), path_};
  const std::string what = "read attribute '" + name + "' of";
  const Id a = open_attr(f, obj, name, what);
  const Id type(H5Aget_type(a), H5Tclose);
  const Id space(H5Aget_space(a), H5Sclose);
  return read_single_string(f, what, obj, type, space, [&](hid_t mem, void* buf) { return H5Aread(a, mem, buf); });
}

bool H5File::has_attr(const std::string& obj, const std::string& name) const {
  const Id o(H5Oopen(fid(), obj.c_str(), H5P_DEFAULT), H5Oclose);
  return o.ok() && H5Aexists(o, name.c_str()) > 0;
}

}  // namespace mc
