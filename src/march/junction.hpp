// The first cells at a junction (front.hpp, Junction): the split face's first cell has
// the wall triangle (t, a, b) at the bottom and the quad (A, B, C, D) of its four lines
// on top (A and D both start at t). No single hexahedron, prism or pyramid has those
// faces, so it is cut about its centre X into a pyramid on each of its four quads and
// a tetrahedron on each of its two triangles. The gap between the two sheet lines along
// the sheet's free edge starts with the prism (t, A, D | w, W_A, W_D).
#pragma once

#include <vector>

#include "front.hpp"

namespace mixmesh::march_detail {

// Local point numbers of JunctionCells::points.
enum JunctionPoint : int {
  wall_corner = 0,  // t, where both lines start
  wall_after = 1,   // a (corner 1 of the split face)
  wall_before = 2,  // b (corner 2)
  top_after = 3,    // A (line of corner 0)
  top_a = 4,        // top of corner 1
  top_b = 5,        // top of corner 2
  top_before = 6,   // D (line of corner 3)
  centre = 7,       // X
  sheet_wall = 8,   // w, the sheet's free-edge node next to t
  sheet_after = 9,  // top of the sheet line on corner 0's side
  sheet_before = 10
};

struct JunctionCell {
  CellType type;
  std::vector<int> nodes;  // local point numbers, VTK order, positive volume
};

struct JunctionCells {
  std::vector<Vector3> points;      // indexed by JunctionPoint
  std::vector<JunctionCell> cells;  // 4 pyramids, 2 tetrahedra, 1 prism
  // Boundary faces of the prism towards the far field, outward: its triangle at the
  // sheet's free edge and its quad between the two lines' tops.
  std::vector<std::vector<int>> hull_faces;
};

// The cells between layer 0 (`bottom`) and layer 1 (`top`), positions per column.
JunctionCells junction_cells(const Front& front, const Junction& junction, const std::vector<Vector3>& bottom,
                             const std::vector<Vector3>& top);

// True when every cell of junction_cells is valid (cell_shape).
bool junction_valid(const JunctionCells& cells);

// The faces whose first cells meet at the junction: the split face first, then the sheet
// faces on the free edge from its node to the sheet columns (the prism between the two
// sheet lines shares a face with each).
std::vector<int> junction_faces(const Front& front, const Junction& junction);

// The junction whose split face is `face`, or nullptr.
const Junction* junction_of(const Front& front, int face);

}  // namespace mixmesh::march_detail
