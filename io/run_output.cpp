#include "io/run_output.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "engine/errors.hpp"
#include "io/xdmf_sidecar.hpp"

namespace mc {

namespace {
std::string stem_path(const std::string& path, const std::string& suffix) {
  std::filesystem::path p(path);
  return (p.parent_path() / (p.stem().string() + suffix)).string();
}
// Writes `text` to `path` through a temporary file renamed over it: a reader sees the old file or the new one, and a
// full disk leaves the old one (the temporary is removed).
void write_atomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  std::FILE* out = std::fopen(tmp.c_str(), "w");
  if (!out) throw IoError(tmp + ": cannot create file: " + std::strerror(errno));
  const bool written = std::fwrite(text.data(), 1, text.size(), out) == text.size() && std::fflush(out) == 0;
  const int write_errno = errno;
  if (std::fclose(out) != 0 || !written) {
    const int e = written ? errno : write_errno;
    std::remove(tmp.c_str());
    throw IoError(path + ": cannot write file: " + std::strerror(e));
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::remove(tmp.c_str());
    throw IoError(path + ": cannot write file: " + ec.message());
  }
}
std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ",") + x;
  return s;
}
// The frame tables as XDMF readers take them. ParaView's Xdmf3 readers (what its "Open" picks) crash on a hyperslab of
// a table written as XDMF 2 writes it, and its legacy XDMF reader cannot read the way XDMF 3 writes one; both read
// a plain dataset. So each frame's row of each table is also a dataset of its own, /views/<name>/<frame>, a virtual
// dataset of the row (no copy of its values): `rows` of `width` values.
struct FrameView {
  std::string name;
  hsize_t rows, width;
};

std::vector<FrameView> frame_views(const H5File& f) {
  const auto d = static_cast<hsize_t>(f.attr_int("/", "dimension"));
  const hsize_t n = f.rows("/specimen/radius");
  std::vector<FrameView> v{{"x", n, d}, {"v", n, d}, {"force", n, d}};
  if (f.exists("/frames/cell_corner")) v.push_back({"cell_corner", f.rows("/specimen/cells/corner"), d});
  if (f.exists("/frames/damage")) v.push_back({"damage", f.shape("/frames/damage").at(1), 1});
  if (f.exists("/frames/fibre_state"))
    for (const char* q : {"fibre_state", "fibre_force", "fibre_slip"})
      v.push_back({q, f.rows("/specimen/fibres/family"), 1});
  return v;
}

// The contacts' tables (README.md, "Output", /contacts): per contact its pair, forces, bond and branch vector; per
// frame the first row of its contacts and how many.
struct ContactTable {
  const char* name;
  bool integer;
  const char* unit;
  bool vector;  // D per contact (pair: 2)
};
constexpr ContactTable kContactTables[] = {{"pair", true, "1", true},           {"normal_force", false, "N", false},
                                           {"shear_force", false, "N", false},  {"bonded", true, "1", false},
                                           {"branch", false, "m", true}};

hsize_t contact_width(const ContactTable& t, hsize_t d) {
  return !t.vector ? 0 : t.name == std::string("pair") ? 2 : d;
}

// The rows of /contacts that frames [0, frames) hold, as the file says (frames' first row and count).
hsize_t contact_rows(const H5File& f, hsize_t frames) {
  if (frames == 0) return 0;
  const auto first = f.read_leading_ints("/contacts/frame_first");
  const auto count = f.read_leading_ints("/contacts/frame_count");
  return static_cast<hsize_t>(first.at(frames - 1) + count.at(frames - 1));
}

// The views of frames [from, to) of the contacts' tables, /views/contact_<name>/<frame> (none for a frame without
// contacts).
void add_contact_views(H5File& f, hsize_t from, hsize_t to) {
  if (!f.exists("/contacts/frame_first")) return;
  const auto d = static_cast<hsize_t>(f.attr_int("/", "dimension"));
  const auto first = f.read_ints("/contacts/frame_first"), count = f.read_ints("/contacts/frame_count");
  for (hsize_t k = from; k < to; ++k) {
    const auto n = static_cast<hsize_t>(count.at(k));
    if (n == 0) continue;
    for (const ContactTable& t : kContactTables) {
      const std::string view = view_path(std::string("contact_") + t.name, k);
      const hsize_t w = contact_width(t, d);
      const auto dims = w > 0 ? std::vector<hsize_t>{n, w} : std::vector<hsize_t>{n};
      if (!f.exists(view)) f.create_rows_view(view, std::string("/contacts/") + t.name, first.at(k), n, dims);
    }
  }
}

// The views of frames [from, to) that are not there yet (opening a view reads its mapping: not done twice).
void add_views(H5File& f, hsize_t from, hsize_t to) {
  const std::vector<FrameView> views = frame_views(f);
  for (hsize_t k = from; k < to; ++k)
    for (const FrameView& v : views) {
      const auto dims = v.width > 1 ? std::vector<hsize_t>{v.rows, v.width} : std::vector<hsize_t>{v.rows};
      if (!f.exists(view_path(v.name, k))) f.create_rows_view(view_path(v.name, k), "/frames/" + v.name, k, 1, dims);
    }
  add_contact_views(f, from, to);
}

// Removes the views of frames from `frames` on (those a resume drops).
void drop_views_from(H5File& f, hsize_t frames) {
  if (!f.exists("/views")) return;
  for (const auto& name : f.list("/views"))
    for (const auto& k : f.list("/views/" + name))
      if (std::stoull(k) >= frames) f.remove("/views/" + name + "/" + k);
}

// Polygons [from, to) in XDMF's Mixed connectivity: each its type (3 polygon; 2 polyline, for a 2D facet's two
// ends, or every one of them when they are `open` lines), its corner count, its corners.
std::vector<std::int64_t> xdmf_mixed(const Polygons& p, std::size_t from, std::size_t to, bool open = false) {
  std::vector<std::int64_t> m;
  for (std::size_t k = from; k < to; ++k) {
    const std::int64_t n = p.start[k + 1] - p.start[k];
    m.insert(m.end(), {n >= 3 && !open ? 3 : 2, n});
    m.insert(m.end(), p.corner.begin() + p.start[k], p.corner.begin() + p.start[k + 1]);
  }
  return m;
}
}  // namespace

RunOutput::RunOutput(const std::string& path, const std::string& scene_text, const std::string& scene_file,
                     const SpecimenData& s)
    : file_(partial_path(path), H5File::Mode::Create), published_(false) {
  try {
    write_initial(scene_text, scene_file, s);
  } catch (...) {
    std::remove(file_.path().c_str());
    throw;
  }
}

void RunOutput::write_initial(const std::string& scene_text, const std::string& scene_file, const SpecimenData& s) {
  file_.set_attr("/", "format", std::string("mesocrack-1"));
  file_.set_attr("/", "dimension", static_cast<std::int64_t>(s.dimension));
  // Absolute, so that `run --resume OUT.h5` alone, from any folder, finds the files the scene names relative to it.
  const std::string where =
      scene_file.empty() ? scene_file : std::filesystem::absolute(scene_file).lexically_normal().string();
  file_.set_attr("/", "scene_file", where);
  file_.write_string("/scene", scene_text);
  const hsize_t n = s.radius.size();
  file_.write("/specimen/x", s.x, {n, static_cast<hsize_t>(s.dimension)});
  file_.write("/specimen/radius", s.radius, {n});
  file_.write("/specimen/phase", s.phase, {n});
  file_.write("/specimen/id", s.id, {n});
  std::vector<std::int64_t> vertex(n);  // each body a vertex of its own: XDMF's Polyvertex connectivity
  for (hsize_t k = 0; k < n; ++k) vertex[k] = static_cast<std::int64_t>(k);
  file_.write("/specimen/vertex", vertex, {n});
  file_.set_attr("/specimen", "phase_names", join(s.phase_names));
  for (const auto& [name, value] : s.facts) file_.set_attr("/specimen", name, value);
  // /specimen/outline_xy [M, 2], outline_start [K + 1]: polygon k is rows start[k]..start[k+1]
  if (!s.outlines.empty()) {
    std::vector<double> xy;
    std::vector<std::int64_t> start{0};
    for (const auto& o : s.outlines) {
      for (const auto& v : o) xy.insert(xy.end(), {v[0], v[1]});
      start.push_back(static_cast<std::int64_t>(xy.size() / 2));
    }
    file_.write("/specimen/outline_xy", xy, {xy.size() / 2, 2});
    file_.write("/specimen/outline_start", start, {start.size()});
  }
  file_.create_table("/frames/time", 0);
  file_.create_table("/frames/step", 0, true);
  for (const char* f : {"/frames/x", "/frames/v", "/frames/force"}) file_.create_table(f, n * s.dimension);
  if (!s.cells.empty()) write_cells(s);
  if (!s.fibres.empty()) write_fibres(s.fibres);
  set_status("running");
  flush();
}

// /specimen/cells (README.md, "Output"): the polygons as built, and what ParaView reads of them; the frames' tables
// of the cells' corners and of the contact facets' damage (none without a contact).
void RunOutput::write_cells(const SpecimenData& s) {
  const CellGeometry& c = s.cells;
  const auto d = static_cast<hsize_t>(s.dimension);
  const std::string g = "/specimen/cells/";
  file_.write(g + "corner", c.corner, {c.corner.size() / d, d});
  for (const auto& [name, p] : {std::pair{"facet", &c.facets}, std::pair{"face", &c.faces}}) {
    file_.write(g + name + "_start", p->start, {p->start.size()});
    file_.write(g + name + "_corner", p->corner, {p->corner.size()});
  }
  file_.write(g + "facet_a", c.facet_a, {c.facet_a.size()});
  file_.write(g + "facet_b", c.facet_b, {c.facet_b.size()});
  file_.set_attr("/specimen/cells", "contacts", static_cast<std::int64_t>(c.contacts));
  std::vector<std::int32_t> face_phase;
  for (const std::int64_t cell : c.face_cell) face_phase.push_back(s.phase.at(cell));
  file_.write(g + "face_cell", c.face_cell, {c.face_cell.size()});
  file_.write(g + "face_phase", face_phase, {face_phase.size()});
  const auto faces = xdmf_mixed(c.faces, 0, c.faces.size()), contacts = xdmf_mixed(c.facets, 0, c.contacts);
  file_.write(g + "xdmf_faces", faces, {faces.size()});
  file_.write(g + "xdmf_contacts", contacts, {contacts.size()});
  file_.create_table("/frames/cell_corner", c.corner.size());
  if (c.contacts > 0) file_.create_table("/frames/damage", c.contacts);
}

// /specimen/fibres (README.md, "Output"): the fibres as polylines, and the frames' tables of what each does.
void RunOutput::write_fibres(const FibreGeometry& f) {
  const std::string g = "/specimen/fibres/";
  file_.write(g + "point", f.point, {f.point.size() / 3, 3});
  file_.write(g + "line_start", f.lines.start, {f.lines.start.size()});
  file_.write(g + "line_point", f.lines.corner, {f.lines.corner.size()});
  file_.write(g + "family", f.family, {f.family.size()});
  file_.write(g + "crossings", f.crossings, {f.crossings.size()});
  const auto lines = xdmf_mixed(f.lines, 0, f.lines.size(), true);
  file_.write(g + "xdmf_lines", lines, {lines.size()});
  for (const char* t : {"/frames/fibre_state", "/frames/fibre_force", "/frames/fibre_slip"})
    file_.create_table(t, f.family.size());
}

namespace {
// The file to resume, or why there is none.
std::string existing(const std::string& path) {
  if (!std::filesystem::exists(path) && std::filesystem::exists(RunOutput::partial_path(path)))
    throw IoError(path + ": cannot open file: no such file; " + RunOutput::partial_path(path) +
                  " is a run that ended before its first complete flush (specimen, step 0): run it again with -o " +
                  path);
  return path;
}
}  // namespace

std::string RunOutput::stored_scene(const std::string& path) {
  return H5File(existing(path), H5File::Mode::ReadOnly).read_string("/scene");
}

RunOutput::RunOutput(const std::string& path) : file_(existing(path), H5File::Mode::ReadOnly) {
  if (!file_.has_attr("/", "format") || file_.attr_string("/", "format") != "mesocrack-1")
    throw IoError(path + ": not a mesocrack output file (no format attribute 'mesocrack-1')");
  if (file_.exists("/history")) names_ = file_.list("/history");
}

std::vector<std::string> RunOutput::files_written(const std::string& path) {
  const std::string xdmf = stem_path(path, ".xdmf"), csv = stem_path(path, "_history.csv");
  return {path, partial_path(path), xdmf, xdmf + ".tmp", csv, csv + ".tmp"};
}

RunOutput::~RunOutput() {
  if (!published_) std::remove(file_.path().c_str());
}

void RunOutput::publish() {
  flush();
  const std::string& partial = file_.path();
  file_.rename(partial.substr(0, partial.size() - std::string(".partial").size()));
  published_ = true;
  write_xdmf();
}

void RunOutput::create_histories(const std::vector<std::string>& names, const std::vector<std::string>& units) {
  names_ = names;
  std::string order;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string ds = "/history/" + names[i];
    if (!file_.exists(ds)) file_.create_table(ds, 0);
    file_.set_attr(ds, "unit", units[i]);
    order += (i ? ";" : "") + names[i];
  }
  file_.set_attr("/history", "order", order);  // the scene's order (HDF5 lists names sorted)
}

void RunOutput::append_history(const std::vector<std::vector<double>>& columns) {
  for (std::size_t i = 0; i < names_.size(); ++i)
    if (!columns[i].empty()) file_.append_rows("/history/" + names_[i], columns[i].data(), columns[i].size());
}

std::int64_t RunOutput::history_rows() const {
  return names_.empty() ? 0 : static_cast<std::int64_t>(file_.rows("/history/time"));
}

void RunOutput::append_frame(double time, std::int64_t step, const std::vector<double>& x, const std::vector<double>& v,
                             const std::vector<double>& force, const CellFrame& cells, const ContactFrame& contacts) {
  if (contacts.recorded) append_contacts(contacts);
  file_.append_rows("/frames/time", &time, 1);
  file_.append_rows("/frames/step", &step, 1);
  append_frame_row("/frames/x", x);
  append_frame_row("/frames/v", v);
  append_frame_row("/frames/force", force);
  if (file_.exists("/frames/cell_corner")) append_frame_row("/frames/cell_corner", cells.corner);
  if (file_.exists("/frames/damage")) append_frame_row("/frames/damage", cells.damage);
  if (file_.exists("/frames/fibre_state")) {
    append_frame_row("/frames/fibre_state", cells.fibre_state);
    append_frame_row("/frames/fibre_force", cells.fibre_force);
    append_frame_row("/frames/fibre_slip", cells.fibre_slip);
  }
  const hsize_t frame = file_.rows("/frames/time") - 1;
  add_views(file_, frame, frame + 1);
  if (published_) write_xdmf();
}

void RunOutput::append_contacts(const ContactFrame& c) {
  const auto d = static_cast<hsize_t>(file_.attr_int("/", "dimension"));
  if (!file_.exists("/contacts/frame_first")) {
    for (const ContactTable& t : kContactTables) {
      const std::string ds = std::string("/contacts/") + t.name;
      file_.create_table(ds, contact_width(t, d), t.integer);
      file_.set_attr(ds, "unit", std::string(t.unit));
    }
    file_.create_table("/contacts/frame_first", 0, true);
    file_.create_table("/contacts/frame_count", 0, true);
    // Frames already written (a resumed file of an older version) hold no contacts.
    const std::vector<std::int64_t> none(file_.rows("/frames/time"), 0);
    file_.append_rows("/contacts/frame_first", none.data(), none.size());
    file_.append_rows("/contacts/frame_count", none.data(), none.size());
  }
  const auto n = static_cast<hsize_t>(c.size());
  if (c.pair.size() != 2 * n || c.bonded.size() != n || c.shear_force.size() != n || c.branch.size() != d * n)
    throw std::invalid_argument(file_.path() + ":/contacts: a frame's contact columns differ in length");
  const auto first = static_cast<std::int64_t>(file_.rows("/contacts/pair")), count = static_cast<std::int64_t>(n);
  file_.append_rows("/contacts/frame_first", &first, 1);
  file_.append_rows("/contacts/frame_count", &count, 1);
  if (n == 0) return;
  file_.append_rows("/contacts/pair", c.pair.data(), n);
  file_.append_rows("/contacts/normal_force", c.normal_force.data(), n);
  file_.append_rows("/contacts/shear_force", c.shear_force.data(), n);
  file_.append_rows("/contacts/bonded", c.bonded.data(), n);
  file_.append_rows("/contacts/branch", c.branch.data(), n);
}

void RunOutput::append_frame_row(const std::string& ds, const std::vector<double>& row) {
  const auto width = file_.shape(ds).at(1);
  if (row.size() != width)
    throw std::invalid_argument(file_.path() + ":" + ds + ": a frame of " + std::to_string(row.size()) +
                                " values, the table's rows hold " + std::to_string(width));
  file_.append_rows(ds, row.data(), 1);
}

std::int64_t RunOutput::frame_rows() const { return static_cast<std::int64_t>(file_.rows("/frames/time")); }

void RunOutput::write_checkpoint(const Archive& a, std::int64_t step) {
  // Write into the older slot; the newer stays valid until this one is complete.
  std::string slot = "/checkpoint/a";
  auto valid = [&](const std::string& s) {
    return file_.exists(s) && file_.has_attr(s, "complete") && file_.attr_int(s, "complete") == 1;
  };
  if (valid("/checkpoint/a")) {
    const bool b_newer =
        valid("/checkpoint/b") && file_.attr_int("/checkpoint/b", "step") > file_.attr_int("/checkpoint/a", "step");
    slot = b_newer ? "/checkpoint/a" : "/checkpoint/b";
  }
  // Mark the slot incomplete before touching it, so a kill during the write cannot leave it looking valid.
  if (file_.exists(slot)) file_.set_attr(slot, "complete", static_cast<std::int64_t>(0));
  flush();
  for (const auto& [k, v] : a.reals) file_.write(slot + "/reals/" + k, v, {v.size()});
  for (const auto& [k, v] : a.bytes) file_.write(slot + "/bytes/" + k, v, {v.size()});
  file_.set_attr(slot, "step", step);
  flush();
  file_.set_attr(slot, "complete", static_cast<std::int64_t>(1));
  flush();
}

std::string RunOutput::newest_checkpoint() const {
  std::string best;
  std::int64_t best_step = -1;
  for (const char* s : {"/checkpoint/a", "/checkpoint/b"})
    if (file_.exists(s) && file_.has_attr(s, "complete") && file_.attr_int(s, "complete") == 1 &&
        file_.attr_int(s, "step") > best_step)
      best = s, best_step = file_.attr_int(s, "step");
  if (best.empty())
    throw IoError(file_.path() +
                  ": no complete checkpoint to resume from (a run writes one at step 0, then every "
                  "output.checkpoint_every steps, or every 60 s of wall time when that key is 0): the file is damaged "
                  "or was not written by `mesocrack run`");
  return best;
}

Archive RunOutput::read_checkpoint() const {
  const std::string best = newest_checkpoint();
  Archive a;
  if (file_.exists(best + "/reals"))
    for (const auto& k : file_.list(best + "/reals")) a.reals[k] = file_.read_doubles(best + "/reals/" + k);
  if (file_.exists(best + "/bytes"))
    for (const auto& k : file_.list(best + "/bytes")) a.bytes[k] = file_.read_bytes(best + "/bytes/" + k);
  return a;
}

namespace {
const char* const kCrackInts[] = {"step", "mode", "kind", "phase_a", "phase_b", "model", "id_a", "id_b"};
}

void RunOutput::create_crack_log(int dimension, const std::vector<std::string>& models) {
  if (file_.exists("/cracks")) return;  // resuming
  for (const char* n : kCrackInts) file_.create_table(std::string("/cracks/") + n, 0, true);
  file_.create_table("/cracks/time", 0);
  file_.create_table("/cracks/position", dimension);
  file_.create_table("/cracks/normal", dimension);
  file_.set_attr("/cracks", "models", join(models));
  file_.set_attr("/cracks", "modes", std::string("1=tensile,2=shear"));
  file_.set_attr("/cracks", "kinds", std::string("0=break,1=first yield"));
}

void RunOutput::append_cracks(const CrackRows& r) {
  if (r.size() == 0) return;
  const std::vector<std::int64_t>* ints[] = {&r.step,    &r.mode,  &r.kind, &r.phase_a,
                                             &r.phase_b, &r.model, &r.id_a, &r.id_b};
  for (int k = 0; k < 8; ++k) file_.append_rows(std::string("/cracks/") + kCrackInts[k], ints[k]->data(), r.size());
  file_.append_rows("/cracks/time", r.time.data(), r.size());
  file_.append_rows("/cracks/position", r.position.data(), r.size());
  file_.append_rows("/cracks/normal", r.normal.data(), r.size());
}

std::int64_t RunOutput::crack_rows() const {
  return file_.exists("/cracks/step") ? static_cast<std::int64_t>(file_.rows("/cracks/step")) : 0;
}

bool killed_run(const H5File& f) { return f.attr_string("/", "status") == "running"; }

void RunOutput::resume_at(std::int64_t history_rows, std::int64_t frame_rows, std::int64_t crack_rows) {
  if (killed_run(file_)) return rewrite_up_to(history_rows, frame_rows, crack_rows);
  file_.reopen(H5File::Mode::ReadWrite);
  if (file_.exists("/cracks"))
    for (const auto& n : file_.list("/cracks")) file_.truncate_rows("/cracks/" + n, crack_rows);
  for (const auto& n : names_) file_.truncate_rows("/history/" + n, history_rows);
  for (const auto& n : file_.list("/frames")) file_.truncate_rows("/frames/" + n, frame_rows);
  if (file_.exists("/contacts/frame_first")) {
    const hsize_t rows = contact_rows(file_, static_cast<hsize_t>(frame_rows));
    for (const auto& n : file_.list("/contacts"))
      file_.truncate_rows("/contacts/" + n, n.rfind("frame_", 0) == 0 ? static_cast<hsize_t>(frame_rows) : rows);
  }
  drop_views_from(file_, static_cast<hsize_t>(frame_rows));
  add_views(file_, 0, static_cast<hsize_t>(frame_rows));  // also those a file of an older version lacks
  write_xdmf();
  flush();
}

// The tables' rows up to the checkpoint, the checkpoint, and everything else as it is go to <path>.partial, which
// then replaces <path>. The other checkpoint slot is left behind: it is older, or was being written when the run
// was killed.
void RunOutput::rewrite_up_to(std::int64_t history_rows, std::int64_t frame_rows, std::int64_t crack_rows) {
  const std::string path = file_.path(), checkpoint = newest_checkpoint();
  H5File fresh(partial_path(path), H5File::Mode::Create);
  try {
    fresh.copy_attrs(file_, "/");
    for (const auto& top : file_.list("/")) {
      const std::string g = "/" + top;
      if (top == "history" || top == "frames" || top == "cracks" || top == "contacts") {
        const auto rows = static_cast<hsize_t>(top == "history"  ? history_rows
                                               : top == "frames" ? frame_rows
                                                                 : crack_rows);
        const hsize_t contacts = top == "contacts" ? contact_rows(file_, static_cast<hsize_t>(frame_rows)) : 0;
        fresh.create_group(g);
        fresh.copy_attrs(file_, g);
        for (const auto& n : file_.list(g))
          fresh.copy_rows(file_, g + "/" + n,
                          top != "contacts"           ? rows
                          : n.rfind("frame_", 0) == 0 ? static_cast<hsize_t>(frame_rows)
                                                      : contacts);
      } else if (top == "checkpoint") {
        fresh.copy_object(file_, checkpoint);
      } else if (top == "views") {
        continue;  // made afresh below, for the frames kept
      } else {
        fresh.copy_object(file_, g);
      }
    }
    add_views(fresh, 0, static_cast<hsize_t>(frame_rows));
    fresh.flush();
    fresh.rename(path);
  } catch (...) {
    std::remove(fresh.path().c_str());
    throw;
  }
  file_ = std::move(fresh);
  write_xdmf();
}

void RunOutput::set_status(const std::string& status, const std::string& message) {
  file_.set_attr("/", "status", status);
  file_.set_attr("/", "status_message", message);
}

void RunOutput::end_with_status(const std::string& status, const std::string& message) {
  flush();
  set_status(status, message);
  flush();
}

void RunOutput::set_xy_plots(const std::string& pairs) { file_.set_attr("/history", "xy_plots", pairs); }

void RunOutput::flush() { file_.flush(); }

void RunOutput::write_csv() const {
  std::ostringstream out;
  std::vector<std::vector<double>> cols;
  for (std::size_t i = 0; i < names_.size(); ++i) {
    out << (i ? "," : "") << names_[i] << " [" << file_.attr_string("/history/" + names_[i], "unit") << "]";
    cols.push_back(file_.read_doubles("/history/" + names_[i]));
  }
  out << "\n" << std::setprecision(17);
  const std::size_t rows = cols.empty() ? 0 : cols[0].size();
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t i = 0; i < cols.size(); ++i) out << (i ? "," : "") << cols[i][r];
    out << "\n";
  }
  write_atomically(stem_path(file_.path(), "_history.csv"), out.str());
}

// One temporal collection of a grid per frame (io/xdmf_sidecar.hpp), written beside the file.
void RunOutput::write_xdmf() const { write_atomically(stem_path(file_.path(), ".xdmf"), xdmf_sidecar(file_)); }

}  // namespace mc
