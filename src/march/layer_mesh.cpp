#include "layer_mesh.hpp"

namespace mixmesh::march_detail {

namespace {

Index column_point(const BoundaryLayer& result, int column, int layer) {
  return result.column_points[static_cast<std::size_t>(column)][static_cast<std::size_t>(layer)];
}

// The side face over front edge corner -> corner + 1 of `face` in cell layer
// `layer`, outward from that cell: (u_k, v_k, v_k+1, u_k+1).
std::array<Index, 4> side_face(const Front& front, const BoundaryLayer& result, int face, int corner,
                               int layer) {
  const FrontFace& f = front.faces[static_cast<std::size_t>(face)];
  const int u = f.columns[static_cast<std::size_t>(corner)];
  const int v = f.columns[static_cast<std::size_t>((corner + 1) % f.corner_count)];
  return {column_point(result, u, layer), column_point(result, v, layer), column_point(result, v, layer + 1),
          column_point(result, u, layer + 1)};
}

}  // namespace

void add_swept_cell(const Front& front, int face, int layer, BoundaryLayer& result) {
  const FrontFace& f = front.faces[static_cast<std::size_t>(face)];
  auto at = [&](int k, int level) {
    return column_point(result, f.columns[static_cast<std::size_t>(k)], level);
  };
  if (f.corner_count == 4) {
    const std::array<Index, 8> nodes{at(0, layer),     at(1, layer),     at(2, layer),     at(3, layer),
                                     at(0, layer + 1), at(1, layer + 1), at(2, layer + 1), at(3, layer + 1)};
    result.mesh.add_cell(CellType::hexahedron, nodes.data(), f.patch);
    result.hexahedron_face.push_back(face);
    result.hexahedron_layer.push_back(layer);
    return;
  }
  // VTK wedge: bottom (a, c, b) so that its right-hand normal points away from the top.
  const std::array<Index, 6> nodes{at(0, layer),     at(2, layer),     at(1, layer),
                                   at(0, layer + 1), at(2, layer + 1), at(1, layer + 1)};
  result.mesh.add_cell(CellType::prism, nodes.data(), f.patch);
  result.prism_face.push_back(face);
  result.prism_layer.push_back(layer);
}

void add_boundary_faces(const Front& front, const MarchOptions& options, BoundaryLayer& result) {
  MixedMesh& mesh = result.mesh;
  const int hull = mesh.marker(options.outer_hull_marker);
  for (std::size_t face = 0; face < front.faces.size(); ++face) {
    const FrontFace& f = front.faces[face];
    const int layers = result.face_layers[face];
    if (layers == 0) continue;
    std::array<Index, 4> bottom{}, top{};
    for (int k = 0; k < f.corner_count; ++k) {
      // Outward from the cell: the wall face runs against the front's winding.
      bottom[static_cast<std::size_t>(k)] =
          column_point(result, f.columns[static_cast<std::size_t>(f.corner_count - 1 - k)], 0);
      top[static_cast<std::size_t>(k)] = column_point(result, f.columns[static_cast<std::size_t>(k)], layers);
    }
    const FaceType type = f.corner_count == 4 ? FaceType::quad : FaceType::triangle;
    if (f.wall)
      mesh.add_face(type, bottom.data(), mesh.marker(front.patch_names[static_cast<std::size_t>(f.patch)]));
    mesh.add_face(type, top.data(), hull);
  }
  // Sides along free edges of the front.
  for (const FreeEdge& edge : front.free_edges) {
    const FrontFace& f = front.faces[static_cast<std::size_t>(edge.face)];
    const int u = f.columns[static_cast<std::size_t>(edge.corner)];
    const int v = f.columns[static_cast<std::size_t>((edge.corner + 1) % f.corner_count)];
    const bool symmetry =
        front.on_symmetry[static_cast<std::size_t>(u)] && front.on_symmetry[static_cast<std::size_t>(v)];
    const int marker = mesh.marker(symmetry ? options.symmetry_marker : options.hull_side_marker);
    for (int layer = 0; layer < result.face_layers[static_cast<std::size_t>(edge.face)]; ++layer) {
      const auto nodes = side_face(front, result, edge.face, edge.corner, layer);
      mesh.add_face(FaceType::quad, nodes.data(), marker);
    }
  }
  // Sides of a column standing above its stopped neighbour belong to the hull.
  for (const SharedEdge& edge : front.shared_edges) {
    const int first = result.face_layers[static_cast<std::size_t>(edge.faces[0])];
    const int second = result.face_layers[static_cast<std::size_t>(edge.faces[1])];
    if (first == second) continue;
    const int taller = first > second ? 0 : 1;
    for (int layer = std::min(first, second); layer < std::max(first, second); ++layer) {
      const auto nodes = side_face(front, result, edge.faces[static_cast<std::size_t>(taller)],
                                   edge.corners[static_cast<std::size_t>(taller)], layer);
      mesh.add_face(FaceType::quad, nodes.data(), hull);
    }
  }
}

}  // namespace mixmesh::march_detail
