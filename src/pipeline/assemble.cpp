#include "assemble.hpp"

#include <algorithm>

#include "mixmesh/core/error.hpp"
#include "mixmesh/mesh/face_connectivity.hpp"

namespace mixmesh::pipeline_detail {

OuterLayer outer_layer(const MixedMesh& layers, const std::vector<std::string>& markers) {
  std::vector<int> wanted(layers.marker_names.size(), 0);
  for (const std::string& marker : markers) {
    const int id = layers.find_marker(marker);
    if (id >= 0) wanted[static_cast<std::size_t>(id)] = 1;
  }
  std::vector<std::array<Index, 4>> hull_keys;
  for (FaceType type : all_face_types)
    for (std::size_t face = 0; face < layers.face_count(type); ++face)
      if (wanted[static_cast<std::size_t>(layers.faces(type).markers[face])])
        hull_keys.push_back(sorted_face_key(layers.face(type, face), node_count(type)));
  std::sort(hull_keys.begin(), hull_keys.end());

  OuterLayer layer;
  for (const CellFace& face : match_faces(layers).boundary) {
    Index nodes[4];
    const int count = face_nodes(layers, face, nodes);
    if (!std::binary_search(hull_keys.begin(), hull_keys.end(), sorted_face_key(nodes, count))) continue;
    const OuterCell outer{static_cast<std::size_t>(face.cell), face.local_face};
    if (face.type == CellType::hexahedron)
      layer.hexahedra.push_back(outer);
    else if (face.type == CellType::prism)
      layer.prisms.push_back(outer);
    else
      throw Error("generate: a " + std::string(name(face.type)) +
                  " of the boundary layers faces the far field");
  }
  return layer;
}

MixedMesh assemble(const MixedMesh& layers, const std::string& hull_marker, const FarFieldResult& farfield,
                   const std::vector<std::string>& wall_markers, bool merge_wall_markers) {
  MixedMesh mesh;
  // The far field's points start with the layers' points, in order.
  if (farfield.input_point_count != layers.points.size())
    throw Error("generate: the far field was built on " + std::to_string(farfield.input_point_count) +
                " points, the layers have " + std::to_string(layers.points.size()));
  mesh.points = farfield.mesh.points;
  for (CellType type : all_cell_types) {
    mesh.block(type) = layers.block(type);
    const CellBlock& added = farfield.mesh.block(type);
    mesh.block(type).nodes.insert(mesh.block(type).nodes.end(), added.nodes.begin(), added.nodes.end());
    mesh.block(type).regions.insert(mesh.block(type).regions.end(), added.regions.begin(),
                                    added.regions.end());
  }
  auto marker_for = [&](const std::string& original) {
    const bool wall = std::find(wall_markers.begin(), wall_markers.end(), original) != wall_markers.end();
    return mesh.marker(merge_wall_markers && wall ? std::string("wall") : original);
  };
  for (FaceType type : all_face_types) {
    for (std::size_t face = 0; face < layers.face_count(type); ++face) {
      const std::string& marker =
          layers.marker_names[static_cast<std::size_t>(layers.faces(type).markers[face])];
      if (marker == hull_marker) continue;  // interior now: tetrahedra on the other side
      mesh.add_face(type, layers.face(type, face), marker_for(marker));
    }
    for (std::size_t face = 0; face < farfield.mesh.face_count(type); ++face) {
      const int id = farfield.mesh.faces(type).markers[face];
      mesh.add_face(type, farfield.mesh.face(type, face),
                    marker_for(farfield.mesh.marker_names[static_cast<std::size_t>(id)]));
    }
  }
  return mesh;
}

}  // namespace mixmesh::pipeline_detail
