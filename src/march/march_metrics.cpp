#include "mixmesh/march/march_metrics.hpp"

#include <algorithm>
#include <cmath>

#include "mixmesh/core/error.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"

namespace mixmesh {

namespace {

double degrees(double radians) {
  return radians * 180.0 / std::acos(-1.0);
}

double angle_between(const Vector3& a, const Vector3& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

double percentile(std::vector<double> values, double fraction) {
  if (values.empty()) return 0.0;
  const auto rank = static_cast<std::size_t>(std::ceil(fraction * static_cast<double>(values.size())));
  const std::size_t position = std::min(rank > 0 ? rank - 1 : 0, values.size() - 1);
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(position), values.end());
  return values[position];
}

}  // namespace

MarchMetrics measure_march(const BoundaryLayer& layer, const SurfaceMesh& surface, const std::string& patch) {
  MarchMetrics metrics;
  const MixedMesh& mesh = layer.mesh;
  metrics.minimum_scaled_jacobian = 1.0;
  for (CellType type : all_cell_types)
    for (std::size_t cell = 0; cell < mesh.cell_count(type); ++cell) {
      const CellShape shape = cell_shape(type, mesh.points, mesh.cell(type, cell));
      metrics.invalid_cells += !shape.valid();
      if (type == CellType::tetrahedron) continue;  // the junction's needle (march_layers.hpp)
      double& minimum = type == CellType::pyramid ? metrics.junction_minimum_scaled_jacobian
                                                  : metrics.minimum_scaled_jacobian;
      minimum = std::min(minimum, shape.min_corner_jacobian);
    }

  // Wall normal per line: angle-weighted corner normals of its wall faces (wake
  // faces are not walls); a line is measured when one of them is on the patch.
  const std::size_t column_count = layer.column_points.size();
  std::vector<Vector3> wall_normal(column_count, Vector3::Zero());
  std::vector<char> measured(column_count, 0);
  auto point = [&](int column, std::size_t level) -> const Vector3& {
    return mesh
        .points[static_cast<std::size_t>(layer.column_points[static_cast<std::size_t>(column)][level])];
  };
  auto add_corner = [&](int column, const Vector3& out, const Vector3& in) {
    const Vector3 corner = out.cross(in);
    if (corner.norm() > 0.0)
      wall_normal[static_cast<std::size_t>(column)] += angle_between(out, in) * corner.normalized();
  };
  for (std::size_t face = 0; face < layer.face_columns.size(); ++face) {
    if (!layer.face_wall[face]) continue;
    const bool on_patch =
        patch.empty() || layer.region_names[static_cast<std::size_t>(layer.face_patch[face])] == patch;
    const auto& columns = layer.face_columns[face];
    const int n = static_cast<int>(columns.size());
    // The wall faces' own corners. A face split at a junction (march_layers.hpp) is the
    // wall triangle (t, a, b) with two lines from t: both lines get that triangle's real
    // corner at t, so they are measured against the wall around them (the wing face on
    // their side and the tip cap), not against the opening the march chooses for them.
    const bool split = n == 4 && point(columns[0], 0) == point(columns[3], 0);
    for (int k = 0; k < n; ++k) {
      const int column = columns[static_cast<std::size_t>(k)];
      if (on_patch) measured[static_cast<std::size_t>(column)] = 1;
      const Vector3& here = point(column, 0);
      if (split && (k == 0 || k == 3)) {
        add_corner(column, point(columns[1], 0) - here, point(columns[2], 0) - here);
        continue;
      }
      add_corner(column, point(columns[static_cast<std::size_t>((k + 1) % n)], 0) - here,
                 point(columns[static_cast<std::size_t>((k + n - 1) % n)], 0) - here);
    }
  }
  std::vector<double> deviations, turns;
  for (std::size_t column = 0; column < column_count; ++column) {
    if (!measured[column] || layer.column_points[column].size() < 2) continue;
    const auto c = static_cast<int>(column);
    Vector3 normal = wall_normal[column];
    if (surface.symmetry_tolerance >= 0.0 &&
        std::abs(point(c, 0).y() - surface.symmetry_y) <= surface.symmetry_tolerance)
      normal.y() = 0.0;  // the wall normal of a node in the symmetry plane lies in it
    deviations.push_back(degrees(angle_between(point(c, 1) - point(c, 0), normal)));
    const std::size_t levels = layer.column_points[column].size();
    // A full column's outermost step is MarchOptions::outer_layer_height's, not the
    // growth law's: its jump is left out.
    const std::size_t law_levels =
        levels == static_cast<std::size_t>(layer.report.layers_requested) + 1 ? levels - 1 : levels;
    for (std::size_t k = 1; k + 1 < levels; ++k) {
      const Vector3 below = point(c, k) - point(c, k - 1);
      const Vector3 above = point(c, k + 1) - point(c, k);
      turns.push_back(degrees(angle_between(below, above)));
      if (k + 2 < law_levels) {
        const Vector3 further = point(c, k + 2) - point(c, k + 1);
        const double jump = std::abs(further.norm() / above.norm() - above.norm() / below.norm());
        metrics.maximum_growth_jump = std::max(metrics.maximum_growth_jump, jump);
      }
    }
  }
  if (deviations.empty()) throw Error("march metrics: no marching line starts on patch '" + patch + "'");
  metrics.lines = static_cast<int>(deviations.size());
  metrics.maximum_normal_deviation_degrees = *std::max_element(deviations.begin(), deviations.end());
  metrics.percentile99_normal_deviation_degrees = percentile(deviations, 0.99);
  metrics.fraction_within_2_degrees = static_cast<double>(std::count_if(deviations.begin(), deviations.end(),
                                                                        [](double d) { return d <= 2.0; })) /
                                      static_cast<double>(deviations.size());
  if (!turns.empty()) {
    metrics.maximum_line_turn_degrees = *std::max_element(turns.begin(), turns.end());
    metrics.percentile99_line_turn_degrees = percentile(turns, 0.99);
  }
  return metrics;
}

}  // namespace mixmesh
