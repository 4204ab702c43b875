// MixedMesh: the one mesh type every stage reads and writes.
//
//   points          #P 3-vectors, contiguous
//   cells[type]     fixed-stride node lists (4 tet, 5 pyramid, 6 prism, 8 hex, VTK order)
//                   with a parallel array of region tags
//   boundary[type]  boundary faces (3 triangle, 4 quad), each with a marker id
//   marker_names    name of every marker id
//
// Planar meshes (2D CFD, the deformation studies) use the same type: triangles and
// quads in the z = 0 plane as planar_cells (markers = region tags) and boundary
// edges with markers; their volume cells and boundary faces are empty.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "mixmesh/mesh/topology.hpp"

namespace mixmesh {

using Index = std::int32_t;
using Vector3 = Eigen::Vector3d;

struct CellBlock {
  std::vector<Index> nodes;  // stride = node_count(type)
  std::vector<int> regions;  // one tag per cell
};

struct FaceBlock {
  std::vector<Index> nodes;  // stride = node_count(type)
  std::vector<int> markers;  // index into MixedMesh::marker_names
};

struct EdgeBlock {
  std::vector<Index> nodes;  // 2 per edge
  std::vector<int> markers;
};

struct MixedMesh {
  std::vector<Vector3> points;
  std::array<CellBlock, 4> cells;
  std::array<FaceBlock, 2> boundary;
  std::vector<std::string> marker_names;
  std::array<FaceBlock, 2> planar_cells;  // planar meshes only
  EdgeBlock boundary_edges;               // planar meshes only

  bool planar() const {
    return cell_count() == 0 && !(planar_cells[0].nodes.empty() && planar_cells[1].nodes.empty());
  }

  CellBlock& block(CellType type) { return cells[index(type)]; }
  const CellBlock& block(CellType type) const { return cells[index(type)]; }
  FaceBlock& faces(FaceType type) { return boundary[index(type)]; }
  const FaceBlock& faces(FaceType type) const { return boundary[index(type)]; }

  std::size_t cell_count(CellType type) const {
    return block(type).nodes.size() / static_cast<std::size_t>(node_count(type));
  }
  std::size_t cell_count() const;
  std::size_t face_count(FaceType type) const {
    return faces(type).nodes.size() / static_cast<std::size_t>(node_count(type));
  }
  std::size_t face_count() const { return face_count(FaceType::triangle) + face_count(FaceType::quad); }

  const Index* cell(CellType type, std::size_t cell_index) const {
    return block(type).nodes.data() + cell_index * static_cast<std::size_t>(node_count(type));
  }
  const Index* face(FaceType type, std::size_t face_index) const {
    return faces(type).nodes.data() + face_index * static_cast<std::size_t>(node_count(type));
  }

  // Appends a cell or face; the node count must match the type.
  void add_cell(CellType type, const Index* nodes, int region = 0);
  void add_face(FaceType type, const Index* nodes, int marker);

  // The id of a marker, added if new.
  int marker(const std::string& name);
  // The id of a marker, or -1 where no marker has that name.
  int find_marker(const std::string& name) const;
};

// Removes points no cell or boundary face uses and renumbers the rest in their old
// order. Returns old→new indices (-1 for removed points).
std::vector<Index> compact_points(MixedMesh& mesh);

// "(x, y, z)": how error messages and logs name a location.
std::string point_text(const Vector3& point);

}  // namespace mixmesh
