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
  // A wall triangle whose corner at a sheet junction marches on both sheet lines: four
  // columns, corners 3 and 0 start at the same surface node (see Junction).
  bool split = false;
  // A sheet's side edge closed round its edge (a wake's tip edge): the columns above and
  // below the sheet at the edge's two nodes, (above b, above a, below a, below b); corners
  // 0 and 3, and 1 and 2, start at the same surface node, so its first cell is a prism.
  bool wrap = false;
};

// Where a wall fan across a sheet (a tip cap) meets the sheet's free edge (the tip
// trailing edge): the lines above and below the sheet must both reach the wall faces of
// the fan, or a gap between them would open at the wall. One triangle of the fan (the
// split face) marches on both lines: its first cell has a triangle at the bottom and a
// quad on top and is cut into pyramids and tetrahedra about a point inside it; every
// cell above is a hexahedron. The first cell of the gap between the two lines along the
// sheet's free edge is the first cell of that edge's wrap face (FrontFace::wrap), a
// prism, so the cut cell stays inside the layers.
struct Junction {
  int face = -1;                     // the split face
  std::array<int, 2> sheet{-1, -1};  // sheet columns next to its corners 0 and 3 along the free edge
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
  std::vector<Junction> junctions;
};

// Throws mixmesh::Error naming the patch / node for indices out of range, degenerate
// faces, inconsistent orientation or edges with more than two faces on one side.
Front build_front(const SurfaceMesh& surface);

// Unit normals of the active wall faces at a line (column), in the order of
// front.column_faces; faces of no area are left out.
std::vector<Vector3> wall_face_normals(const Front& front, const std::vector<Vector3>& points,
                                       const std::vector<char>& face_active, int line);

}  // namespace mixmesh::march_detail
