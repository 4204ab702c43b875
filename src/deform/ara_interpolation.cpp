// The ARA interpolation to nodes and its negative-volume repair (Martineau & Georgala
// eq. 22–27): see ara_stages.hpp.
#include <algorithm>
#include <cmath>

#include "deform/ara_stages.hpp"
#include "deform/rotation.hpp"

namespace mixmesh::deform::detail {

namespace {

// The position of `node` interpolated from its cells' rigid motions (eq. 22–26); in a
// repair pass, weighted towards the cells that are small or inverted (eq. 27).
Vector3 interpolate(const AraGeometry& geometry, const std::vector<Vector3>& points, const CellMotion& motion,
                    std::size_t node, int repair_pass, const std::vector<double>* deformed_volume) {
  const DualMesh& dual = geometry.dual;
  const bool rotate = !motion.turn.empty();
  auto candidate = [&](std::size_t cell) -> Vector3 {
    // x′_j = R_j(x_i − c_j) + c_j + u_j: the node moved rigidly with cell j (eq. 23).
    if (!rotate) return points[node] + motion.velocity[cell];
    return points[node] + motion.velocity[cell] + motion.turn[cell] * (points[node] - geometry.centres[cell]);
  };
  const std::size_t begin = dual.point_cell_offsets[node];
  const std::size_t end = dual.point_cell_offsets[node + 1];
  double volume_average = 0.0;
  if (repair_pass > 0) {
    for (std::size_t slot = begin; slot < end; ++slot)
      volume_average += std::abs((*deformed_volume)[static_cast<std::size_t>(dual.point_cells[slot])]);
    volume_average /= static_cast<double>(end - begin);
  }
  Vector3 sum = Vector3::Zero();
  double total = 0.0;
  for (std::size_t slot = begin; slot < end; ++slot) {
    const std::size_t cell = static_cast<std::size_t>(dual.point_cells[slot]);
    double weight = geometry.node_weights[slot];
    if (repair_pass > 0) {
      // Eq. 27 (reconstructed): ω′ = ω (1 + m V_ave / V_j); inverted and tiny cells are
      // clamped to a thousandth of V_ave, so they weigh most.
      const double own = std::max((*deformed_volume)[cell], 1e-3 * volume_average);
      weight *= 1.0 + repair_pass * volume_average / own;
    }
    sum += weight * candidate(cell);
    total += weight;
  }
  if (total <= 0.0) {  // every weight clipped: plain average
    sum = Vector3::Zero();
    for (std::size_t slot = begin; slot < end; ++slot)
      sum += candidate(static_cast<std::size_t>(dual.point_cells[slot]));
    total = static_cast<double>(end - begin);
  }
  return Vector3(sum / total);
}

}  // namespace

std::vector<Vector3> interpolate_to_nodes(const AraGeometry& geometry, const std::vector<Vector3>& points,
                                          const BoundaryMotion& boundary, const CellMotion& motion) {
  const DualMesh& dual = geometry.dual;
  std::vector<Vector3> result(points.size());
  parallel_items(points.size(), [&](std::size_t node) {
    const std::size_t begin = dual.point_cell_offsets[node];
    const std::size_t end = dual.point_cell_offsets[node + 1];
    if (boundary.roles[node] == NodeRole::prescribed || begin == end) {
      result[node] = points[node] + boundary.displacement[node];
      return;
    }
    result[node] = interpolate(geometry, points, motion, node, 0, nullptr);
  });
  project_sliding(boundary, points, result);
  return result;
}

RepairOutcome repair_inverted_cells(const AraGeometry& geometry, const std::vector<Vector3>& points,
                                    const BoundaryMotion& boundary, const CellMotion& motion, int passes,
                                    std::vector<Vector3>& moved) {
  const DualMesh& dual = geometry.dual;
  const std::size_t cells = dual.cell_count();
  std::vector<double> deformed_volume(cells);
  std::vector<char> invalid(cells, 0);
  parallel_items(cells, [&](std::size_t cell) {
    deformed_volume[cell] = cell_measure(dual, cell, moved);
    invalid[cell] = !cell_valid(dual, cell, moved);
  });
  std::size_t inverted = static_cast<std::size_t>(std::count(invalid.begin(), invalid.end(), 1));
  RepairOutcome outcome;
  outcome.inverted_after_interpolation = inverted;
  // A pass can make things worse where the cells' rigid motions disagree; the result
  // with the fewest inverted cells is the one returned.
  std::vector<Vector3> best;
  if (inverted > 0) best = moved;
  std::size_t best_inverted = inverted;
  std::vector<char> touched(points.size(), 0);
  for (int pass = 1; pass <= passes && inverted > 0; ++pass) {
    std::vector<Index> nodes;
    for (std::size_t cell = 0; cell < cells; ++cell) {
      if (!invalid[cell]) continue;
      for (int local = 0; local < dual.cell_size(cell); ++local) {
        const Index node = dual.nodes(cell)[local];
        if (boundary.roles[static_cast<std::size_t>(node)] == NodeRole::prescribed) continue;
        if (touched[static_cast<std::size_t>(node)] == pass) continue;
        touched[static_cast<std::size_t>(node)] = static_cast<char>(pass);
        nodes.push_back(node);
      }
    }
    std::vector<Vector3> updated(nodes.size());
    parallel_items(nodes.size(), [&](std::size_t slot) {
      updated[slot] = interpolate(geometry, points, motion, static_cast<std::size_t>(nodes[slot]), pass,
                                  &deformed_volume);
    });
    for (std::size_t slot = 0; slot < nodes.size(); ++slot)
      moved[static_cast<std::size_t>(nodes[slot])] = updated[slot];
    project_sliding(boundary, points, moved);
    // Only the cells of the moved nodes change: checking those alone instead of every
    // cell gives the same count (a full check of the M6's 701 k cells took 0.1–0.2 s a pass).
    const std::vector<Index> changed = cells_of_nodes(dual, nodes);
    parallel_items(changed.size(), [&](std::size_t slot) {
      const std::size_t cell = static_cast<std::size_t>(changed[slot]);
      deformed_volume[cell] = cell_measure(dual, cell, moved);
      invalid[cell] = !cell_valid(dual, cell, moved);
    });
    inverted = static_cast<std::size_t>(std::count(invalid.begin(), invalid.end(), 1));
    outcome.passes = pass;
    if (inverted < best_inverted) {
      best = moved;
      best_inverted = inverted;
    }
  }
  if (inverted > best_inverted) moved = std::move(best);
  outcome.inverted_after_repair = std::min(inverted, best_inverted);
  return outcome;
}

}  // namespace mixmesh::deform::detail
