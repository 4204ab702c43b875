// The split of an outer layer cell about one point (Wild Fig. 2): its pieces, their
// quality, and the choice of the point, the diagonals and the stack of cells split.
#pragma once

#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

#include "mixmesh/interface/interface_split.hpp"
#include "mixmesh/mesh/face_connectivity.hpp"

namespace mixmesh::interface_detail {

// Position (0 or 1) of the first node of the chosen diagonal q[s]–q[s+2].
int diagonal_start(const std::vector<Vector3>& points, const Index* quad, HullDiagonal rule);

// The pieces a split about `apex` makes: pyramids on the quads that stay, two
// tetrahedra on every outer quad (along its chosen diagonal), one on every triangle.
// Faces in `skipped_faces` (inside a stack, see Level) get none.
// visit(CellType, nodes, is_hull_triangle) with the apex as node index `apex_index`.
// Bit f of `flipped` cuts outer quad f along the other diagonal than the rule's.
template <typename Visit>
void for_each_piece(CellType type, const std::vector<Vector3>& points, const Index* nodes,
                    unsigned outer_faces, unsigned skipped_faces, unsigned flipped,
                    const InterfaceOptions& options, Index apex_index, Visit visit) {
  const CellDescriptor& shape = descriptor(type);
  for (int face = 0; face < shape.face_count; ++face) {
    if ((skipped_faces >> face) & 1u) continue;
    const LocalFace& local = shape.faces[static_cast<std::size_t>(face)];
    Index corners[4] = {-1, -1, -1, -1};  // outward from the cell
    for (int corner = 0; corner < local.node_count; ++corner)
      corners[corner] = nodes[local.nodes[static_cast<std::size_t>(corner)]];
    const bool outer = (outer_faces >> face) & 1u;
    // Tetrahedron face 0-2-1 is outward, so (a, c, b, apex) keeps a-b-c outward.
    auto tetrahedron = [&](Index a, Index b, Index c) {
      const Index piece[4] = {a, c, b, apex_index};
      visit(CellType::tetrahedron, piece, outer);
    };
    if (local.node_count == 3) {
      tetrahedron(corners[0], corners[1], corners[2]);
    } else if (!outer) {
      // The pyramid base 0-1-2-3 turns counter-clockwise seen from the apex, i.e.
      // opposite to the cell's outward winding.
      const Index piece[5] = {corners[0], corners[3], corners[2], corners[1], apex_index};
      visit(CellType::pyramid, piece, false);
    } else {
      const int start =
          diagonal_start(points, corners, options.diagonal) ^ static_cast<int>((flipped >> face) & 1u);
      tetrahedron(corners[start], corners[start + 1], corners[start + 2]);
      tetrahedron(corners[start], corners[start + 2], corners[(start + 3) % 4]);
    }
  }
}

// One cell of what is split about one point: the outer cell alone, or a stack of it and
// the cells under it in its column (the faces between them skipped). In a column of
// outer cells (`column_axis`) every level may face the far field, by its ends.
struct Level {
  const Index* nodes = nullptr;
  unsigned outer_faces = 0u;
  unsigned skipped_faces = 0u;
};

template <typename Visit>
void for_each_stack_piece(CellType type, const std::vector<Vector3>& points, const std::vector<Level>& levels,
                          unsigned flipped, const InterfaceOptions& options, Index apex_index, Visit visit) {
  for (const Level& level : levels)
    for_each_piece(type, points, level.nodes, level.outer_faces, level.skipped_faces, flipped, options,
                   apex_index, visit);
}

// The quality of a split about the last point of `points`: the worst piece's smallest
// corner Jacobian (scaled; negative when a piece is inverted or tangled), the same of its
// pyramids alone, and the largest dihedral angle of its tetrahedra.
struct PieceQuality {
  double worst = 1.0;
  double worst_pyramid = 1.0;
  double largest_dihedral = 0.0;
};
// Where and how a cell is split: the split point, the outer quads cut along the other
// diagonal than the rule's (bits as in for_each_piece), the quality of its pieces (worst
// not positive: no split makes every piece valid), and the cells split about the point
// (the outer cell, then the others of its stack: under it, or along its column).
struct SplitChoice {
  Vector3 point = Vector3::Zero();
  unsigned flipped = 0u;
  PieceQuality quality{0.0, 0.0, 180.0};
  std::vector<std::size_t> cells;
  std::vector<unsigned> skipped_faces;  // per cell: the faces inside the stack
};

// Whether a split's pieces meet options.stack_dihedral and options.stack_pyramid_quality.
bool meets_bounds(const PieceQuality& quality, const InterfaceOptions& options);

// The split of one cell or stack (`levels`, in mesh numbering).
SplitChoice choose_split(CellType type, const std::vector<Vector3>& mesh_points,
                         const std::vector<Level>& mesh_levels, const InterfaceOptions& options);

// The cell of the same type across each face of each cell of `type`: (cell, its local
// face), or (-1, -1).
using FaceNeighbours = std::vector<std::pair<Index, int>>;

FaceNeighbours same_type_neighbours(const MixedMesh& mesh, CellType type,
                                    const FaceConnectivity& connectivity);

// A hexahedron in a column of outer cells: its outer quads are ends, each at most a
// quarter of its largest face and all sides of it (a wake's last cell at its tip edge,
// whose end quad faces the far field). Then its largest face and the one opposite,
// across which the column runs; else nullopt.
std::optional<std::pair<int, int>> column_axis(const MixedMesh& mesh, CellType type, std::size_t cell,
                                               unsigned outer_faces);

// The split of an outer cell. An outer hexahedron (or prism) whose split about its
// centre leaves a tetrahedron with a dihedral angle above options.stack_dihedral (a layer
// cell much thinner than wide: the outer quad's two tetrahedra have their apex half the
// cell's height under the quad's diagonal, so their angle at the apex edge opposite it is
// 180 degrees less about twice atan(h / w)), or a pyramid flatter than
// options.stack_pyramid_quality (the pyramid on the inner quad of a cell h high and L
// long has a scaled Jacobian of about h / L), is split together with the hexahedra under
// it, as one stack about its middle: the lowest stack that meets both bounds, else the
// best one. The stack's side quads keep their pyramids, so neighbouring columns conform
// whatever their own stack; a side quad that faces the far field (a column above a
// neighbour whose growth stopped) gets its two tetrahedra as in a single cell. The top
// is the largest outer quad; a hexahedron in a column of outer cells (`column_axis`)
// stacks either way along the column, whose last cell may face the far field by its top
// as well. `barred` per cell: 0 free, 1 capped (only a
// column's stack takes it, and its cap with it), 2 in another split (never taken).
SplitChoice choose_stack(const MixedMesh& mesh, CellType type, std::size_t cell,
                         const std::vector<unsigned>& outer_faces, const std::vector<char>& barred,
                         const FaceNeighbours& neighbours, const InterfaceOptions& options);

// Two splits as one, where `first` (whose cells start the stack) and `second` touch
// only where columns of outer cells run on (`column_axis`), hold at most
// options.stack_cells cells together, and split better together than apart. In a column of outer cells (a
// wake's last cell at its tip edge, under many layers) the stacks chosen one after another can leave the
// column's last cells to a stack too thin for its length.
std::optional<SplitChoice> joined_stack(const MixedMesh& mesh, CellType type, const SplitChoice& first,
                                        const SplitChoice& second, const FaceNeighbours& neighbours,
                                        const std::vector<unsigned>& outer_faces,
                                        const InterfaceOptions& options);

}  // namespace mixmesh::interface_detail
