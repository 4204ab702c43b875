// SurfaceMesh: the wall (and wake) surface the marching starts from.
//
// Patches share nodes along seams (one point index, never two coincident points).
// Orientation: every face's right-hand normal points into the flow, away from the
// body. Conventions of the wing case:
//   wing  structured, i runs from the trailing edge along the lower surface, round
//         the leading edge and back along the upper surface to the trailing edge
//         (a sharp trailing edge is one node: i = 0 and i = ni-1 share indices);
//         j runs from the root (y = 0, symmetry plane) to the tip.
//   wake  structured, role wake: a floating sheet marched to both sides (C-type);
//         i runs downstream from the trailing edge (its i = 0 nodes are the wing's
//         trailing-edge nodes), j as on the wing; normal +z.
//   tip   unstructured triangles closing the wing at the tip, sharing the wing's
//         j = nj-1 nodes.
#pragma once

#include <string>
#include <vector>

#include "mixmesh/mesh/mixed_mesh.hpp"

namespace mixmesh {

enum class PatchRole { wall, wake };

struct StructuredPatch {
  std::string name;
  PatchRole role = PatchRole::wall;
  int ni = 0;                // nodes in i
  int nj = 0;                // nodes in j
  std::vector<Index> nodes;  // ni * nj point indices, i fastest
  // Wing patches: the i of the leading edge; faces with i below it are the lower
  // surface (marker <name>_lower), the others the upper one. -1 for other patches.
  int leading_edge_i = -1;
  Index node(int i, int j) const {
    return nodes[static_cast<std::size_t>(j) * static_cast<std::size_t>(ni) + static_cast<std::size_t>(i)];
  }
};

struct TrianglePatch {
  std::string name;
  PatchRole role = PatchRole::wall;
  std::vector<Index> triangles;  // 3 point indices each
};

struct SurfaceMesh {
  std::vector<Vector3> points;
  std::vector<StructuredPatch> structured;
  std::vector<TrianglePatch> unstructured;
  // Nodes with |y - symmetry_y| below this tolerance lie on the symmetry plane and
  // must stay in it; a negative tolerance means there is no symmetry plane.
  double symmetry_y = 0.0;
  double symmetry_tolerance = -1.0;
};

}  // namespace mixmesh
