// Builds one hexahedron through the installed headers and library and prints its
// volume; the package test expects "1".
#include <iostream>

#include "mixmesh/mesh/cell_geometry.hpp"

int main() {
  mixmesh::MixedMesh mesh;
  mesh.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const mixmesh::Index nodes[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  mesh.add_cell(mixmesh::CellType::hexahedron, nodes);
  std::cout << mixmesh::signed_volume(mixmesh::CellType::hexahedron, mesh.points, nodes) << '\n';
  return 0;
}
