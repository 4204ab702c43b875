#include "concave_corners.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mixmesh/mesh/cell_geometry.hpp"

namespace mixmesh::march_detail {

namespace {

// Corner thickness at the corner and its growth with the distance from it, both a
// quarter: a line at distance d from the corner then marches d / 4 + size / 4 <= d / 2
// (for d >= size), so its top stays half way between the corner line's and its own
// offset without the corner.
constexpr double corner_fraction = 0.25;
constexpr double corner_slope = 0.25;
// Wall and sheet faces meet at a concave corner when the angle between their normals is
// at least this (the domain's angle there is at most 180 - 30 degrees). At a sharp
// trailing edge the wall faces and the sheet meet at half the edge's angle.
constexpr double corner_normal_degrees = 30.0;

Vector3 centre(const std::vector<Vector3>& points, const FrontFace& face) {
  Vector3 sum = Vector3::Zero();
  for (int k = 0; k < face.corner_count; ++k)
    sum += points[static_cast<std::size_t>(face.columns[static_cast<std::size_t>(k)])];
  return sum / face.corner_count;
}

double segment_distance(const Vector3& point, const Vector3& start, const Vector3& end) {
  const Vector3 along = end - start;
  const double length = along.squaredNorm();
  const double t = length > 0.0 ? std::clamp((point - start).dot(along) / length, 0.0, 1.0) : 0.0;
  return (point - (start + t * along)).norm();
}

}  // namespace

std::vector<ConcaveCorner> concave_corners(const Front& front, const std::vector<Vector3>& points) {
  std::vector<ConcaveCorner> corners;
  const double least_cosine = std::cos(corner_normal_degrees * M_PI / 180.0);
  for (const SharedEdge& edge : front.shared_edges) {
    const FrontFace& first = front.faces[static_cast<std::size_t>(edge.faces[0])];
    const FrontFace& second = front.faces[static_cast<std::size_t>(edge.faces[1])];
    if (first.wall == second.wall || first.wrap || second.wrap || first.split || second.split) continue;
    const FrontFace& wall = first.wall ? first : second;
    const FrontFace& sheet = first.wall ? second : first;
    const int corner = first.wall ? edge.corners[0] : edge.corners[1];
    const Vector3& start = points[static_cast<std::size_t>(wall.columns[static_cast<std::size_t>(corner)])];
    const Vector3& end = points[static_cast<std::size_t>(
        wall.columns[static_cast<std::size_t>((corner + 1) % wall.corner_count)])];
    const double length = (end - start).norm();
    const Vector3 wall_area = face_area_vector(points, wall.columns.data(), wall.corner_count);
    const Vector3 sheet_area = face_area_vector(points, sheet.columns.data(), sheet.corner_count);
    if (!(length > 0.0) || wall_area.norm() == 0.0 || sheet_area.norm() == 0.0) continue;
    const Vector3 wall_normal = wall_area.normalized();
    // Concave: the sheet lies on the side the wall faces, and turns away from the wall's
    // plane by more than a trailing edge's half angle.
    if (wall_normal.dot(sheet_area.normalized()) > least_cosine) continue;
    if ((centre(points, sheet) - 0.5 * (start + end)).dot(wall_normal) <= 0.0) continue;
    // A face's height over the edge: its area over the edge's length (twice that for a
    // triangle).
    const auto height = [&](const FrontFace& face, const Vector3& area) {
      return (face.corner_count == 3 ? 2.0 : 1.0) * area.norm() / length;
    };
    const double size = std::min(height(wall, wall_area), height(sheet, sheet_area));
    corners.push_back({start, end, size});
  }
  return corners;
}

std::vector<double> corner_thickness_limits(const std::vector<ConcaveCorner>& corners,
                                            const std::vector<Vector3>& points) {
  std::vector<double> limit(points.size(), std::numeric_limits<double>::infinity());
  for (std::size_t c = 0; c < points.size(); ++c)
    for (const ConcaveCorner& corner : corners)
      limit[c] = std::min(limit[c], corner_fraction * corner.size +
                                        corner_slope * segment_distance(points[c], corner.start, corner.end));
  return limit;
}

}  // namespace mixmesh::march_detail
