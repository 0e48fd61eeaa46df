#include "io/xdmf_sidecar.hpp"

#include <filesystem>
#include <iomanip>
#include <sstream>

namespace mc {

namespace {

// A whole dataset of `size` values (and `width` per row, if more than 1).
std::string dataset(const std::string& h5, const std::string& ds, hsize_t size, const char* type, int precision,
                    hsize_t width = 1) {
  std::ostringstream s;
  s << "<DataItem Dimensions=\"" << size;
  if (width > 1) s << " " << width;
  s << "\" NumberType=\"" << type << "\" Precision=\"" << precision << "\" Format=\"HDF\">" << h5 << ":" << ds
    << "</DataItem>";
  return s.str();
}

// The sizes of a specimen of cells' datasets (README.md, "Output"), as the XDMF sidecar states them.
struct CellSizes {
  hsize_t corners, faces, faces_mixed, contacts, contacts_mixed;
};

CellSizes cell_sizes(const H5File& f) {
  const std::string g = "/specimen/cells/";
  return {f.rows(g + "corner"), f.rows(g + "face_cell"), f.rows(g + "xdmf_faces"),
          f.exists("/frames/damage") ? f.shape("/frames/damage").at(1) : 0, f.rows(g + "xdmf_contacts")};
}

// Frame f of the output file `h5`, which holds `frames`, of a specimen in `d` dimensions.
struct XdmfFrame {
  const std::string& h5;
  int d;
  hsize_t f, frames;
  double time;
  // The frame's view `name` (frame_views): `rows` of `width` values.
  std::string view(const std::string& name, hsize_t rows, hsize_t width = 1) const {
    return dataset(h5, view_path(name, f), rows, "Float", 8, width);
  }
  std::string geometry() const { return d == 2 ? "XY" : "XYZ"; }
  std::string head(const std::string& name) const {
    std::ostringstream s;
    s << std::setprecision(17) << "   <Grid Name=\"" << name << f << "\" GridType=\"Uniform\">\n    <Time Value=\""
      << time << "\"/>\n";
    return s.str();
  }
};

// The bodies (particles, or the cells' nodes) as points, each a vertex (a file of an older version lists no vertices:
// points without cells), with the phases' names (the integers of `phase`, in order) as information.
std::string points_grid(const XdmfFrame& fr, const std::string& name, hsize_t n, bool vertices,
                        const std::string& phase_names) {
  std::ostringstream x;
  std::string escaped;  // the names as an XML attribute's value
  for (const char c : phase_names)
    escaped += c == '&' ? "&amp;" : c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '"' ? "&quot;" : std::string(1, c);
  x << fr.head(name) << "    <Information Name=\"phase_names\" Value=\"" << escaped << "\"/>\n";
  if (vertices)
    x << "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n << "\" NodesPerElement=\"1\">"
      << dataset(fr.h5, "/specimen/vertex", n, "Int", 8) << "</Topology>\n";
  else
    x << "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n << "\"/>\n";
  x << "    <Geometry GeometryType=\"" << fr.geometry() << "\">" << fr.view("x", n, fr.d) << "</Geometry>\n"
    << "    <Attribute Name=\"radius\" AttributeType=\"Scalar\" Center=\"Node\">"
    << dataset(fr.h5, "/specimen/radius", n, "Float", 8) << "</Attribute>\n"
    << "    <Attribute Name=\"phase\" AttributeType=\"Scalar\" Center=\"Node\">"
    << dataset(fr.h5, "/specimen/phase", n, "Int", 4) << "</Attribute>\n"
    << "    <Attribute Name=\"id\" AttributeType=\"Scalar\" Center=\"Node\">"
    << dataset(fr.h5, "/specimen/id", n, "Int", 8) << "</Attribute>\n";
  // The out-of-balance force: the resultant of each body's contacts, gravity and damping, not a contact force.
  // 2D vectors have two components, which every reader takes.
  for (const auto& [q, shown] : {std::pair{"v", "velocity"}, std::pair{"force", "out_of_balance_force"}})
    x << "    <Attribute Name=\"" << shown << "\" AttributeType=\"Vector\" Center=\"Node\">"
      << fr.view(q, n, fr.d) << "</Attribute>\n";
  x << "   </Grid>\n";
  return x.str();
}

// The frame's contacts between particles as lines between their centres, by normal force (positive in compression),
// shear force, bond and branch vector: ParaView's force chains (a Tube filter scaled by the normal force).
std::string contacts_grid(const XdmfFrame& fr, hsize_t n, hsize_t contacts) {
  std::ostringstream x;
  x << fr.head("contacts") << "    <Topology TopologyType=\"Polyline\" NumberOfElements=\"" << contacts
    << "\" NodesPerElement=\"2\">" << dataset(fr.h5, view_path("contact_pair", fr.f), contacts, "Int", 8, 2)
    << "</Topology>\n"
    << "    <Geometry GeometryType=\"" << fr.geometry() << "\">" << fr.view("x", n, fr.d) << "</Geometry>\n";
  for (const char* a : {"normal_force", "shear_force"})
    x << "    <Attribute Name=\"" << a << "\" AttributeType=\"Scalar\" Center=\"Cell\">"
      << fr.view(std::string("contact_") + a, contacts) << "</Attribute>\n";
  x << "    <Attribute Name=\"bonded\" AttributeType=\"Scalar\" Center=\"Cell\">"
    << dataset(fr.h5, view_path("contact_bonded", fr.f), contacts, "Int", 8) << "</Attribute>\n"
    << "    <Attribute Name=\"branch\" AttributeType=\"Vector\" Center=\"Cell\">"
    << fr.view("contact_branch", contacts, fr.d) << "</Attribute>\n"
    << "   </Grid>\n";
  return x.str();
}

// The cells' surfaces where the frame's corners are, by cell and phase.
std::string cells_grid(const XdmfFrame& fr, const CellSizes& c) {
  const std::string g = "/specimen/cells/";
  std::ostringstream x;
  x << fr.head("cells") << "    <Topology TopologyType=\"Mixed\" NumberOfElements=\"" << c.faces << "\">"
    << dataset(fr.h5, g + "xdmf_faces", c.faces_mixed, "Int", 8) << "</Topology>\n"
    << "    <Geometry GeometryType=\"" << fr.geometry() << "\">" << fr.view("cell_corner", c.corners, fr.d)
    << "</Geometry>\n"
    << "    <Attribute Name=\"cell\" AttributeType=\"Scalar\" Center=\"Cell\">"
    << dataset(fr.h5, g + "face_cell", c.faces, "Int", 8) << "</Attribute>\n"
    << "    <Attribute Name=\"phase\" AttributeType=\"Scalar\" Center=\"Cell\">"
    << dataset(fr.h5, g + "face_phase", c.faces, "Int", 4) << "</Attribute>\n"
    << "   </Grid>\n";
  return x.str();
}

// The contact facets where they were built, by their damage in the frame.
std::string facets_grid(const XdmfFrame& fr, const CellSizes& c) {
  const std::string g = "/specimen/cells/";
  std::ostringstream x;
  x << fr.head("facets") << "    <Topology TopologyType=\"Mixed\" NumberOfElements=\"" << c.contacts << "\">"
    << dataset(fr.h5, g + "xdmf_contacts", c.contacts_mixed, "Int", 8) << "</Topology>\n"
    << "    <Geometry GeometryType=\"" << fr.geometry() << "\">"
    << dataset(fr.h5, g + "corner", c.corners, "Float", 8, fr.d) << "</Geometry>\n"
    << "    <Attribute Name=\"damage\" AttributeType=\"Scalar\" Center=\"Cell\">"
    << fr.view("damage", c.contacts) << "</Attribute>\n"
    << "   </Grid>\n";
  return x.str();
}

// The fibres where they were placed, each a polyline through its crossings, by family, crossing count, and its state,
// force and slip in the frame.
std::string fibres_grid(const XdmfFrame& fr, const H5File& f) {
  const std::string g = "/specimen/fibres/";
  const hsize_t n = f.rows(g + "family");
  std::ostringstream x;
  x << fr.head("fibres") << "    <Topology TopologyType=\"Mixed\" NumberOfElements=\"" << n << "\">"
    << dataset(fr.h5, g + "xdmf_lines", f.rows(g + "xdmf_lines"), "Int", 8) << "</Topology>\n"
    << "    <Geometry GeometryType=\"XYZ\">" << dataset(fr.h5, g + "point", f.rows(g + "point"), "Float", 8, 3)
    << "</Geometry>\n";
  for (const char* a : {"family", "crossings"})
    x << "    <Attribute Name=\"" << a << "\" AttributeType=\"Scalar\" Center=\"Cell\">"
      << dataset(fr.h5, g + a, n, "Int", 4) << "</Attribute>\n";
  for (const char* a : {"state", "force", "slip"})
    x << "    <Attribute Name=\"" << a << "\" AttributeType=\"Scalar\" Center=\"Cell\">"
      << fr.view(std::string("fibre_") + a, n) << "</Attribute>\n";
  x << "   </Grid>\n";
  return x.str();
}

}  // namespace

// One temporal collection of a grid per frame: the particles as points, and their contacts as lines ("contacts")
// when the frames record them; or three, the cells' nodes as points, the cells and the contact facets, which
// ParaView shows as the blocks "nodes", "cells" and "facets", and a fourth of the fibres ("fibres") when the
// specimen has them.
std::string xdmf_sidecar(const H5File& file) {
  const int d = static_cast<int>(file.attr_int("/", "dimension"));
  const auto n = file.rows("/specimen/radius");
  const auto frames = file.rows("/frames/time");
  const auto times = file.read_doubles("/frames/time");
  const std::string h5 = std::filesystem::path(file.path()).filename().string();
  std::ostringstream x;
  x << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"2.0\">\n <Domain>\n";
  // `shown(f)`: frame f has a grid of this collection (a frame without contacts has none of them).
  const auto collection = [&](const std::string& name, const auto& grid, const auto& shown) {
    x << "  <Grid Name=\"" << name << "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (hsize_t f = 0; f < frames; ++f)
      if (shown(f)) x << grid(XdmfFrame{h5, d, f, frames, times[f]});
    x << "  </Grid>\n";
  };
  const auto every = [](hsize_t) { return true; };
  const bool vertices = file.exists("/specimen/vertex");
  const std::string phases =
      file.has_attr("/specimen", "phase_names") ? file.attr_string("/specimen", "phase_names") : "";
  if (!file.exists("/frames/cell_corner")) {
    collection("frames", [&](const XdmfFrame& fr) { return points_grid(fr, "frame", n, vertices, phases); }, every);
    if (file.exists("/contacts/frame_count")) {
      const auto count = file.read_ints("/contacts/frame_count");
      const auto has = [&](hsize_t f) { return f < count.size() && count[f] > 0; };
      collection(
          "contacts",
          [&](const XdmfFrame& fr) { return contacts_grid(fr, n, static_cast<hsize_t>(count[fr.f])); }, has);
    }
  } else {
    const CellSizes sizes = cell_sizes(file);
    collection("nodes", [&](const XdmfFrame& fr) { return points_grid(fr, "nodes", n, vertices, phases); }, every);
    collection("cells", [&](const XdmfFrame& fr) { return cells_grid(fr, sizes); }, every);
    if (sizes.contacts > 0)
      collection("facets", [&](const XdmfFrame& fr) { return facets_grid(fr, sizes); }, every);
    if (file.exists("/frames/fibre_state"))
      collection("fibres", [&](const XdmfFrame& fr) { return fibres_grid(fr, file); }, every);
  }
  x << " </Domain>\n</Xdmf>\n";
  return x.str();
}


}  // namespace mc
