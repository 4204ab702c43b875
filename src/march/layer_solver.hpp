// The implicit corrector of one marching step: the face-weighted Laplace equation
// for all nodes of the new layer at once, solved by Jacobi sweeps or by a sparse
// linear solve of the whole layer per outer iteration.
#pragma once

#include <vector>

#include "front.hpp"
#include "mixmesh/march/laplace_operators.hpp"

namespace mixmesh::march_detail {

// The new layer and how far the last iteration moved it: the largest node change of
// the last sweep (or outer iteration) divided by that node's marching step.
struct LayerSolution {
  std::vector<Vector3> positions;
  int iterations = 0;
  double last_change = 0.0;
};

// Positions of the new layer that solve the discrete face-weighted Laplace equation
// (structured stencil or prism ring per column, Wild eq. (1) and (6)) with the
// marching targets `predicted`, by `sweeps` Jacobi sweeps starting from the targets.
// Columns with a stopped face, and columns on free edges, keep their target.
LayerSolution solve_layer_by_sweeps(const Front& front, int sweeps, const std::vector<char>& face_active,
                                    const std::vector<Vector3>& current,
                                    const std::vector<Vector3>& predicted, double symmetry_y);

// The same equations solved implicitly: per outer iteration the weights are frozen,
// the linear system of every Laplace column of the layer is assembled (neighbours as
// unknowns, stopped columns as known values, symmetry nodes held in their plane) and
// solved by BiCGSTAB (sparse LU if that fails); free-edge columns are then updated as
// in a sweep, and outer steps that grow the change are damped. Stops when the change
// is below `tolerance` or after `iterations` outer iterations. Throws mixmesh::Error
// if the system is singular.
LayerSolution solve_layer_sparse(const Front& front, int iterations, double tolerance,
                                 const std::vector<char>& face_active, const std::vector<Vector3>& current,
                                 const std::vector<Vector3>& predicted, double symmetry_y);

// Mean marching direction (next - current) of each column and its ring
// neighbours, a neighbour weighted by (step / distance)^2 up to 1.
std::vector<Vector3> neighbour_mean_directions(const Front& front, const std::vector<char>& column_active,
                                               const std::vector<Vector3>& current,
                                               const std::vector<Vector3>& next);

// Shared by both solvers.
// 1 for columns all of whose faces are active and whose step is not zero: the
// columns the corrector moves.
std::vector<char> corrected_columns(const Front& front, const std::vector<char>& face_active,
                                    const std::vector<Vector3>& current,
                                    const std::vector<Vector3>& predicted);
// Position of ring entry `entry` (negative: mirrored in the symmetry plane).
Vector3 ring_position(int entry, const std::vector<Vector3>& positions, double symmetry_y);
// Frozen weights of column c's Laplace equation (structured or ring column) at `positions`.
LaplaceWeights column_weights(const Front& front, std::size_t c, const std::vector<Vector3>& positions,
                              const std::vector<Vector3>& current, const std::vector<Vector3>& predicted,
                              double symmetry_y);
// Free-edge column: the direction of its step averaged with its fan's (length kept).
Vector3 free_column_update(const Front& front, std::size_t c, const std::vector<Vector3>& positions,
                           const std::vector<Vector3>& current, const std::vector<Vector3>& predicted);
// Largest |after - before| / |predicted - current| over the corrected columns.
double relative_change(const std::vector<char>& corrected, const std::vector<Vector3>& before,
                       const std::vector<Vector3>& after, const std::vector<Vector3>& current,
                       const std::vector<Vector3>& predicted);

}  // namespace mixmesh::march_detail
