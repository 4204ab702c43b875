// The first cells at a junction (front.hpp, Junction): the split face's first cell has
// the wall triangle (t, a, b) at the bottom and the quad (A, B, C, D) of its four lines
// on top (A and D both start at t). No single hexahedron, prism or pyramid has those
// faces, so it is cut about its centre X into a pyramid on each of its four quads and
// a tetrahedron on each of its two triangles. The gap between the two sheet lines along
// the sheet's free edge is closed by the wrap face there (front.hpp), whose first cell,
// the prism (t, A, D | w, W_A, W_D), shares the cut cell's triangle (t, A, D).
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
  centre = 7        // X
};

struct JunctionCell {
  CellType type;
  std::vector<int> nodes;  // local point numbers, VTK order, positive volume
};

struct JunctionCells {
  std::vector<Vector3> points;      // indexed by JunctionPoint
  std::vector<JunctionCell> cells;  // 4 pyramids, 2 tetrahedra
};

// The cells between layer 0 (`bottom`) and layer 1 (`top`), positions per column.
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
