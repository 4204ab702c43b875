// The surface's faces as the marching front reads them, and where a sheet (a wake)
// leaves the wall: which side of the sheet each wall face at it joins, and the
// junctions planned where a fan of wall faces lies across the sheet (a tip cap).
#pragma once

#include <array>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "front.hpp"

namespace mixmesh::march_detail {

struct SurfaceFace {
  int corner_count;
  std::array<Index, 4> nodes;
  int patch;
  bool wake;
};

// The faces of every patch, structured patches first; checks their node indices.
std::vector<SurfaceFace> surface_faces(const SurfaceMesh& surface, std::vector<std::string>& patch_names);

// Which side of a sheet the wall faces at its nodes join.
struct SheetSides {
  // Sheet normal at every wake node: decides which side a wall face touching it takes.
  std::vector<Vector3> wake_normal;
  std::vector<std::array<int, 4>> corner_side;
  std::unordered_map<Index, std::vector<std::pair<std::size_t, int>>> across;  // node -> (face, corner)
  std::unordered_map<Index, std::vector<std::size_t>> wall_at_wake;
};

// The junctions planned at the nodes where wall faces lie across a sheet.
struct JunctionPlans {
  std::vector<int> split_corner;
  std::vector<std::pair<std::size_t, Index>> junction_nodes;  // (split face, sheet free-edge node)
};

// The side of every wall face corner at a sheet node, and the fans across the sheet.
SheetSides sheet_sides(const SurfaceMesh& surface, const std::vector<SurfaceFace>& faces);

// Nodes on a free edge of a sheet: a sheet edge of one sheet face that no wall face
// uses and that does not lie in the symmetry plane (the plane closes a sheet's root
// edge: the wall faces across the sheet there, a blunt base's, join the lines on
// either side like the others; as a free edge they got a line of their own, and the
// layers did not close round it on the plane).
std::vector<char> sheet_free_edge_nodes(const SurfaceMesh& surface, const std::vector<SurfaceFace>& faces);

// Gives the wall faces across a sheet their sides (in sides.corner_side) and plans the
// junctions where such a fan meets the sheet's free edge.
JunctionPlans plan_junctions(const SurfaceMesh& surface, const std::vector<SurfaceFace>& faces,
                             const std::vector<char>& on_sheet_free_edge, SheetSides& sides);

}  // namespace mixmesh::march_detail
