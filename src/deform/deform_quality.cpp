// Quality before and after a deformation: scaled Jacobian, near-wall orthogonality,
// sliver histogram.
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "deform/deform_quality.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/quality/cell_quality.hpp"

namespace mixmesh::deform {

namespace {

constexpr double degrees_per_radian = 180.0 / 3.14159265358979323846;

bool is_wall(const std::vector<MarkerRole>& roles, int marker) {
  return marker < 0 || static_cast<std::size_t>(marker) >= roles.size() ||
         roles[static_cast<std::size_t>(marker)] != MarkerRole::sliding;
}

// Normal of a wall face (planar: edge) in the order its nodes are stored.
Vector3 face_normal(const std::vector<Vector3>& points, const Index* nodes, int count) {
  if (count == 2) {
    const Vector3 along =
        points[static_cast<std::size_t>(nodes[1])] - points[static_cast<std::size_t>(nodes[0])];
    return {-along.y(), along.x(), 0.0};
  }
  return face_area_vector(points, nodes, count);
}

}  // namespace

WallLines wall_lines(const MixedMesh& mesh, const std::vector<MarkerRole>& marker_roles) {
  return detail::wall_lines(mesh, detail::build_dual_mesh(mesh), marker_roles);
}

QualitySummary summarise_quality(const MixedMesh& mesh, const std::vector<MarkerRole>& marker_roles) {
  const detail::DualMesh dual = detail::build_dual_mesh(mesh);
  return detail::summarise_quality(mesh, dual,
                                   wall_angles(mesh, detail::wall_lines(mesh, dual, marker_roles)));
}

WallLines detail::wall_lines(const MixedMesh& mesh, const DualMesh& dual,
                             const std::vector<MarkerRole>& marker_roles) {
  WallLines lines;
  lines.face_offsets.push_back(0);
  std::vector<char> on_wall(mesh.points.size(), 0);
  // A line may not end on a wall or far-field face, but may on a sliding plane: the
  // grid lines of a wall node on a symmetry plane run in it, and in a one-cell-thick
  // quasi-2D mesh every node is on one of its two planes.
  std::vector<char> on_boundary(mesh.points.size(), 0);
  for (std::size_t face = 0; face < dual.face_count(); ++face) {
    if (!is_wall(marker_roles, dual.face_marker[face])) continue;
    const Index* nodes = dual.boundary_nodes(face);
    const int count = dual.face_size(face);
    for (int local = 0; local < count; ++local) on_boundary[static_cast<std::size_t>(nodes[local])] = 1;
    std::vector<Index> ordered(nodes, nodes + count);
    const Vector3 inward =
        detail::cell_centre(dual, static_cast<std::size_t>(dual.face_cell[face]), mesh.points) -
        detail::face_centre(dual, face, mesh.points);
    if (face_normal(mesh.points, ordered.data(), count).dot(inward) < 0.0)
      std::reverse(ordered.begin(), ordered.end());
    lines.face_nodes.insert(lines.face_nodes.end(), ordered.begin(), ordered.end());
    lines.face_offsets.push_back(lines.face_nodes.size());
    for (Index node : ordered) on_wall[static_cast<std::size_t>(node)] = 1;
  }
  // Node normals, then the best edge leaving each wall node.
  std::vector<Vector3> normal(mesh.points.size(), Vector3::Zero());
  for (std::size_t face = 0; face + 1 < lines.face_offsets.size(); ++face) {
    const Index* nodes = lines.face_nodes.data() + lines.face_offsets[face];
    const int count = static_cast<int>(lines.face_offsets[face + 1] - lines.face_offsets[face]);
    const Vector3 face_direction = face_normal(mesh.points, nodes, count).normalized();
    for (int local = 0; local < count; ++local)
      normal[static_cast<std::size_t>(nodes[local])] += face_direction;
  }
  std::vector<double> best_cosine(mesh.points.size(), -2.0);
  std::vector<Index> best_end(mesh.points.size(), -1);
  auto consider = [&](Index from, Index to) {
    const std::size_t at = static_cast<std::size_t>(from);
    if (!on_wall[at] || on_boundary[static_cast<std::size_t>(to)]) return;
    const Vector3 edge = mesh.points[static_cast<std::size_t>(to)] - mesh.points[at];
    const double cosine = edge.normalized().dot(normal[at].normalized());
    if (cosine > best_cosine[at]) {
      best_cosine[at] = cosine;
      best_end[at] = to;
    }
  };
  for (std::size_t cell = 0; cell < dual.cell_count(); ++cell)
    detail::for_each_cell_edge(dual, cell, [&](Index from, Index to) {
      consider(from, to);
      consider(to, from);
    });
  for (std::size_t node = 0; node < mesh.points.size(); ++node) {
    if (!on_wall[node]) continue;
    lines.wall_nodes.push_back(static_cast<Index>(node));
    lines.line_ends.push_back(best_end[node]);
  }
  return lines;
}

std::vector<double> wall_angles(const MixedMesh& mesh, const WallLines& lines) {
  std::vector<Vector3> normal(mesh.points.size(), Vector3::Zero());
  for (std::size_t face = 0; face + 1 < lines.face_offsets.size(); ++face) {
    const Index* nodes = lines.face_nodes.data() + lines.face_offsets[face];
    const int count = static_cast<int>(lines.face_offsets[face + 1] - lines.face_offsets[face]);
    const Vector3 direction = face_normal(mesh.points, nodes, count).normalized();
    for (int local = 0; local < count; ++local) normal[static_cast<std::size_t>(nodes[local])] += direction;
  }
  std::vector<double> angles(lines.wall_nodes.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t entry = 0; entry < lines.wall_nodes.size(); ++entry) {
    if (lines.line_ends[entry] < 0) continue;
    const std::size_t node = static_cast<std::size_t>(lines.wall_nodes[entry]);
    const Vector3 edge = mesh.points[static_cast<std::size_t>(lines.line_ends[entry])] - mesh.points[node];
    const double cosine = std::clamp(edge.normalized().dot(normal[node].normalized()), -1.0, 1.0);
    angles[entry] = std::acos(cosine) * degrees_per_radian;
  }
  return angles;
}

QualitySummary detail::summarise_quality(const MixedMesh& mesh, const DualMesh& dual,
                                         const std::vector<double>& angles,
                                         const std::vector<char>* invalid) {
  QualitySummary summary;
  struct Partial {
    double min_jacobian = std::numeric_limits<double>::infinity();
    std::size_t invalid = 0;
    std::array<std::size_t, 10> slivers{};
  };
  const Partial total = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, dual.cell_count()), Partial{},
      [&](const tbb::blocked_range<std::size_t>& range, Partial partial) {
        for (std::size_t cell = range.begin(); cell != range.end(); ++cell) {
          const int kind = dual.cell_kind[cell];
          const Index* nodes = dual.nodes(cell);
          const double jacobian =
              kind >= detail::planar_triangle
                  ? scaled_jacobian(kind == detail::planar_triangle ? FaceType::triangle : FaceType::quad,
                                    mesh.points, nodes)
                  : scaled_jacobian(static_cast<CellType>(kind), mesh.points, nodes);
          partial.min_jacobian = std::min(partial.min_jacobian, jacobian);
          partial.invalid += invalid ? static_cast<std::size_t>((*invalid)[cell])
                                     : static_cast<std::size_t>(!detail::cell_valid(dual, cell, mesh.points));
          if (kind == index(CellType::tetrahedron)) {
            const double eta = sliver(mesh.points, nodes);
            const int bin = std::clamp(static_cast<int>(eta / 0.0745), 0, 9);
            ++partial.slivers[static_cast<std::size_t>(bin)];
          }
        }
        return partial;
      },
      [](Partial a, const Partial& b) {
        a.min_jacobian = std::min(a.min_jacobian, b.min_jacobian);
        a.invalid += b.invalid;
        for (std::size_t bin = 0; bin < a.slivers.size(); ++bin) a.slivers[bin] += b.slivers[bin];
        return a;
      });
  summary.min_scaled_jacobian = total.min_jacobian;
  summary.invalid_cells = total.invalid;
  summary.sliver_histogram = total.slivers;
  double sum = 0.0;
  std::size_t count = 0;
  for (double angle : angles) {
    if (!std::isfinite(angle)) continue;
    summary.max_wall_angle = std::max(summary.max_wall_angle, angle);
    sum += angle;
    ++count;
  }
  summary.mean_wall_angle = count > 0 ? sum / static_cast<double>(count) : 0.0;
  return summary;
}

}  // namespace mixmesh::deform
