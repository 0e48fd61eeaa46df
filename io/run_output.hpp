// The output file of a run (layout in README.md, "Output"): scene text, initial specimen (and a specimen of rigid
// cells' polygons), histories, frames, checkpoints, status; an XDMF sidecar so ParaView opens the frames (particles;
// or the cells moving and their facets' damage); histories as CSV when the run ends.
// A new file is written as <path>.partial and renamed to <path> by `publish` once its initial contents are flushed:
// <path> is complete or absent. Everything written after that is flushed at once (`flush`), so a run killed at any
// moment leaves a file readable up to its last flush, and up to its last checkpoint when killed during a flush
// (see H5File); a resume continues it in a fresh copy (`rewrite_up_to`).
#pragma once
#include <array>
#include <string>
#include <vector>

#include "engine/archive.hpp"
#include "engine/system.hpp"  // SpecimenData, CellFrame, CrackRows
#include "io/h5_file.hpp"

namespace mc {

// The run that wrote `f` was killed: its status still says "running". Its tables may be half-written past its last
// complete flush (see H5File): read them with read_leading_*, and never write into the file.
bool killed_run(const H5File& f);

class RunOutput {
 public:
  // A new file, <path>.partial until `publish` (an existing <path> stays until then). Destroyed unpublished, it
  // removes the partial file.
  RunOutput(const std::string& path, const std::string& scene_text, const std::string& scene_file,
            const SpecimenData& s);
  // An existing file, to resume it: read-only until `rewrite_up_to`.
  explicit RunOutput(const std::string& path);
  // The scene text stored in an existing output file, read without opening it for writing.
  static std::string stored_scene(const std::string& path);
  ~RunOutput();
  RunOutput(const RunOutput&) = delete;
  RunOutput& operator=(const RunOutput&) = delete;
  // Flushes, renames <path>.partial to <path> (replacing any file there) and writes the XDMF sidecar.
  void publish();
  static std::string partial_path(const std::string& path) { return path + ".partial"; }
  // Every file a run with output `path` writes: the file, its partial name, its sidecars and their temporaries.
  static std::vector<std::string> files_written(const std::string& path);

  void create_histories(const std::vector<std::string>& names, const std::vector<std::string>& units);
  void append_history(const std::vector<std::vector<double>>& columns);  // one column per series, equal lengths
  std::int64_t history_rows() const;
  // `cells`: the frame of a specimen of cells (SpecimenData::cells), nothing for particles. std::invalid_argument
  // when a frame's sizes are not the file's.
  // `contacts`: the frame's contacts between particles, when recorded (/contacts).
  void append_frame(double time, std::int64_t step, const std::vector<double>& x, const std::vector<double>& v,
                    const std::vector<double>& force, const CellFrame& cells = {}, const ContactFrame& contacts = {});
  std::int64_t frame_rows() const;

  // The crack log: one row per bond break or first yield (layout in README.md, "Output").
  void create_crack_log(int dimension, const std::vector<std::string>& models);
  void append_cracks(const CrackRows& rows);
  std::int64_t crack_rows() const;

  // Checkpoints alternate between two slots; a slot counts only once its `complete` attribute is written, so a
  // kill while writing one leaves the other intact.
  void write_checkpoint(const Archive& a, std::int64_t step);
  Archive read_checkpoint() const;  // the newest complete one; IoError if there is none
  // Resuming: drops the history rows, frames and cracks written after the checkpoint being resumed, and opens the
  // file for writing. A file its run closed (any status but "running") is truncated in place. The file of a run
  // that was killed may have been killed during a flush, half-updated beyond its checkpoint: readable up to it but
  // not safely writable, so it is rewritten into a fresh file that replaces it (a copy of the whole file). A failed
  // rewrite leaves the file as it was.
  void resume_at(std::int64_t history_rows, std::int64_t frame_rows, std::int64_t crack_rows);

  void set_status(const std::string& status, const std::string& message = "");
  // The run's last word: everything flushed, then the status alone in a flush of its own, so that a file whose
  // status is not "running" was complete before it (resume_at writes into it in place).
  void end_with_status(const std::string& status, const std::string& message);
  void set_xy_plots(const std::string& pairs);
  void flush();
  void write_csv() const;  // <stem>_history.csv
  const std::string& path() const { return file_.path(); }
  H5File& file() { return file_; }

 private:
  void write_initial(const std::string& scene_text, const std::string& scene_file, const SpecimenData& s);
  void write_cells(const SpecimenData& s);
  void write_fibres(const FibreGeometry& g);
  void append_frame_row(const std::string& ds, const std::vector<double>& row);
  void append_contacts(const ContactFrame& contacts);
  void write_xdmf() const;
  std::string newest_checkpoint() const;  // the complete slot of the highest step
  void rewrite_up_to(std::int64_t history_rows, std::int64_t frame_rows,
                     std::int64_t crack_rows);  // <stem>.xdmf, rewritten atomically
                                                // after each frame once published
  H5File file_;
  std::vector<std::string> names_;
  bool published_ = true;
};

}  // namespace mc
