#include "layer_solver.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace mixmesh::march_detail {

std::vector<char> corrected_columns(const Front& front, const std::vector<char>& face_active,
                                    const std::vector<Vector3>& current,
                                    const std::vector<Vector3>& predicted) {
  std::vector<char> corrected(current.size(), 1);
  for (std::size_t face = 0; face < front.faces.size(); ++face)
    if (!face_active[face])
      for (int k = 0; k < front.faces[face].corner_count; ++k)
        corrected[static_cast<std::size_t>(front.faces[face].columns[static_cast<std::size_t>(k)])] = 0;
  for (std::size_t c = 0; c < current.size(); ++c)
    if (!(predicted[c] - current[c]).norm()) corrected[c] = 0;
  return corrected;
}

Vector3 ring_position(int entry, const std::vector<Vector3>& positions, double symmetry_y) {
  if (entry >= 0) return positions[static_cast<std::size_t>(entry)];
  Vector3 mirrored = positions[static_cast<std::size_t>(-entry - 1)];
  mirrored.y() = 2.0 * symmetry_y - mirrored.y();
  return mirrored;
}

namespace {

// The neighbour points of column c in the layer: its structured stencil, or its ring
// (symmetry-plane entries mirrored).
StructuredStencil stencil_of(const Front& front, std::size_t c, const std::vector<Vector3>& positions) {
  const auto& s = front.stencil[c];
  auto at = [&](int k) { return positions[static_cast<std::size_t>(s[static_cast<std::size_t>(k)])]; };
  return {at(0), at(1), at(2), at(3), at(4), at(5), at(6), at(7)};
}

std::vector<Vector3> ring_of(const Front& front, std::size_t c, const std::vector<Vector3>& positions,
                             double symmetry_y) {
  std::vector<Vector3> ring;
  ring.reserve(front.ring[c].size());
  for (int entry : front.ring[c]) ring.push_back(ring_position(entry, positions, symmetry_y));
  return ring;
}

}  // namespace

LaplaceWeights column_weights(const Front& front, std::size_t c, const std::vector<Vector3>& positions,
                              const std::vector<Vector3>& current, const std::vector<Vector3>& predicted,
                              double symmetry_y) {
  if (front.neighbourhood[c] == Neighbourhood::structured)
    return structured_laplace_weights(stencil_of(front, c, positions), predicted[c], current[c]);
  return prism_laplace_weights(ring_of(front, c, positions, symmetry_y), positions[c], predicted[c],
                               current[c]);
}

Vector3 free_column_update(const Front& front, std::size_t c, const std::vector<Vector3>& positions,
                           const std::vector<Vector3>& current, const std::vector<Vector3>& predicted) {
  // No Laplace stencil on an open fan: the direction of the step is averaged with the
  // directions of the fan's lines (length kept).
  const Vector3 own = predicted[c] - current[c];
  const double length = own.norm();
  Vector3 sum = own / length;
  int count = 0;
  Vector3 neighbours = Vector3::Zero();
  for (int entry : front.ring[c]) {
    const auto n = static_cast<std::size_t>(entry);
    const Vector3 step = positions[n] - current[n];
    if (step.norm() > 0.0) neighbours += step.normalized();
    ++count;
  }
  if (count > 0) sum += neighbours / count;
  return sum.norm() > 0.0 ? Vector3(current[c] + length * sum.normalized()) : positions[c];
}

double relative_change(const std::vector<char>& corrected, const std::vector<Vector3>& before,
                       const std::vector<Vector3>& after, const std::vector<Vector3>& current,
                       const std::vector<Vector3>& predicted) {
  double change = 0.0;
  for (std::size_t c = 0; c < before.size(); ++c)
    if (corrected[c])
      change = std::max(change, (after[c] - before[c]).norm() / (predicted[c] - current[c]).norm());
  return change;
}

LayerSolution solve_layer_by_sweeps(const Front& front, int sweeps, const std::vector<char>& face_active,
                                    const std::vector<Vector3>& current,
                                    const std::vector<Vector3>& predicted, double symmetry_y) {
  const std::size_t column_count = current.size();
  const std::vector<char> corrected = corrected_columns(front, face_active, current, predicted);
  LayerSolution solution;
  solution.positions = predicted;
  std::vector<Vector3>& positions = solution.positions;
  std::vector<Vector3> updated = predicted;
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    tbb::parallel_for(std::size_t{0}, column_count, [&](std::size_t c) {
      if (!corrected[c]) return;
      if (front.neighbourhood[c] == Neighbourhood::free) {
        updated[c] = free_column_update(front, c, positions, current, predicted);
      } else if (front.neighbourhood[c] == Neighbourhood::structured) {
        updated[c] = structured_laplace_update(stencil_of(front, c, positions), predicted[c], current[c]);
      } else {
        updated[c] = prism_laplace_update(ring_of(front, c, positions, symmetry_y), positions[c],
                                          predicted[c], current[c]);
      }
      if (front.on_symmetry[c]) updated[c].y() = symmetry_y;
    });
    solution.last_change = relative_change(corrected, positions, updated, current, predicted);
    solution.iterations = sweep + 1;
    positions.swap(updated);
    updated = positions;
  }
  return solution;
}

std::vector<Vector3> neighbour_mean_directions(const Front& front, const std::vector<char>& column_active,
                                               const std::vector<Vector3>& current,
                                               const std::vector<Vector3>& next) {
  const std::size_t column_count = current.size();
  std::vector<Vector3> direction(column_count, Vector3::Zero());
  auto unit = [](const Vector3& v) {
    return v.norm() > 0.0 ? Vector3(v.normalized()) : Vector3(Vector3::Zero());
  };
  tbb::parallel_for(std::size_t{0}, column_count, [&](std::size_t c) {
    if (!column_active[c]) return;
    const double height = (next[c] - current[c]).squaredNorm();
    Vector3 sum = unit(next[c] - current[c]);
    for (int entry : front.ring[c]) {
      const auto neighbour = static_cast<std::size_t>(entry >= 0 ? entry : -entry - 1);
      if (!column_active[neighbour]) continue;
      Vector3 step = unit(next[neighbour] - current[neighbour]);
      if (entry < 0) step.y() = -step.y();
      // Weight step / spacing, at most 1: the lines couple as the layer grows as thick
      // as the surface cells are wide.
      const double spacing = (current[neighbour] - current[c]).squaredNorm();
      sum += (spacing > height ? std::sqrt(height / spacing) : 1.0) * step;
    }
    if (front.on_symmetry[c]) sum.y() = 0.0;
    direction[c] = unit(sum);
  });
  return direction;
}

}  // namespace mixmesh::march_detail
