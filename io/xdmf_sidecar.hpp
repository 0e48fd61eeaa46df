// The XDMF sidecar of a run's HDF5 file (README.md, "Output"): what ParaView reads to show the frames, one
// temporal collection per kind of body (particles and their contacts; or the cells' nodes, the cells, the contact
// facets and the fibres), each a grid per frame over the file's datasets and its /views.
#pragma once
#include <string>

#include "io/h5_file.hpp"

namespace mc {

// The path of frame `frame`'s view `name` of a frame dataset (its rows of that frame).
inline std::string view_path(const std::string& name, hsize_t frame) {
  return "/views/" + name + "/" + std::to_string(frame);
}

// The sidecar's text for the file f, whose datasets it names by the file's name alone (the two lie side by side).
std::string xdmf_sidecar(const H5File& f);

}  // namespace mc
