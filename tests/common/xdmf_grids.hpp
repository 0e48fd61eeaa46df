// The XDMF sidecar of an output file read against the file (README, "Output"): each uniform grid's topology,
// geometry and attributes as large as the HDF5 datasets they name, for the tests of the rigid cells' and the fibres'
// output.
#pragma once
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "io/h5_file.hpp"
#include "tests/common/cli_harness.hpp"

// Test-only, with internal linkage in each test file that includes it, as cli_harness.hpp.
namespace {

std::vector<hsize_t> numbers(const std::string& text) {
  std::vector<hsize_t> v;
  std::istringstream in(text);
  for (hsize_t x; in >> x;) v.push_back(x);
  return v;
}

hsize_t product(const std::vector<hsize_t>& v) {
  hsize_t p = 1;
  for (hsize_t x : v) p *= x;
  return p;
}

// What one element (Topology, Geometry, Attribute) of a uniform grid in the sidecar reads: how many rows and values
// it gives, checked on the way against the datasets it names.
struct XdmfData {
  hsize_t rows = 0, values = 0;
  std::string dataset;  // the HDF5 dataset read whole (a frame's row: its view, /views/<name>/<frame>)
};

XdmfData read_data(const std::string& line, const mc::H5File& f) {
  static const std::regex hdf(R"re(<DataItem Dimensions="([0-9 ]+)"[^>]*Format="HDF">[^:<]*:([^<]+)</DataItem>)re");
  std::smatch m;
  REQUIRE_MESSAGE(std::regex_search(line, m, hdf), line);
  const std::vector<hsize_t> dims = numbers(m[1]);
  const std::string dataset = m[2];
  CAPTURE(dataset);
  REQUIRE(f.exists(dataset));
  CHECK(dims == f.shape(dataset));  // every dataset as large as the sidecar says (a frame's view as its row's values)
  return {dims[0], product(dims), dataset};
}

// Each uniform grid of the sidecar (its lines from `<Grid ... GridType="Uniform">` to `</Grid>`) is consistent with
// the file: the topology's elements (a Mixed one's walked through its connectivity) use the geometry's points, and
// each attribute has one value per element (Center="Cell") or point (Center="Node"). Returns the grids' names.
std::vector<std::string> check_uniform_grids(const std::string& xdmf, const mc::H5File& f) {
  std::vector<std::string> names;
  std::istringstream lines(xdmf);
  std::vector<std::string> grid;
  for (std::string line; std::getline(lines, line);) {
    if (line.find("GridType=\"Uniform\"") != std::string::npos)
      grid = {line};
    else if (!grid.empty() && line.find("</Grid>") == std::string::npos)
      grid.push_back(line);
    if (grid.empty() || line.find("</Grid>") == std::string::npos) continue;
    CAPTURE(grid[0]);
    names.push_back(grid[0].substr(grid[0].find("Name=\"") + 6, grid[0].find("\" ") - grid[0].find("Name=\"") - 6));
    const auto find = [&](const std::string& tag) {
      std::vector<std::string> found;
      for (const auto& l : grid)
        if (l.find("<" + tag) != std::string::npos) found.push_back(l);
      return found;
    };
    REQUIRE(find("Topology").size() == 1);
    REQUIRE(find("Geometry").size() == 1);
    const std::string topology = find("Topology")[0];
    const hsize_t elements =
        numbers(std::regex_replace(topology, std::regex(R"re(.*NumberOfElements="([0-9]+)".*)re"), "$1"))[0];
    const XdmfData points = read_data(find("Geometry")[0], f);
    if (topology.find("Mixed") != std::string::npos) {
      const XdmfData connectivity = read_data(topology, f);
      const auto mixed = f.read_ints(connectivity.dataset);
      hsize_t walked = 0;
      std::size_t k = 0;
      for (; k < mixed.size(); k += 2 + mixed[k + 1], ++walked) {
        // polygons; polylines: a 2D facet's two ends, a fibre's ends and crossings
        CHECK((mixed[k] == 3 ? mixed[k + 1] >= 3 : mixed[k] == 2 && mixed[k + 1] >= 2));
        for (std::int64_t i = 0; i < mixed[k + 1]; ++i) CHECK(static_cast<hsize_t>(mixed[k + 2 + i]) < points.rows);
      }
      CHECK(k == mixed.size());
      CHECK(walked == elements);
    } else {
      CHECK(topology.find("Polyvertex") != std::string::npos);
      CHECK(elements == points.rows);
    }
    for (const auto& attribute : find("Attribute")) {
      CAPTURE(attribute);
      const XdmfData a = read_data(attribute, f);
      const bool cell = attribute.find("Center=\"Cell\"") != std::string::npos;
      CHECK(a.rows == (cell ? elements : points.rows));
    }
    grid.clear();
  }
  return names;
}

}  // namespace
