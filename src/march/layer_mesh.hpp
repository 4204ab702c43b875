// Turning the marched columns into the cells and boundary faces of a BoundaryLayer.
#pragma once

#include "front.hpp"
#include "mixmesh/march/march_layers.hpp"

namespace mixmesh::march_detail {

// Appends the cell front face `face` sweeps between layers `layer` and layer + 1
// of its columns (column_points must already hold layer + 1).
void add_swept_cell(const Front& front, int face, int layer, BoundaryLayer& result);

// Cuts each junction's split face (junction.hpp): its first cell and the hexahedra
// above it, as high as gives the best pieces below the face's outermost cell, become
// pyramids and two tetrahedra about one inner point. Needs face_layers complete.
void add_junction_stacks(const Front& front, BoundaryLayer& result);

// Adds the boundary faces: wall faces (patch names), the outer hull (column tops and
// the sides exposed above a neighbouring column that stopped lower), and the sides
// along free edges of the front (symmetry marker in the symmetry plane, hull-side
// marker elsewhere). Needs face_layers and column_points complete.
void add_boundary_faces(const Front& front, const MarchOptions& options, BoundaryLayer& result);

}  // namespace mixmesh::march_detail
