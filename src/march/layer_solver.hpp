// The implicit corrector of one marching step: the face-weighted Laplace equation
// for all nodes of the new layer at once.
#pragma once

#include <vector>

#include "front.hpp"

namespace mixmesh::march_detail {

// Positions of the new layer that solve the discrete face-weighted Laplace equation
// (structured stencil or prism ring per column, Wild eq. (1) and (6)) with the
// marching targets `predicted`, by `sweeps` Jacobi sweeps starting from the targets.
// Columns with a stopped face, and columns on free edges, keep their target.
std::vector<Vector3> solve_layer(const Front& front, int sweeps, const std::vector<char>& face_active,
                                 const std::vector<Vector3>& current, const std::vector<Vector3>& predicted,
                                 double symmetry_y);

// Mean marching direction (next - current) of each column and its ring
// neighbours, a neighbour weighted by (step / distance)^2 up to 1.
std::vector<Vector3> neighbour_mean_directions(const Front& front, const std::vector<char>& column_active,
                                               const std::vector<Vector3>& current,
                                               const std::vector<Vector3>& next);

}  // namespace mixmesh::march_detail
