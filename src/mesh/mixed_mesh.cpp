#include "mixmesh/mesh/mixed_mesh.hpp"

#include <algorithm>
#include <sstream>

namespace mixmesh {

std::size_t MixedMesh::cell_count() const {
  std::size_t count = 0;
  for (CellType type : all_cell_types) count += cell_count(type);
  return count;
}

void MixedMesh::add_cell(CellType type, const Index* nodes, int region) {
  CellBlock& target = block(type);
  target.nodes.insert(target.nodes.end(), nodes, nodes + node_count(type));
  target.regions.push_back(region);
}

void MixedMesh::add_face(FaceType type, const Index* nodes, int marker_id) {
  FaceBlock& target = faces(type);
  target.nodes.insert(target.nodes.end(), nodes, nodes + node_count(type));
  target.markers.push_back(marker_id);
}

int MixedMesh::marker(const std::string& marker_name) {
  const int found = find_marker(marker_name);
  if (found >= 0) return found;
  marker_names.push_back(marker_name);
  return static_cast<int>(marker_names.size()) - 1;
}

int MixedMesh::find_marker(const std::string& marker_name) const {
  const auto found = std::find(marker_names.begin(), marker_names.end(), marker_name);
  return found == marker_names.end() ? -1 : static_cast<int>(found - marker_names.begin());
}

std::vector<Index> compact_points(MixedMesh& mesh) {
  std::vector<Index> renumber(mesh.points.size(), -1);
  auto mark = [&](const std::vector<Index>& nodes) {
    for (Index node : nodes) renumber[static_cast<std::size_t>(node)] = 0;
  };
  for (const CellBlock& cells : mesh.cells) mark(cells.nodes);
  for (const FaceBlock& faces : mesh.boundary) mark(faces.nodes);
  for (const FaceBlock& faces : mesh.planar_cells) mark(faces.nodes);
  mark(mesh.boundary_edges.nodes);

  Index next = 0;
  for (std::size_t point = 0; point < mesh.points.size(); ++point) {
    if (renumber[point] < 0) continue;
    mesh.points[static_cast<std::size_t>(next)] = mesh.points[point];
    renumber[point] = next++;
  }
  mesh.points.resize(static_cast<std::size_t>(next));

  auto apply = [&](std::vector<Index>& nodes) {
    for (Index& node : nodes) node = renumber[static_cast<std::size_t>(node)];
  };
  for (CellBlock& cells : mesh.cells) apply(cells.nodes);
  for (FaceBlock& faces : mesh.boundary) apply(faces.nodes);
  for (FaceBlock& faces : mesh.planar_cells) apply(faces.nodes);
  apply(mesh.boundary_edges.nodes);
  return renumber;
}

std::string point_text(const Vector3& point) {
  std::ostringstream text;
  text << "(" << point.x() << ", " << point.y() << ", " << point.z() << ")";
  return text.str();
}

}  // namespace mixmesh
