#include "io/file_access.hpp"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>

#include "mixmesh/core/error.hpp"

namespace mixmesh::io_detail {

std::string read_file(const std::filesystem::path& path) {
  std::error_code code;
  if (std::filesystem::is_directory(path, code))
    throw file_error(path.string(), 0, "is a directory, not a mesh file");
  std::ifstream stream(path, std::ios::binary);
  if (!stream) throw file_error(path.string(), 0, std::string("cannot open: ") + std::strerror(errno));
  stream.seekg(0, std::ios::end);
  const std::streamoff size = stream.tellg();
  if (size < 0) throw file_error(path.string(), 0, "cannot determine the file size");
  std::string contents(static_cast<std::size_t>(size), '\0');
  stream.seekg(0, std::ios::beg);
  stream.read(contents.data(), size);
  if (!stream) throw file_error(path.string(), 0, "read failed");
  return contents;
}

void write_file(const std::filesystem::path& path, std::string_view contents) {
  std::ofstream stream(path, std::ios::binary | std::ios::trunc);
  if (!stream) throw file_error(path.string(), 0, std::string("cannot create: ") + std::strerror(errno));
  stream.write(contents.data(), static_cast<std::streamsize>(contents.size()));
  stream.close();
  if (!stream) throw file_error(path.string(), 0, "write failed (disk full?)");
}

void check_writable(const MixedMesh& mesh, const std::filesystem::path& path) {
  const auto point_count = static_cast<Index>(mesh.points.size());
  auto check_nodes = [&](const std::vector<Index>& nodes, std::string_view what) {
    for (std::size_t slot = 0; slot < nodes.size(); ++slot)
      if (nodes[slot] < 0 || nodes[slot] >= point_count)
        throw Error(path.string() + ": cannot write: " + std::string(what) + " node " +
                    std::to_string(nodes[slot]) + " out of range (" + std::to_string(point_count) +
                    " points)");
  };
  auto check_markers = [&](const std::vector<int>& markers, std::string_view what) {
    for (int marker : markers)
      if (marker < 0 || static_cast<std::size_t>(marker) >= mesh.marker_names.size())
        throw Error(path.string() + ": cannot write: " + std::string(what) + " marker id " +
                    std::to_string(marker) + " has no name (" + std::to_string(mesh.marker_names.size()) +
                    " marker names)");
  };
  for (CellType type : all_cell_types) check_nodes(mesh.block(type).nodes, name(type));
  for (FaceType type : all_face_types) {
    check_nodes(mesh.faces(type).nodes, "boundary face");
    check_markers(mesh.faces(type).markers, "boundary face");
    check_nodes(mesh.planar_cells[static_cast<std::size_t>(index(type))].nodes, "planar cell");
  }
  check_nodes(mesh.boundary_edges.nodes, "boundary edge");
  check_markers(mesh.boundary_edges.markers, "boundary edge");
  for (std::size_t point = 0; point < mesh.points.size(); ++point)
    if (!mesh.points[point].allFinite())
      throw Error(path.string() + ": cannot write: point " + std::to_string(point) + " is not finite");
}

void append_real(std::string& out, double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

void append_integer(std::string& out, long long value) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

}  // namespace mixmesh::io_detail
