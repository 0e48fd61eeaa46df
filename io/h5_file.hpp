// One HDF5 file, through the HDF5 C API: whole datasets, strings, extendible row tables and attributes.
// Object paths are absolute ("/history/time") or relative to the root group. Every failure throws mc::IoError
// naming the file, the object and the reason; HDF5's own error printing is silenced.
//
// Crash safety (default file format, no SWMR): a writer killed between two flushes leaves the file as it was
// at its last flush(), except for objects replaced, removed or truncated since then, whose old bytes HDF5 may
// already have reused. A writer killed during flush() itself leaves some objects updated and others not: tables
// of unequal lengths, a chunk index pointing past the file's recorded end, half-rewritten groups. What was
// complete before that flush still reads (read_leading_*), but the file must not be written again: a resume copies
// it into a fresh file (copy_*). To keep the flushed
// state on disk, the metadata cache of a writable file never evicts: the metadata of every object touched stays
// in memory (some KB per object) until the file is closed.
// While a process has the file open for writing, HDF5's file lock keeps other processes from opening it
// (HDF5_USE_FILE_LOCKING=FALSE overrides); the lock goes with the process, even a killed one.
// A change that fails in HDF5 or the system (a full disk, a write error; not a check such as a missing dataset)
// abandons the file: HDF5 can no longer write to it, nothing more is flushed (a flush cut short by a full disk could
// leave it unreadable), and every later call throws. On disk it stays as it was at its last successful flush(), which
// reserves the disk space its metadata needs before writing any of it. An abandoned file is never closed through HDF5
// (a failed close corrupts HDF5's state and crashes the process at exit); its few KB of memory go with the process.
//
// Replaced or removed objects leave their file space unused once the file is closed (h5repack reclaims it).
// Not for concurrent use: one thread at a time per file.
#pragma once
#include <hdf5.h>

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace mc {

class H5File {
 public:
  enum class Mode { Create /*truncate*/, ReadWrite, ReadOnly };
  H5File(const std::string& path, Mode mode);
  ~H5File();  // closes; never throws
  H5File(H5File&& other) noexcept;
  H5File& operator=(H5File&& other) noexcept;
  H5File(const H5File&) = delete;
  H5File& operator=(const H5File&) = delete;

  const std::string& path() const { return path_; }
  // After it the file on disk is complete and readable (it reaches the OS, not necessarily the platter). The disk
  // space the flush needs is reserved first: a full disk fails it before anything is written.
  void flush();
  // Closes the file and opens it again in another mode (a file read first, then written).
  void reopen(Mode mode);
  // Renames the open file (std::filesystem::rename: atomic within a directory, replacing any file there).
  void rename(const std::string& to);
  // True after a failed change (see above).
  bool abandoned() const { return abandoned_; }
  // Group or dataset at any depth; false when any component is missing.
  bool exists(const std::string& obj) const;
  // Child names of a group, sorted.
  std::vector<std::string> list(const std::string& group) const;
  // Creates the group and any missing parents; nothing if it exists.
  void create_group(const std::string& group);
  // Unlinks the object if present.
  void remove(const std::string& obj);

  // Whole datasets. Missing parent groups are created; an existing dataset at that path is replaced.
  // dims is the row-major shape (empty: scalar); its product must equal data.size() (std::invalid_argument).
  void write(const std::string& ds, const std::vector<double>& data, const std::vector<hsize_t>& dims);
  void write(const std::string& ds, const std::vector<std::int64_t>& data, const std::vector<hsize_t>& dims);
  void write(const std::string& ds, const std::vector<std::int32_t>& data, const std::vector<hsize_t>& dims);
  void write(const std::string& ds, const std::vector<std::uint8_t>& data, const std::vector<hsize_t>& dims);
  // Scalar fixed-length UTF-8 string (h5py reads it as bytes; .asstr() gives str).
  void write_string(const std::string& ds, const std::string& text);
  // read_doubles converts from any numeric type; read_ints and read_bytes from integer types only.
  std::vector<double> read_doubles(const std::string& ds, std::vector<hsize_t>* dims = nullptr) const;
  std::vector<std::int64_t> read_ints(const std::string& ds, std::vector<hsize_t>* dims = nullptr) const;
  std::vector<std::uint8_t> read_bytes(const std::string& ds, std::vector<hsize_t>* dims = nullptr) const;
  // Fixed- or variable-length string (so files written by h5py read too).
  std::string read_string(const std::string& ds) const;
  std::vector<hsize_t> shape(const std::string& ds) const;

  // Extendible tables: rows of `width` doubles or int64s growing along the first dimension (width 0: a 1-D
  // dataset). Chunks hold about 64 KiB. create_table replaces an existing dataset at that path.
  void create_table(const std::string& ds, hsize_t width, bool integer = false);
  // A view of `rows` rows of a table from row `first` on as a dataset of its own, of the table's type, shaped `dims`
  // (as many values as the rows hold; HDF5's virtual dataset in the same file, no copy). For readers that take
  // whole datasets only.
  void create_rows_view(const std::string& view, const std::string& table, hsize_t first, hsize_t rows,
                        const std::vector<hsize_t>& dims);
  // nrows * width values, row-major; the value type must match the table's.
  void append_rows(const std::string& ds, const double* rows, hsize_t nrows);
  void append_rows(const std::string& ds, const std::int64_t* rows, hsize_t nrows);
  hsize_t rows(const std::string& ds) const;
  // Shrinks to nrows (drops rows written after a checkpoint); a table shorter than nrows is an IoError.
  void truncate_rows(const std::string& ds, hsize_t nrows);

  // The rows of a table that a killed writer left readable: all of them, or those before the first chunk that
  // cannot be read (one its unfinished flush pointed to before the chunk's place was in the file).
  std::vector<double> read_leading_doubles(const std::string& ds) const;
  std::vector<std::int64_t> read_leading_ints(const std::string& ds) const;

  // Copies from another open file into this one (a resume rewrites the file it resumes: see RunOutput).
  // A group with everything beneath it, or a dataset, with attributes. Missing parent groups are created.
  void copy_object(const H5File& from, const std::string& obj);
  // The attributes of a group or dataset that exists in both files; none may exist here yet.
  void copy_attrs(const H5File& from, const std::string& obj);
  // A new table here holding the first `nrows` rows of the table `ds` of `from`, with its type, chunks and
  // attributes. Only those rows are read: the rest of `from`'s table may be damaged.
  void copy_rows(const H5File& from, const std::string& ds, hsize_t nrows);

  // Scalar attributes on an existing group or dataset, created or overwritten. In this file format an
  // object's attributes share 64 KiB: longer text belongs in a dataset.
  void set_attr(const std::string& obj, const std::string& name, double v);
  void set_attr(const std::string& obj, const std::string& name, std::int64_t v);
  void set_attr(const std::string& obj, const std::string& name, const std::string& v);
  double attr_double(const std::string& obj, const std::string& name) const;
  std::int64_t attr_int(const std::string& obj, const std::string& name) const;
  std::string attr_string(const std::string& obj, const std::string& name) const;
  // False also when the object is missing.
  bool has_attr(const std::string& obj, const std::string& name) const;
  // The object's numeric scalar attributes, by name (text attributes left out).
  std::vector<std::pair<std::string, double>> number_attrs(const std::string& obj) const;

 private:
  hid_t fid() const;  // the open file id, with HDF5's error printing off for the calling thread
  // Runs a change to the file; when a call into HDF5 or the system fails in it, the file is abandoned.
  void change(const std::function<void()>& f);
  void abandon() noexcept;
  void close() noexcept;

  std::string path_;
  hid_t file_ = H5I_INVALID_HID;
  bool writable_ = false;
  bool abandoned_ = false;
};

}  // namespace mc
