// The parts of H5File that read or copy part of a file: the rows of a table a killed writer left readable, and
// objects, attributes and leading rows copied into another file (a resume rewrites the file it resumes).
#include <algorithm>
#include <functional>
#include <numeric>
#include <vector>

#include "io/h5_detail.hpp"
#include "io/h5_file.hpp"

namespace mc {

using namespace h5;

namespace {

// Values in one row of a table of shape `dims`.
hsize_t row_width(const std::vector<hsize_t>& dims) {
  return std::accumulate(dims.begin() + 1, dims.end(), hsize_t{1}, std::multiplies<>());
}

// Selects rows [first, first + count) of a table of shape `dims` in each of `spaces`; returns the memory space
// they fill.
Id select_rows(const std::vector<hid_t>& spaces, const std::vector<hsize_t>& dims, hsize_t first, hsize_t count) {
  std::vector<hsize_t> start(dims.size(), 0), extent = dims;
  start[0] = first;
  extent[0] = count;
  for (const hid_t space : spaces)
    H5Sselect_hyperslab(space, H5S_SELECT_SET, start.data(), nullptr, extent.data(), nullptr);
  return Id(H5Screate_simple(static_cast<int>(extent.size()), extent.data(), nullptr), H5Sclose);
}

// The table's rows chunk by chunk, up to the first chunk that cannot be read.
template <class T>
std::vector<T> leading_rows(File f, const std::string& ds, hid_t mem_type) {
  const std::string what = "read the rows of table";
  const Id d = open_dataset(f, ds, what);
  const Id space(H5Dget_space(d), H5Sclose), dcpl(H5Dget_create_plist(d), H5Pclose);
  const std::vector<hsize_t> dims = dims_of(space);
  if (dims.empty()) f.fail(what, ds, "a scalar dataset has no rows");
  std::vector<hsize_t> chunk(dims.size(), 0);
  if (H5Pget_layout(dcpl) != H5D_CHUNKED || H5Pget_chunk(dcpl, static_cast<int>(chunk.size()), chunk.data()) < 0)
    chunk[0] = std::max<hsize_t>(dims[0], 1);
  std::vector<T> out;
  for (hsize_t first = 0; first < dims[0]; first += chunk[0]) {
    const hsize_t count = std::min(chunk[0], dims[0] - first);
    std::vector<T> rows(count * row_width(dims));
    const Id mem = select_rows({space}, dims, first, count);
    if (H5Dread(d, mem_type, mem, space, H5P_DEFAULT, rows.data()) < 0) break;
    out.insert(out.end(), rows.begin(), rows.end());
  }
  return out;
}

}  // namespace

std::vector<double> H5File::read_leading_doubles(const std::string& ds) const {
  return leading_rows<double>({fid(), path_}, ds, H5T_NATIVE_DOUBLE);
}

std::vector<std::int64_t> H5File::read_leading_ints(const std::string& ds) const {
  return leading_rows<std::int64_t>({fid(), path_}, ds, H5T_NATIVE_INT64);
}

void H5File::copy_object(const H5File& from, const std::string& obj) {
  change([&] {
    const File f{fid(), path_};
    const std::string what = "copy from " + from.path() + " the object";
    const Id lcpl = parents_created();
    if (H5Ocopy(from.fid(), obj.c_str(), f.id, obj.c_str(), H5P_DEFAULT, lcpl) < 0) f.fail(what, obj, hdf5_reason());
  });
}

void H5File::copy_attrs(const H5File& from, const std::string& obj) {
  change([&] {
    const File src{from.fid(), from.path()}, dst{fid(), path_};
    const std::string what = "copy the attributes of";
    const Id in = open_object(src, obj, what), out = open_object(dst, obj, what);
    for (const auto& name : attr_names(src, in, obj, what)) {
      const Id a(H5Aopen(in, name.c_str(), H5P_DEFAULT), H5Aclose);
      if (!a.ok()) src.fail(what, obj, hdf5_reason());
      const Id type(H5Aget_type(a), H5Tclose), space(H5Aget_space(a), H5Sclose);
      // Read and written in the file's own type: a byte copy. Variable-length values would be pointers.
      if (H5Tdetect_class(type, H5T_VLEN) > 0 || H5Tis_variable_str(type) > 0)
        src.fail(what, obj, "attribute '" + name + "' has variable length");
      std::vector<unsigned char> bytes(H5Aget_storage_size(a));
      if (H5Aread(a, type, bytes.data()) < 0) src.fail(what, obj, hdf5_reason());
      Id b(H5Acreate2(out, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
      if (!b.ok() || H5Awrite(b, type, bytes.data()) < 0 || b.close() < 0) dst.fail(what, obj, hdf5_reason());
    }
  });
}

void H5File::copy_rows(const H5File& from, const std::string& ds, hsize_t nrows) {
  change([&] {
    const File src{from.fid(), from.path()}, dst{fid(), path_};
    const std::string what = "copy the rows of table";
    const Id in = open_dataset(src, ds, what);
    const Id type(H5Dget_type(in), H5Tclose), dcpl(H5Dget_create_plist(in), H5Pclose);
    const Id in_space(H5Dget_space(in), H5Sclose);
    std::vector<hsize_t> dims = dims_of(in_space);
    if (dims.empty()) src.fail(what, ds, "a scalar dataset has no rows");
    if (dims[0] < nrows)
      src.fail(what, ds, "it has " + std::to_string(dims[0]) + " rows, fewer than " + std::to_string(nrows));
    std::vector<hsize_t> maxdims = dims;
    maxdims[0] = H5S_UNLIMITED;
    dims[0] = nrows;
    const Id out_space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), maxdims.data()), H5Sclose);
    const Id lcpl = parents_created();
    Id out(H5Dcreate2(dst.id, ds.c_str(), type, out_space, lcpl, dcpl, H5P_DEFAULT), H5Dclose);
    if (!out.ok()) dst.fail(what, ds, hdf5_reason());
    // In blocks of about 64 MB: a frame table can be far larger than memory should hold at once.
    const hsize_t row_bytes = std::max<hsize_t>(1, H5Tget_size(type) * row_width(dims));
    const hsize_t block = std::max<hsize_t>(1, (64u << 20) / row_bytes);
    std::vector<unsigned char> bytes;
    for (hsize_t first = 0; first < nrows; first += block) {
      const hsize_t count = std::min(block, nrows - first);
      bytes.resize(count * row_bytes);
      const Id mem = select_rows({in_space, out_space}, dims, first, count);
      if (H5Dread(in, type, mem, in_space, H5P_DEFAULT, bytes.data()) < 0) src.fail(what, ds, hdf5_reason());
      if (H5Dwrite(out, type, mem, out_space, H5P_DEFAULT, bytes.data()) < 0) dst.fail(what, ds, hdf5_reason());
    }
    if (out.close() < 0) dst.fail(what, ds, hdf5_reason());
  });
  copy_attrs(from, ds);
}

}  // namespace mc
