#include "mixmesh/mesh/cell_geometry.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace mixmesh {

Vector3 cell_centre(CellType type, const std::vector<Vector3>& points, const Index* nodes) {
  const int count = node_count(type);
  Vector3 sum = Vector3::Zero();
  for (int local = 0; local < count; ++local) sum += points[static_cast<std::size_t>(nodes[local])];
  return sum / count;
}

Vector3 face_area_vector(const std::vector<Vector3>& points, const Index* nodes, int count) {
  Vector3 normal = Vector3::Zero();
  for (int corner = 0; corner < count; ++corner) {
    const Vector3& from = points[static_cast<std::size_t>(nodes[corner])];
    const Vector3& to = points[static_cast<std::size_t>(nodes[(corner + 1) % count])];
    normal += from.cross(to);
  }
  return 0.5 * normal;
}

int inverted_face_pyramids(CellType type, const std::vector<Vector3>& points, const Index* nodes) {
  // A tetrahedron's centroid (which the construction below gives exactly) lies inside
  // it whenever its volume is positive.
  if (type == CellType::tetrahedron) return 0;
  const CellDescriptor& cell = descriptor(type);
  auto at = [&](int local) -> const Vector3& { return points[static_cast<std::size_t>(nodes[local])]; };
  std::array<Vector3, 6> face_centres, face_areas;  // outward area vectors (faces wind outward)
  Vector3 estimate = Vector3::Zero();
  for (int face = 0; face < cell.face_count; ++face) {
    const LocalFace& local = cell.faces[face];
    Vector3 average = Vector3::Zero();
    for (int corner = 0; corner < local.node_count; ++corner) average += at(local.nodes[corner]);
    average /= local.node_count;
    Vector3 area = Vector3::Zero(), weighted = Vector3::Zero();
    double total = 0.0;
    for (int corner = 0; corner < local.node_count; ++corner) {
      const Vector3& from = at(local.nodes[corner]);
      const Vector3& to = at(local.nodes[(corner + 1) % local.node_count]);
      const Vector3 normal = (to - from).cross(average - from);
      const double magnitude = normal.norm();
      area += normal;
      weighted += magnitude * (from + to + average);
      total += magnitude;
    }
    face_areas[face] = 0.5 * area;
    face_centres[face] = total > 0.0 ? Vector3(weighted / (3.0 * total)) : average;
    estimate += face_centres[face];
  }
  estimate /= cell.face_count;
  Vector3 centroid = Vector3::Zero();
  double volume = 0.0;
  for (int face = 0; face < cell.face_count; ++face) {
    const double pyramid = std::max(face_areas[face].dot(face_centres[face] - estimate), 1e-300);
    centroid += pyramid * (0.75 * face_centres[face] + 0.25 * estimate);
    volume += pyramid;
  }
  centroid /= volume;
  int inverted = 0;
  for (int face = 0; face < cell.face_count; ++face)
    inverted += !(face_areas[face].dot(face_centres[face] - centroid) > 0.0);
  return inverted;
}

CellShape cell_shape(CellType type, const std::vector<Vector3>& points, const Index* nodes) {
  const CellDescriptor& cell = descriptor(type);
  auto at = [&](int local) -> const Vector3& { return points[static_cast<std::size_t>(nodes[local])]; };
  const Vector3 centre = cell_centre(type, points, nodes);

  CellShape shape;
  double volume6 = 0.0;
  for (int face = 0; face < cell.face_count; ++face) {
    const LocalFace& local = cell.faces[face];
    // Outward faces: the tetrahedron (a, b, c, centre) is positive when the face is
    // seen counter-clockwise from outside, so the sign is flipped.
    if (local.node_count == 3) {
      const double part =
          -tetrahedron_volume6(at(local.nodes[0]), at(local.nodes[1]), at(local.nodes[2]), centre);
      volume6 += part;
      shape.negative_subtetrahedra += part <= 0.0;
      continue;
    }
    const Vector3 face_centre =
        0.25 * (at(local.nodes[0]) + at(local.nodes[1]) + at(local.nodes[2]) + at(local.nodes[3]));
    for (int corner = 0; corner < 4; ++corner) {
      const double part = -tetrahedron_volume6(at(local.nodes[corner]), at(local.nodes[(corner + 1) % 4]),
                                               face_centre, centre);
      volume6 += part;
      shape.negative_subtetrahedra += part <= 0.0;
    }
  }
  shape.volume = volume6 / 6.0;

  shape.min_corner_jacobian = 1e300;
  for (int corner = 0; corner < cell.corner_count; ++corner) {
    const Corner& local = cell.corners[corner];
    const Vector3 first = at(local.neighbours[0]) - at(local.node);
    const Vector3 second = at(local.neighbours[1]) - at(local.node);
    const Vector3 third = at(local.neighbours[2]) - at(local.node);
    const double lengths = first.norm() * second.norm() * third.norm();
    const double determinant = first.cross(second).dot(third);
    const double scaled = lengths > 0.0 ? determinant / lengths : -1.0;
    shape.negative_corners += scaled <= 0.0;
    if (scaled < shape.min_corner_jacobian) shape.min_corner_jacobian = scaled;
  }
  return shape;
}

double signed_volume(CellType type, const std::vector<Vector3>& points, const Index* nodes) {
  return cell_shape(type, points, nodes).volume;
}

std::optional<Vector3> tetrahedron_circumcentre(const Vector3& a, const Vector3& b, const Vector3& c,
                                                const Vector3& d) {
  // |x - a|^2 = |x - p|^2 for p = b, c, d: (p - a) . (x - a) = |p - a|^2 / 2.
  Eigen::Matrix3d rows;
  rows << (b - a).transpose(), (c - a).transpose(), (d - a).transpose();
  const Vector3 right(0.5 * (b - a).squaredNorm(), 0.5 * (c - a).squaredNorm(), 0.5 * (d - a).squaredNorm());
  if (!(std::abs(rows.determinant()) > 0.0)) return std::nullopt;
  const Vector3 centre = a + rows.inverse() * right;
  if (!centre.allFinite()) return std::nullopt;
  return centre;
}

double largest_dihedral_degrees(const Vector3& a, const Vector3& b, const Vector3& c, const Vector3& d) {
  // Unit normals of the faces opposite each vertex, turned away from it. The dihedral
  // angle at an edge is 180 degrees less the angle between the outward normals of its
  // two faces, so the largest one belongs to the two normals closest in direction.
  const std::array<const Vector3*, 4> p{&a, &b, &c, &d};
  std::array<Vector3, 4> normal;
  for (int i = 0; i < 4; ++i) {
    const Vector3& x = *p[static_cast<std::size_t>((i + 1) % 4)];
    const Vector3& y = *p[static_cast<std::size_t>((i + 2) % 4)];
    const Vector3& z = *p[static_cast<std::size_t>((i + 3) % 4)];
    Vector3 n = (y - x).cross(z - x);
    const double length = n.norm();
    if (!(length > 0.0)) return 180.0;
    n /= length;
    if (n.dot(*p[static_cast<std::size_t>(i)] - x) > 0.0) n = -n;
    normal[static_cast<std::size_t>(i)] = n;
  }
  double closest = -1.0;
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = i + 1; j < 4; ++j) closest = std::max(closest, normal[i].dot(normal[j]));
  return 180.0 - std::acos(std::clamp(closest, -1.0, 1.0)) * 180.0 / M_PI;
}

}  // namespace mixmesh
