// Safety checks of a new layer before it is accepted: every new cell must be valid
// (cell_shape) and the new layer front must not cut itself.
#pragma once

#include <vector>

#include "front.hpp"

namespace mixmesh::march_detail {

// The cell that front face `face` sweeps from `bottom` to `top` (positions per
// column), in VTK order with local node numbers 0 .. 7 into `points`.
CellType swept_cell(const Front& front, int face, const std::vector<Vector3>& bottom,
                    const std::vector<Vector3>& top, std::vector<Vector3>& points);

// The faces among `faces` whose swept cell is not valid.
std::vector<int> invalid_cells(const Front& front, const std::vector<int>& faces,
                               const std::vector<Vector3>& bottom, const std::vector<Vector3>& top);

// The faces among `faces` whose top face meets the top face of another face of
// `faces` that shares no column with it, or is crossed by the marching step
// (bottom -> top) of a column not its own, and the faces of such columns (boxes
// first, exact predicates on the candidates).
std::vector<int> intersecting_faces(const Front& front, const std::vector<int>& faces,
                                    const std::vector<Vector3>& bottom, const std::vector<Vector3>& top);

}  // namespace mixmesh::march_detail
