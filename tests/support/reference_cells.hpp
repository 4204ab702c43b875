// Hand-built reference cells and meshes for the unit tests: one cell of each type
// with positive volume in VTK order, and a small mesh holding all four types.
#pragma once

#include <utility>

#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/mesh/face_connectivity.hpp"
#include "mixmesh/mesh/mixed_mesh.hpp"

namespace mixmesh::reference {

// A single cell of the given type on the unit cube / unit triangle, volume > 0.
inline MixedMesh single_cell(CellType type) {
  MixedMesh mesh;
  switch (type) {
    case CellType::tetrahedron:
      mesh.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
      break;
    case CellType::pyramid:
      mesh.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 1}};
      break;
    case CellType::prism:  // VTK wedge: 0-1-2 clockwise seen from the top 3-4-5
      mesh.points = {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}, {0, 1, 1}, {1, 0, 1}};
      break;
    case CellType::hexahedron:
      mesh.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
      break;
  }
  std::vector<Index> nodes(static_cast<std::size_t>(node_count(type)));
  for (std::size_t local = 0; local < nodes.size(); ++local) nodes[local] = static_cast<Index>(local);
  mesh.add_cell(type, nodes.data());
  return mesh;
}

// Puts the nodes of a cell into positive orientation: a reflection of the node order
// that keeps the cell's topology (used to build test cells without hand-ordering).
inline void orient_positively(MixedMesh& mesh) {
  for (CellType type : all_cell_types) {
    const std::size_t stride = static_cast<std::size_t>(node_count(type));
    auto& nodes = mesh.block(type).nodes;
    for (std::size_t first = 0; first < nodes.size(); first += stride) {
      if (signed_volume(type, mesh.points, &nodes[first]) > 0) continue;
      Index* cell = &nodes[first];
      switch (type) {
        case CellType::tetrahedron:
          std::swap(cell[1], cell[2]);
          break;
        case CellType::pyramid:
          std::swap(cell[1], cell[3]);
          break;
        case CellType::prism:
          std::swap(cell[1], cell[2]);
          std::swap(cell[4], cell[5]);
          break;
        case CellType::hexahedron:
          std::swap(cell[1], cell[3]);
          std::swap(cell[5], cell[7]);
          break;
      }
    }
  }
}

// Tags every boundary face of the cells: faces with all nodes at z = 0 get "wall",
// the others "farfield".
inline void tag_boundary(MixedMesh& mesh) {
  const FaceConnectivity faces = match_faces(mesh);
  const int wall = mesh.marker("wall");
  const int farfield = mesh.marker("farfield");
  for (const CellFace& face : faces.boundary) {
    Index nodes[4];
    const int count = face_nodes(mesh, face, nodes);
    bool on_wall = true;
    for (int corner = 0; corner < count; ++corner)
      on_wall = on_wall && mesh.points[static_cast<std::size_t>(nodes[corner])].z() == 0.0;
    mesh.add_face(count == 3 ? FaceType::triangle : FaceType::quad, nodes, on_wall ? wall : farfield);
  }
}

// A wake layer hexahedron 8 µm thick under a 4 × 10 cm face, warped by a bending mode
// (an IDW step on a random wing), in hexahedron node order: every corner and
// sub-tetrahedron positive, its face pyramids on the centroid inverted (checkMesh's
// "face pyramids incorrectly oriented").
inline std::vector<Vector3> warped_wake_hexahedron() {
  return {{1.2256798049130431, 0.87780310797415084, 0.079142988210004039},
          {1.2661606338252624, 0.8790726194783518, 0.071874017043730892},
          {1.2805760054537865, 0.97821658301744352, 0.091432891834283936},
          {1.2404000539757827, 0.97785694888647501, 0.094158731998119333},
          {1.2256801957844536, 0.87780210036781103, 0.079149153433077962},
          {1.2661612226409324, 0.87907123594122927, 0.071882240193709993},
          {1.2805765153091182, 0.97821529693123199, 0.091440263864830701},
          {1.2404004756018705, 0.9778558902778608, 0.094164782214790979}};
}

// A conforming mesh with one cell of each type:
//   hexahedron  the unit cube, nodes 0-7
//   pyramid     on the cube's top face, apex 8 = (0.5, 0.5, 1.5)
//   tetrahedron on the pyramid's y = 0 side (4, 5, 8) with node 9 = (0.5, -0.5, 1.5)
//   prism       extruded outward from the tetrahedron's face (4, 5, 9), nodes 10-12
// Boundary faces: "wall" at z = 0, "farfield" elsewhere.
inline MixedMesh four_type_mesh() {
  MixedMesh mesh;
  mesh.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},       {0, 0, 1},
                 {1, 0, 1}, {1, 1, 1}, {0, 1, 1}, {0.5, 0.5, 1.5}, {0.5, -0.5, 1.5}};
  const Vector3 offset = Vector3(0, -1, -1).normalized() * 0.5;
  for (Index node : {4, 5, 9}) mesh.points.push_back(mesh.points[static_cast<std::size_t>(node)] + offset);
  const Index hexahedron[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  const Index pyramid[5] = {4, 5, 6, 7, 8};
  const Index tetrahedron[4] = {4, 5, 8, 9};
  const Index prism[6] = {4, 5, 9, 10, 11, 12};
  mesh.add_cell(CellType::hexahedron, hexahedron, 1);
  mesh.add_cell(CellType::pyramid, pyramid, 2);
  mesh.add_cell(CellType::tetrahedron, tetrahedron, 3);
  mesh.add_cell(CellType::prism, prism, 4);
  orient_positively(mesh);
  tag_boundary(mesh);
  return mesh;
}

}  // namespace mixmesh::reference
