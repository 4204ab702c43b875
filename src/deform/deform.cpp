// One deformation step and sequences of them: boundary motion, method, checks.
#include "mixmesh/deform/deform.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>

#include "deform/deform_quality.hpp"
#include "deform/dual_mesh.hpp"
#include "deform/layer_lines.hpp"
#include "deform/rotation.hpp"
#include "deform/untangle.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/quality/validity.hpp"

namespace mixmesh::deform {

namespace {

// What a step measures on the mesh it starts from: the same for every step of a sequence
// that deforms one mesh, so deform_sequence measures it once.
struct StartMesh {
  detail::DualMesh dual;  // cells as nodes; the same for the deformed mesh
  WallLines lines;        // grid lines chosen on this mesh, kept for the deformed one
  std::vector<double> angles;
  QualitySummary quality;
  detail::LayerLines layers;  // moved with their base after the method (layer_lines.hpp)
  double layer_seconds = 0.0;
};

std::shared_ptr<const StartMesh> measure_start(const MixedMesh& mesh, const std::vector<MarkerRole>& roles,
                                               const Log& log) {
  auto start = std::make_shared<StartMesh>();
  start->dual = detail::build_dual_mesh(mesh);
  Stopwatch layer_clock;
  start->layers = detail::find_layer_lines(start->dual, roles, mesh.points);
  start->layer_seconds = layer_clock.seconds();
  const detail::LayerLines& layers = start->layers;
  log.detail("layer lines: " + std::to_string(layers.wall_columns) + " wall columns, " +
             std::to_string(layers.sheet_faces) + " sheet faces with " +
             std::to_string(layers.sheet_columns) + " columns, " + std::to_string(layers.line_nodes) +
             " line nodes, " + std::to_string(layers.columns_to_boundary) +
             " columns reach a boundary (left to the method), " + std::to_string(layers.conflicts) +
             " conflicts; " + std::to_string(start->layer_seconds) + " s");
  start->lines = detail::wall_lines(mesh, start->dual, roles);
  start->angles = wall_angles(mesh, start->lines);
  start->quality = detail::summarise_quality(mesh, start->dual, start->angles);
  return start;
}

// deform_step, with the measures of `mesh` from an earlier step when `measured` holds them
// (it is filled otherwise).
DeformResult step_from(const MixedMesh& mesh, const MixedMesh& reference, const Motion& motion, int step,
                       DeformationMethod& method, const Log& log,
                       std::shared_ptr<const StartMesh>& measured) {
  Stopwatch clock;
  const BoundaryMotion boundary = boundary_motion(mesh, reference, motion, step);
  double seconds = clock.seconds();
  // The layer lines are part of the step's time on the first step that uses them; the
  // quality measured with them is not.
  if (!measured) {
    measured = measure_start(mesh, boundary.marker_roles, log);
    seconds += measured->layer_seconds;
  }
  clock = Stopwatch();
  // The dual mesh is offered for this move() only, however it ends.
  struct Offer {
    DeformationMethod& method;
    ~Offer() { method.offer_dual_mesh(nullptr); }
  };
  method.offer_dual_mesh(&measured->dual);
  const Offer offer{method};
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
  detail::transport_layer_lines(measured->layers, boundary, mesh.points, points);
  detail::project_sliding(boundary, mesh.points, points);
  detail::keep_off_sliding_planes(boundary, mesh.points, points);
  const detail::UntangleReport untangled = detail::untangle(measured->dual, boundary, mesh.points, points);
  if (untangled.inverted_before > 0)
    log.detail("untangle: " + std::to_string(untangled.inverted_before) +
               " inverted cells after the layer transport, " + std::to_string(untangled.inverted_after) +
               " after " + std::to_string(untangled.rounds) + " rounds of affine maps" +
               (untangled.optimise_before > 0
                    ? " and the optimisation of " + std::to_string(untangled.optimise_before)
                    : std::string()) +
               " (" + std::to_string(untangled.moved_nodes) + " nodes moved)");

  DeformResult result;
  result.mesh = mesh;
  result.mesh.points = std::move(points);
  result.seconds = seconds + clock.seconds();

  // One dual mesh and one set of wall lines (chosen on the undeformed mesh) serve the
  // figures before and after: the cells are the same, only the points moved.
  const detail::DualMesh& dual = measured->dual;
  const WallLines& lines = measured->lines;
  const std::vector<double> after = wall_angles(result.mesh, lines);
  result.before = measured->quality;
  result.after = detail::summarise_quality(result.mesh, dual, after, &untangled.invalid);
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

  const std::vector<double>& before = measured->angles;
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

}  // namespace

DeformResult deform_step(const MixedMesh& mesh, const MixedMesh& reference, const Motion& motion, int step,
                         DeformationMethod& method, const Log& log) {
  std::shared_ptr<const StartMesh> measured;
  return step_from(mesh, reference, motion, step, method, log, measured);
}

std::string step_stem(const std::string& stem, int step, int steps) {
  if (steps <= 1) return stem;
  char suffix[32];
  std::snprintf(suffix, sizeof suffix, "_%04d", step);
  return stem + suffix;
}

void deform_sequence(const MixedMesh& mesh, const Motion& motion, DeformationMethod& method, const Log& log,
                     const DeformOptions& options,
                     const std::function<void(int step, const DeformResult& result)>& each_step) {
  const ValidityReport input = validate(mesh);
  if (!input.valid()) throw Error("the mesh to deform is itself invalid: " + input.summary());
  MixedMesh previous;
  std::shared_ptr<const StartMesh> measured;  // of the mesh the steps start from
  for (int step = 1; step <= motion.steps; ++step) {
    const MixedMesh& start = motion.incremental && step > 1 ? previous : mesh;
    if (motion.incremental) measured.reset();  // each step starts from the last one's mesh
    DeformResult result = step_from(start, mesh, motion, step, method, log, measured);
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
