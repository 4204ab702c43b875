// The dual mesh the deformation methods work on: cells as nodes, shared faces as edges,
// one representation for volume meshes (tet/pyramid/prism/hex, faces) and planar
// meshes (triangles/quads in z = 0, edges). Internal to the deform module.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "mixmesh/mesh/mixed_mesh.hpp"
#include "mixmesh/mesh/topology.hpp"

namespace mixmesh::deform::detail {

// Cell kinds: the four volume types by CellType index, then the planar ones.
inline constexpr int planar_triangle = 4;
inline constexpr int planar_quad = 5;

struct DualMesh {
  bool planar = false;
  std::size_t point_count = 0;

  // Cells, CSR: nodes of cell c are cell_nodes[cell_offsets[c] .. cell_offsets[c+1]).
  std::vector<std::size_t> cell_offsets;
  std::vector<Index> cell_nodes;
  std::vector<std::uint8_t> cell_kind;
  std::vector<std::size_t> index_in_block;  // for messages

  // Interior faces (planar: edges) between two cells, with their area (length).
  std::vector<std::array<Index, 2>> interior_cells;
  std::vector<double> interior_area;

  // Boundary faces (planar: edges), CSR, each with its marker and the cell it bounds.
  std::vector<std::size_t> face_offsets;
  std::vector<Index> face_nodes;
  std::vector<int> face_marker;
  std::vector<Index> face_cell;

  // Point → cells, CSR.
  std::vector<std::size_t> point_cell_offsets;
  std::vector<Index> point_cells;

  std::size_t cell_count() const { return cell_kind.size(); }
  std::size_t face_count() const { return face_marker.size(); }
  int cell_size(std::size_t cell) const {
    return static_cast<int>(cell_offsets[cell + 1] - cell_offsets[cell]);
  }
  const Index* nodes(std::size_t cell) const { return cell_nodes.data() + cell_offsets[cell]; }
  int face_size(std::size_t face) const {
    return static_cast<int>(face_offsets[face + 1] - face_offsets[face]);
  }
  const Index* boundary_nodes(std::size_t face) const { return face_nodes.data() + face_offsets[face]; }
};

// Throws mixmesh::Error for a tagged boundary face or edge that bounds no cell, and
// for a mesh with neither volume nor planar cells.
DualMesh build_dual_mesh(const MixedMesh& mesh);

// Mean of the nodes (the dual node of a cell, the centre of a face).
Vector3 cell_centre(const DualMesh& dual, std::size_t cell, const std::vector<Vector3>& points);
Vector3 face_centre(const DualMesh& dual, std::size_t face, const std::vector<Vector3>& points);
// Area (length) of a boundary face (edge).
double face_area(const DualMesh& dual, std::size_t face, const std::vector<Vector3>& points);
// Signed volume (planar: signed area in z = 0).
double cell_measure(const DualMesh& dual, std::size_t cell, const std::vector<Vector3>& points);
// Positive volume and no tangled corner (volume: mixmesh::cell_shape; planar: positive
// area and every corner turning counter-clockwise).
bool cell_valid(const DualMesh& dual, std::size_t cell, const std::vector<Vector3>& points);
// Calls edge(from, to) for every edge of a cell: the sides of a planar cell in order,
// the descriptor's edges of a volume cell.
template <class Edge>
void for_each_cell_edge(const DualMesh& dual, std::size_t cell, Edge&& edge) {
  const Index* nodes = dual.nodes(cell);
  const int kind = dual.cell_kind[cell];
  if (kind >= planar_triangle) {
    const int count = dual.cell_size(cell);
    for (int corner = 0; corner < count; ++corner) edge(nodes[corner], nodes[(corner + 1) % count]);
    return;
  }
  const CellDescriptor& type = descriptor(static_cast<CellType>(kind));
  for (int k = 0; k < type.edge_count; ++k)
    edge(nodes[type.edges[static_cast<std::size_t>(k)][0]],
         nodes[type.edges[static_cast<std::size_t>(k)][1]]);
}

// The cells using any of `nodes`, sorted, each once.
std::vector<Index> cells_of_nodes(const DualMesh& dual, const std::vector<Index>& nodes);
// "hexahedron", "quad", …
std::string cell_kind_name(int kind);

// 64-bit hashes to recognise a mesh again (not cryptographic): of the connectivity
// (cells, boundary faces or edges with their markers, point count), of the points' bits,
// and of a list of indices mixed into a hash.
std::uint64_t connectivity_hash(const MixedMesh& mesh);
std::uint64_t points_hash(const std::vector<Vector3>& points);
std::uint64_t combine_hash(std::uint64_t hash, const std::vector<Index>& values);
// `count` bytes mixed into a hash, eight at a time (the same mixing as the hashes above).
std::uint64_t combine_hash(std::uint64_t hash, const char* bytes, std::size_t count);

// Greedy colouring of the dual graph: no two cells sharing a face have one colour.
// Returns the cells of each colour.
std::vector<std::vector<Index>> colour_cells(const DualMesh& dual);

}  // namespace mixmesh::deform::detail
