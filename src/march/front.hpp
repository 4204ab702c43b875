// The marching front: the surface seen as marching lines ("columns") and the faces
// between them. A surface node has one column, or two (above and below) when it lies
// on a wake sheet; every face lists the columns of its side, with its right-hand
// normal pointing along the march. Built once from the SurfaceMesh.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "mixmesh/mesh/mixed_mesh.hpp"
#include "mixmesh/surface/surface_mesh.hpp"

namespace mixmesh::march_detail {

// How a column's new position is smoothed.
enum class Neighbourhood : std::uint8_t {
  structured,  // interior node of a structured patch: Wild eq. (1) stencil
  ring,        // closed ring of neighbours: Wild eq. (6)
  free         // open fan on a free edge: marching direction averaged with the fan's
};

struct FrontFace {
  int corner_count = 0;
  std::array<int, 4> columns{-1, -1, -1, -1};
  int patch = 0;     // region index (structured patches first, then triangle patches)
  bool wall = true;  // a wall face (false: a wake face, interior to the mesh)
};

// A front edge with a single face: the sides along it are boundary faces.
struct FreeEdge {
  int face;
  int corner;  // edge from corner to corner + 1 (the face's own winding)
};

// A front edge shared by two faces, for the hull where one column stops lower.
struct SharedEdge {
  std::array<int, 2> faces;
  std::array<int, 2> corners;
};

struct Front {
  std::vector<Index> column_node;
  std::vector<int> column_side;
  std::vector<char> on_symmetry;
  std::vector<FrontFace> faces;
  std::vector<std::vector<int>> column_faces;
  std::vector<Neighbourhood> neighbourhood;
  // structured: east, west, north, south, north-east, north-west, south-east, south-west
  std::vector<std::array<int, 8>> stencil;
  // ring: counter-clockwise neighbours; entry -(c + 1) is column c mirrored in the
  // symmetry plane (rings of symmetry nodes are closed by their mirror image); for
  // free columns the open fan.
  std::vector<std::vector<int>> ring;
  std::vector<FreeEdge> free_edges;
  std::vector<SharedEdge> shared_edges;
  std::vector<std::string> patch_names;
};

// Throws mixmesh::Error naming the patch / node for indices out of range, degenerate
// faces, inconsistent orientation or edges with more than two faces on one side.
Front build_front(const SurfaceMesh& surface);

}  // namespace mixmesh::march_detail
