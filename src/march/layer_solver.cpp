#include "layer_solver.hpp"

#include <tbb/parallel_for.h>

#include <cmath>

#include "mixmesh/march/laplace_operators.hpp"

namespace mixmesh::march_detail {

namespace {

// Position of ring entry `entry` (negative: mirrored in the symmetry plane).
Vector3 ring_position(int entry, const std::vector<Vector3>& positions, double symmetry_y) {
  if (entry >= 0) return positions[static_cast<std::size_t>(entry)];
  Vector3 mirrored = positions[static_cast<std::size_t>(-entry - 1)];
  mirrored.y() = 2.0 * symmetry_y - mirrored.y();
  return mirrored;
}

}  // namespace

std::vector<Vector3> solve_layer(const Front& front, int sweeps, const std::vector<char>& face_active,
                                 const std::vector<Vector3>& current, const std::vector<Vector3>& predicted,
                                 double symmetry_y) {
  const std::size_t column_count = current.size();
  std::vector<char> complete(column_count, 1);
  for (std::size_t face = 0; face < front.faces.size(); ++face)
    if (!face_active[face])
      for (int k = 0; k < front.faces[face].corner_count; ++k)
        complete[static_cast<std::size_t>(front.faces[face].columns[static_cast<std::size_t>(k)])] = 0;

  std::vector<Vector3> positions = predicted, updated = predicted;
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    tbb::parallel_for(std::size_t{0}, column_count, [&](std::size_t c) {
      if (!complete[c] || !(predicted[c] - current[c]).norm()) return;
      switch (front.neighbourhood[c]) {
        case Neighbourhood::structured: {
          const auto& s = front.stencil[c];
          auto at = [&](int k) {
            return positions[static_cast<std::size_t>(s[static_cast<std::size_t>(k)])];
          };
          const StructuredStencil stencil{at(0), at(1), at(2), at(3), at(4), at(5), at(6), at(7)};
          updated[c] = structured_laplace_update(stencil, predicted[c], current[c]);
          break;
        }
        case Neighbourhood::ring: {
          std::vector<Vector3> ring;
          ring.reserve(front.ring[c].size());
          for (int entry : front.ring[c]) ring.push_back(ring_position(entry, positions, symmetry_y));
          updated[c] = prism_laplace_update(ring, positions[c], predicted[c], current[c]);
          break;
        }
        case Neighbourhood::free: {
          // No Laplace stencil on an open fan: the direction of the step is averaged
          // with the directions of the fan's lines (length kept).
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
          if (sum.norm() > 0.0) updated[c] = current[c] + length * sum.normalized();
          break;
        }
      }
      if (front.on_symmetry[c]) updated[c].y() = symmetry_y;
    });
    positions.swap(updated);
    updated = positions;
  }
  return positions;
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
