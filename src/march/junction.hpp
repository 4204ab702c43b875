// The cells at a junction (front.hpp, Junction): the split face's first cell has the
// wall triangle (t, a, b) at the bottom and the quad of its four lines on top (the lines
// of corners 0 and 3 both start at t). No single hexahedron, prism or pyramid has those
// faces, so the cell is cut about an inner point into a pyramid on each of its quads and
// a tetrahedron on each of its two triangles. The gap between the two sheet lines along
// the sheet's free edge is closed by the wrap face there (front.hpp), whose first cell,
// a prism, shares the cut cell's triangle over edge 3 -> 0.
//
// A first cell is a first spacing high and as wide as the wall triangle (a thousand
// times more at a sharp trailing edge), so every piece on its wall triangle or its top
// quad is flat. The cut is therefore made in a *stack*: the first cell and the
// hexahedra above it up to a height where an inner point sees every face well. The
// stack's faces are the faces its cells shared with their neighbours, so the mesh stays
// conforming.
#pragma once

#include <array>
#include <vector>

#include "front.hpp"

namespace mixmesh::march_detail {

struct JunctionCell {
  CellType type;
  std::vector<int> nodes;  // local point numbers, VTK order, positive volume
};

// levels[k][c]: the point of the split face's corner c on layer k (k = 0 … layers); on
// layer 0 corners 0 and 3 are the same point.
using JunctionLevels = std::vector<std::array<Vector3, 4>>;

struct JunctionCells {
  // Local point numbers: stack_point(layer, corner), then the inner point (centre_point).
  std::vector<Vector3> points;
  std::vector<JunctionCell> cells;  // 4 pyramids per layer, 2 tetrahedra
  // The worst piece: a pyramid by its smallest corner Jacobian, a tetrahedron by the
  // sine of 180 degrees less its largest dihedral angle (the sliver measure: the
  // tetrahedron on the wrap's triangle is a needle, which is harmless); <= 0 if invalid.
  double quality = -1.0;
  int layers() const { return static_cast<int>(points.size() / 4) - 1; }
  int centre_point() const { return static_cast<int>(points.size()) - 1; }
};

// Local number of corner `corner` of the split face on layer `layer` (on layer 0,
// corner 3 is corner 0's point).
inline int stack_point(int layer, int corner) {
  return layer == 0 && corner == 3 ? 0 : 4 * layer + corner;
}

// The stack's pieces about the inner point whose worst piece is best.
JunctionCells junction_cells(const JunctionLevels& levels);

// The first cell's pieces between layer 0 (`bottom`) and layer 1 (`top`), positions per
// column: what the march checks as it grows the first layer.
JunctionCells junction_cells(const Front& front, const Junction& junction, const std::vector<Vector3>& bottom,
                             const std::vector<Vector3>& top);

// True when every cell of junction_cells is valid (cell_shape).
bool junction_valid(const JunctionCells& cells);

// The faces whose first cells meet at the junction: the split face first, then the sheet
// faces and the wrap face on the free edge from its node to the sheet columns.
std::vector<int> junction_faces(const Front& front, const Junction& junction);

// The first marching direction of each junction line (per column; zero for other
// columns, and where no direction sees every face): the direction that sees its wall
// faces and the opening of the wrap face best (visible_direction). The caller leans it
// off the sheet on the line's side.
std::vector<Vector3> junction_directions(const Front& front, const std::vector<Vector3>& points,
                                         const std::vector<char>& face_active);

// The junction whose split face is `face`, or nullptr.
const Junction* junction_of(const Front& front, int face);

}  // namespace mixmesh::march_detail
