// First directions of the two lines at a junction. At the end of a swept blunt base a
// junction line serves the base's face, which looks downstream and inboard, and the
// tip's, which looks outboard. Their angle-weighted normal is the base's (its corner is
// the widest), so the line leaned inboard: the tip's corner folded under it, and the
// wrap face's first triangle (the two lines and their node) turned over, since a line
// along the sheet's free edge opens nothing across it. Random wings with a base swept
// 33-38 degrees stopped the junction's faces at the first layer and left the hull open.
#include <algorithm>

#include "junction.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/mesh/visible_direction.hpp"

namespace mixmesh::march_detail {

namespace {

// The direction in which the wrap face opens at a junction line: in the sheet's
// surface, across its free edge (from the line to `sheet_column`), away from the sheet's
// faces at the line.
Vector3 wrap_opening(const Front& front, const std::vector<Vector3>& points,
                     const std::vector<char>& face_active, int line, int sheet_column) {
  const Vector3 along =
      points[static_cast<std::size_t>(sheet_column)] - points[static_cast<std::size_t>(line)];
  if (along.norm() == 0.0) return Vector3::Zero();
  Vector3 inward = Vector3::Zero();
  for (int face : front.column_faces[static_cast<std::size_t>(line)]) {
    const FrontFace& sheet = front.faces[static_cast<std::size_t>(face)];
    if (sheet.wall || !face_active[static_cast<std::size_t>(face)]) continue;
    Vector3 centre = Vector3::Zero();
    for (int k = 0; k < sheet.corner_count; ++k)
      centre += points[static_cast<std::size_t>(sheet.columns[static_cast<std::size_t>(k)])];
    inward += centre / sheet.corner_count - points[static_cast<std::size_t>(line)];
  }
  const Vector3 edge = along.normalized();
  const Vector3 outward = -(inward - inward.dot(edge) * edge);
  return outward.norm() > 0.0 ? Vector3(outward.normalized()) : Vector3::Zero();
}

}  // namespace

std::vector<Vector3> junction_directions(const Front& front, const std::vector<Vector3>& points,
                                         const std::vector<char>& face_active) {
  std::vector<Vector3> directions(points.size(), Vector3::Zero());
  for (const Junction& junction : front.junctions)
    for (int end : {0, 1}) {
      const int line = front.faces[static_cast<std::size_t>(junction.face)].columns[end == 0 ? 0 : 3];
      std::vector<Vector3> normals = wall_face_normals(front, points, face_active, line);
      const Vector3 opening =
          wrap_opening(front, points, face_active, line, junction.sheet[static_cast<std::size_t>(end)]);
      if (opening.squaredNorm() > 0.0) normals.insert(normals.begin(), opening);
      directions[static_cast<std::size_t>(line)] = visible_direction(normals);
    }
  return directions;
}

}  // namespace mixmesh::march_detail
