#include "io/h5_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <functional>
#include <numeric>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "engine/errors.hpp"
#include "io/h5_detail.hpp"

namespace mc {
namespace {

using namespace h5;

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

void H5File::change(const std::function<void()>& f) {
  g_call_failed = false;
  try {
    f();
  } catch (const IoError&) {
    if (writable_ && g_call_failed) abandon();
    throw;
  }
}

void H5File::flush() {
  change([&] {
    const File f{fid(), path_};
    reserve_allocated_space(f);
    if (H5Fflush(f.id, H5F_SCOPE_GLOBAL) < 0) f.fail("flush file", "", hdf5_reason());
  });
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

void H5File::create_rows_view(const std::string& view, const std::string& table, hsize_t first, hsize_t rows,
                              const std::vector<hsize_t>& dims) {
  change([&] {
    const File f{fid(), path_};
    const std::string what = "create view of " + table;
    clear_for_dataset(f, view, what);
    const Id source_set = open_dataset(f, table, what);
    const Id type(H5Dget_type(source_set), H5Tclose);
    const std::vector<hsize_t> table_dims = dataset_dims(source_set);
    const hsize_t width = table_dims.size() == 2 ? table_dims[1] : 1;
    hsize_t count = 1;
    for (const hsize_t n : dims) count *= n;
    if (table_dims.empty() || table_dims.size() > 2 || rows == 0 || first + rows > table_dims[0] ||
        count != rows * width)
      f.fail(what, view,
             "rows " + std::to_string(first) + " to " + std::to_string(first + rows) + " do not hold " +
                 std::to_string(count) + " values");
    const Id source = simple_space(table_dims);
    const hsize_t start[2] = {first, 0}, stride[2] = {1, 1}, block_count[2] = {rows, width};
    const Id view_space = simple_space(dims);
    const Id dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
    if (H5Sselect_hyperslab(source, H5S_SELECT_SET, start, stride, block_count, nullptr) < 0 ||
        H5Pset_virtual(dcpl, view_space, ".", table.c_str(), source) < 0)
      f.fail(what, view, hdf5_reason());
    const Id lcpl = parents_created();
    Id d(H5Dcreate2(f.id, view.c_str(), type, view_space, lcpl, dcpl, H5P_DEFAULT), H5Dclose);
    if (!d.ok() || d.close() < 0) f.fail(what, view, hdf5_reason());
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

std::vector<std::pair<std::string, double>> H5File::number_attrs(const std::string& obj) const {
  const File f{fid(), path_};
  const std::string what = "list the attributes of";
  const Id o = open_object(f, obj, what);
  std::vector<std::pair<std::string, double>> out;
  for (const auto& name : attr_names(f, o, obj, what)) {
    const Id a = open_attr(f, obj, name, what);
    const Id type(H5Aget_type(a), H5Tclose);
    const H5T_class_t c = H5Tget_class(type);
    if (c == H5T_INTEGER || c == H5T_FLOAT) out.push_back({name, attr_double(obj, name)});
  }
  return out;
}

}  // namespace mc
