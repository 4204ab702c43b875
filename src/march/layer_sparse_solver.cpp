// The implicit variant of the layer corrector: one sparse linear system per outer
// iteration for the whole new layer (Wild §II.A: "each layer is solved implicitly").
#include <tbb/parallel_for.h>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include <algorithm>
#include <limits>

#include "layer_solver.hpp"
#include "mixmesh/core/error.hpp"

namespace mixmesh::march_detail {

namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;
using Triplet = Eigen::Triplet<double>;

// Columns of a neighbour set: stencil or ring entries as (column, mirrored).
struct Neighbour {
  std::size_t column;
  bool mirrored;
};

std::vector<Neighbour> neighbours_of(const Front& front, std::size_t c) {
  std::vector<Neighbour> result;
  if (front.neighbourhood[c] == Neighbourhood::structured) {
    for (int entry : front.stencil[c]) result.push_back({static_cast<std::size_t>(entry), false});
    return result;
  }
  for (int entry : front.ring[c])
    result.push_back(entry >= 0 ? Neighbour{static_cast<std::size_t>(entry), false}
                                : Neighbour{static_cast<std::size_t>(-entry - 1), true});
  return result;
}

// Solves matrix * change = right for the change of the current iterate. BiCGSTAB
// (Jacobi-preconditioned; the rows have a unit diagonal and are diagonally dominant
// where the marching weight dominates) from a zero change, so its relative tolerance
// applies to the correction, not to the coordinates; sparse LU if it does not converge.
Eigen::MatrixXd solve_change(const SparseMatrix& matrix, const Eigen::MatrixXd& right) {
  if (right.norm() == 0.0) return Eigen::MatrixXd::Zero(right.rows(), right.cols());
  Eigen::BiCGSTAB<SparseMatrix> iterative;
  iterative.setTolerance(1e-6);
  iterative.setMaxIterations(std::max<Eigen::Index>(100, matrix.rows() / 10));
  iterative.compute(matrix);
  Eigen::MatrixXd change(right.rows(), right.cols());
  bool converged = iterative.info() == Eigen::Success;
  for (Eigen::Index k = 0; k < right.cols() && converged; ++k) {
    change.col(k) = iterative.solve(right.col(k));
    converged = iterative.info() == Eigen::Success;
  }
  if (converged) return change;
  Eigen::SparseLU<SparseMatrix> direct;
  direct.compute(matrix);
  if (direct.info() != Eigen::Success)
    throw Error("march: the sparse layer system is singular (" + direct.lastErrorMessage() + ")");
  return direct.solve(right);
}

}  // namespace

LayerSolution solve_layer_sparse(const Front& front, int iterations, double tolerance,
                                 const std::vector<char>& face_active, const std::vector<Vector3>& current,
                                 const std::vector<Vector3>& predicted, double symmetry_y) {
  const std::size_t column_count = current.size();
  const std::vector<char> corrected = corrected_columns(front, face_active, current, predicted);
  // Unknowns: the corrected Laplace columns; all other columns are known values.
  std::vector<int> unknown(column_count, -1);
  std::vector<std::size_t> columns;
  for (std::size_t c = 0; c < column_count; ++c)
    if (corrected[c] && front.neighbourhood[c] != Neighbourhood::free) {
      unknown[c] = static_cast<int>(columns.size());
      columns.push_back(c);
    }
  const auto size = static_cast<Eigen::Index>(columns.size());
  std::vector<std::vector<Neighbour>> neighbours(columns.size());
  for (std::size_t row = 0; row < columns.size(); ++row) neighbours[row] = neighbours_of(front, columns[row]);

  LayerSolution solution;
  solution.positions = predicted;
  std::vector<Vector3>& positions = solution.positions;
  // x and z share one matrix; y has its own: a mirrored neighbour enters as 2 y_s - y,
  // and a symmetry node's row is y = y_s.
  std::vector<LaplaceWeights> weights(columns.size());
  double relaxation = 1.0, previous_change = std::numeric_limits<double>::infinity();
  for (int iteration = 0; iteration < iterations; ++iteration) {
    tbb::parallel_for(std::size_t{0}, columns.size(), [&](std::size_t row) {
      weights[row] = column_weights(front, columns[row], positions, current, predicted, symmetry_y);
    });
    std::vector<Triplet> entries_xz, entries_y;
    entries_xz.reserve(columns.size() * 9);
    entries_y.reserve(columns.size() * 9);
    Eigen::MatrixX2d right_xz(size, 2);
    Eigen::VectorXd right_y(size);
    for (std::size_t row = 0; row < columns.size(); ++row) {
      const std::size_t c = columns[row];
      const auto i = static_cast<Eigen::Index>(row);
      // Each row divided by its denominator: unit diagonal, whatever the cell size.
      const LaplaceWeights& w = weights[row];
      const Vector3 target = (w.target_weight / w.denominator) * predicted[c];
      double known_x = target.x(), known_y = target.y(), known_z = target.z();
      entries_xz.emplace_back(i, i, 1.0);
      entries_y.emplace_back(i, i, 1.0);
      const bool in_plane = front.on_symmetry[c];
      for (std::size_t k = 0; k < neighbours[row].size(); ++k) {
        const auto [neighbour, mirrored] = neighbours[row][k];
        const double weight = w.neighbour[k] / w.denominator;
        const double sign = mirrored ? -1.0 : 1.0;
        if (mirrored) known_y += 2.0 * symmetry_y * weight;
        if (unknown[neighbour] >= 0) {
          entries_xz.emplace_back(i, unknown[neighbour], -weight);
          if (!in_plane) entries_y.emplace_back(i, unknown[neighbour], -sign * weight);
        } else {
          const Vector3& point = positions[neighbour];
          known_x += weight * point.x();
          known_y += sign * weight * point.y();
          known_z += weight * point.z();
        }
      }
      right_xz(i, 0) = known_x;
      right_xz(i, 1) = known_z;
      right_y(i) = in_plane ? symmetry_y : known_y;
    }
    SparseMatrix matrix_xz(size, size), matrix_y(size, size);
    matrix_xz.setFromTriplets(entries_xz.begin(), entries_xz.end());
    matrix_y.setFromTriplets(entries_y.begin(), entries_y.end());
    // Solved for the change of the iterate: right side = residual of the frozen system.
    Eigen::MatrixX2d iterate_xz(size, 2);
    Eigen::VectorXd iterate_y(size);
    for (std::size_t row = 0; row < columns.size(); ++row) {
      const auto i = static_cast<Eigen::Index>(row);
      const Vector3& point = positions[columns[row]];
      iterate_xz(i, 0) = point.x();
      iterate_xz(i, 1) = point.z();
      iterate_y(i) = point.y();
    }
    const Eigen::MatrixXd change_xz = solve_change(matrix_xz, right_xz - matrix_xz * iterate_xz);
    const Eigen::MatrixXd change_y = solve_change(matrix_y, right_y - matrix_y * iterate_y);

    std::vector<Vector3> updated = positions;
    for (std::size_t row = 0; row < columns.size(); ++row) {
      const auto i = static_cast<Eigen::Index>(row);
      updated[columns[row]] += Vector3(change_xz(i, 0), change_y(i, 0), change_xz(i, 1));
    }
    // Free-edge columns follow their fans as in a sweep, from the solved layer.
    const std::vector<Vector3> solved = updated;
    for (std::size_t c = 0; c < column_count; ++c)
      if (corrected[c] && front.neighbourhood[c] == Neighbourhood::free)
        updated[c] = free_column_update(front, c, solved, current, predicted);
    for (std::size_t c = 0; c < column_count; ++c)
      if (corrected[c] && front.on_symmetry[c]) updated[c].y() = symmetry_y;
    solution.last_change = relative_change(corrected, positions, updated, current, predicted);
    solution.iterations = iteration + 1;
    if (solution.last_change < tolerance) {
      positions.swap(updated);
      break;
    }
    // The weights depend on the positions: where a full step grows the change instead
    // of shrinking it (the fixed-point map is not contractive there), the steps are
    // damped, halving down to 1/16.
    relaxation = solution.last_change > previous_change ? std::max(0.5 * relaxation, 1.0 / 16.0)
                                                        : std::min(1.5 * relaxation, 1.0);
    previous_change = solution.last_change;
    for (std::size_t c = 0; c < column_count; ++c)
      if (corrected[c]) positions[c] += relaxation * (updated[c] - positions[c]);
  }
  return solution;
}

}  // namespace mixmesh::march_detail
