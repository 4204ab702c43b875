// One deformation step and sequences of them: boundary motion, method, checks.
#include "mixmesh/deform/deform.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "deform/deform_quality.hpp"
#include "deform/dual_mesh.hpp"
#include "deform/rotation.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/quality/validity.hpp"

namespace mixmesh::deform {

DeformResult deform_step(const MixedMesh& mesh, const MixedMesh& reference, const Motion& motion, int step,
                         DeformationMethod& method, const Log& log, const DeformOptions& options) {
  (void)options;
  Stopwatch clock;
  const BoundaryMotion boundary = boundary_motion(mesh, reference, motion, step);
  std::vector<Vector3> points = method.move(mesh, boundary, log);
  if (points.size() != mesh.points.size())
    throw Error(method.name() + ": returned " + std::to_string(points.size()) + " points for " +
                std::to_string(mesh.points.size()));
  // The framework owns the boundary: prescribed nodes exactly where the motion says,
  // symmetry nodes in their planes, whatever the method did.
  for (std::size_t node = 0; node < points.size(); ++node) {
    if (boundary.roles[node] == NodeRole::prescribed)
      points[node] = mesh.points[node] + boundary.displacement[node];
    if (!points[node].allFinite())
      throw Error(method.name() + ": non-finite position for node " + std::to_string(node) + " at " +
                  point_text(mesh.points[node]));
  }
  detail::project_sliding(boundary, mesh.points, points);

  DeformResult result;
  result.mesh = mesh;
  result.mesh.points = std::move(points);
  result.seconds = clock.seconds();

  // One dual mesh and one set of wall lines (chosen on the undeformed mesh) serve the
  // figures before and after: the cells are the same, only the points moved.
  const detail::DualMesh dual = detail::build_dual_mesh(mesh);
  const WallLines lines = detail::wall_lines(mesh, dual, boundary.marker_roles);
  result.before = detail::summarise_quality(mesh, dual, lines);
  result.after = detail::summarise_quality(result.mesh, dual, lines);
  result.invalid_count = result.after.invalid_cells;
  for (std::size_t cell = 0; cell < dual.cell_count() && result.invalid_examples.size() < 5 &&
                             result.invalid_examples.size() < result.invalid_count;
       ++cell) {
    if (detail::cell_valid(dual, cell, result.mesh.points)) continue;
    result.invalid_examples.push_back({detail::cell_kind_name(dual.cell_kind[cell]),
                                       dual.index_in_block[cell],
                                       detail::cell_centre(dual, cell, result.mesh.points)});
  }
  const ValidityReport validity = validate(result.mesh);
  result.valid = result.invalid_count == 0 && validity.valid();
  if (result.invalid_count == 0 && !validity.valid()) log.warning("deformed mesh: " + validity.summary());

  const std::vector<double> before = wall_angles(mesh, lines);
  const std::vector<double> after = wall_angles(result.mesh, lines);
  for (std::size_t entry = 0; entry < before.size(); ++entry) {
    const double change = std::abs(after[entry] - before[entry]);
    if (!std::isfinite(change)) continue;
    const std::size_t node = static_cast<std::size_t>(lines.wall_nodes[entry]);
    if (boundary.body[node] < 0) {
      result.fixed_wall_angle_change = std::max(result.fixed_wall_angle_change, change);
    } else if (change > result.max_wall_angle_change) {
      result.max_wall_angle_change = change;
      result.max_wall_angle_change_location = mesh.points[node];
    }
  }
  std::ostringstream summary;
  summary << "step " << step << '/' << motion.steps << " (" << method.name() << "): " << result.seconds
          << " s, min scaled Jacobian " << result.before.min_scaled_jacobian << " -> "
          << result.after.min_scaled_jacobian << ", wall-line angle change up to "
          << result.max_wall_angle_change << " deg at " << point_text(result.max_wall_angle_change_location)
          << " (fixed walls " << result.fixed_wall_angle_change << " deg), invalid cells "
          << result.invalid_count;
  log.info(summary.str());
  return result;
}

void deform_sequence(const MixedMesh& mesh, const Motion& motion, DeformationMethod& method, const Log& log,
                     const DeformOptions& options,
                     const std::function<void(int step, const DeformResult& result)>& each_step) {
  const ValidityReport input = validate(mesh);
  if (!input.valid()) throw Error("the mesh to deform is itself invalid: " + input.summary());
  MixedMesh previous;
  for (int step = 1; step <= motion.steps; ++step) {
    const MixedMesh& start = motion.incremental && step > 1 ? previous : mesh;
    DeformResult result = deform_step(start, mesh, motion, step, method, log, options);
    if (!result.valid && !options.keep_invalid) {
      std::ostringstream message;
      message << "step " << step << ": " << result.invalid_count << " cells stay inverted after repair";
      for (const InvalidCell& cell : result.invalid_examples)
        message << "; " << cell.entity << ' ' << cell.index << " at " << point_text(cell.location);
      if (result.invalid_count == 0) message << " (" << validate(result.mesh).summary() << ')';
      message << "; nothing written";
      if (!options.invalid_advice.empty()) message << " (" << options.invalid_advice << ')';
      throw Error(message.str());
    }
    each_step(step, result);
    if (motion.incremental) previous = std::move(result.mesh);
  }
}

}  // namespace mixmesh::deform
