// Face matching: which cell faces are interior (two cells, opposite orientation),
// which lie on the boundary, and what is non-conforming.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "mixmesh/mesh/mixed_mesh.hpp"

namespace mixmesh {

// One face of one cell.
struct CellFace {
  CellType type;
  Index cell;
  int local_face;
};

struct FaceConnectivity {
  std::vector<std::array<CellFace, 2>> interior;
  std::vector<CellFace> boundary;                         // on exactly one cell
  std::vector<CellFace> shared_by_many;                   // faces on three or more cells
  std::vector<std::array<CellFace, 2>> same_orientation;  // two cells, same winding
  // Boundary cell faces with no tagged boundary face of the same nodes.
  std::vector<CellFace> untagged_boundary;
  // Tagged boundary faces (type, index) that match no boundary cell face.
  std::vector<std::pair<FaceType, std::size_t>> stray_boundary_faces;
  // Boundary triangles whose three nodes belong to one boundary quad: a triangle
  // meets a quad without a pyramid between them.
  std::size_t triangles_in_quads = 0;

  bool conforming() const {
    return shared_by_many.empty() && same_orientation.empty() && triangles_in_quads == 0;
  }
};

FaceConnectivity match_faces(const MixedMesh& mesh);

// The nodes of a face sorted ascending, padded with -1 for triangles: equal keys
// mean the same face whatever the winding.
std::array<Index, 4> sorted_face_key(const Index* nodes, int count);

// The nodes of a cell face, in outward order; returns the node count (3 or 4).
int face_nodes(const MixedMesh& mesh, const CellFace& face, Index* nodes);

// The edges used by exactly one of `triangles` (of a hull: its footprint on a symmetry
// plane, or the free edges of an open hull), each oriented as in its triangle.
std::vector<std::array<Index, 2>> triangle_free_edges(const std::vector<std::array<Index, 3>>& triangles);

}  // namespace mixmesh
