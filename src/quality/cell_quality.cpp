#include "mixmesh/quality/cell_quality.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mixmesh/mesh/cell_geometry.hpp"

namespace mixmesh {

namespace {

constexpr double pi = 3.14159265358979323846;

const Vector3& at(const std::vector<Vector3>& points, Index node) {
  return points[static_cast<std::size_t>(node)];
}

// Factor that makes the scaled Jacobian of the regular cell 1: the inverse of its
// corner value (√2/2 tet and pyramid, √3/2 prism, 1 hex).
double jacobian_normaliser(CellType type) {
  switch (type) {
    case CellType::tetrahedron:
    case CellType::pyramid:
      return verdict_corner_factor;
    case CellType::prism:
      return 2.0 / std::sqrt(3.0);
    case CellType::hexahedron:
      break;
  }
  return 1.0;
}

// det of the normalised vectors; 0 when one of them has zero length.
double normalised_determinant(const Vector3& first, const Vector3& second, const Vector3& third) {
  const double lengths = first.norm() * second.norm() * third.norm();
  if (!(lengths > 0.0)) return lengths == 0.0 ? 0.0 : std::nan("");
  return first.cross(second).dot(third) / lengths;
}

// Worst equiangle deviation of one corner angle (radians) from the ideal angle.
double angle_skew(double angle, double ideal) {
  return std::max((angle - ideal) / (pi - ideal), (ideal - angle) / ideal);
}

// The extreme corner cosines of the triangles [0] and quads [1] of a cell; only the
// extremes need an acos, which keeps the skewness cheap.
struct CornerCosines {
  std::array<double, 2> smallest{2.0, 2.0};
  std::array<double, 2> largest{-2.0, -2.0};
  bool finite = true;

  void add_polygon(const std::vector<Vector3>& points, const Index* nodes, const int* local, int count) {
    const std::size_t kind = count == 3 ? 0 : 1;
    for (int corner = 0; corner < count; ++corner) {
      const Vector3& here = at(points, nodes[local[corner]]);
      const Vector3 previous = at(points, nodes[local[(corner + count - 1) % count]]) - here;
      const Vector3 next = at(points, nodes[local[(corner + 1) % count]]) - here;
      const double cosine = previous.dot(next) / std::sqrt(previous.squaredNorm() * next.squaredNorm());
      if (!std::isfinite(cosine)) finite = false;
      smallest[kind] = std::min(smallest[kind], cosine);
      largest[kind] = std::max(largest[kind], cosine);
    }
  }

  double skewness() const {
    if (!finite) return std::nan("");
    double worst = 0.0;
    for (std::size_t kind = 0; kind < 2; ++kind) {
      if (smallest[kind] > 1.5) continue;  // no polygon of this kind
      const double ideal = kind == 0 ? pi / 3.0 : pi / 2.0;
      worst = std::max({worst, angle_skew(std::acos(std::clamp(smallest[kind], -1.0, 1.0)), ideal),
                        angle_skew(std::acos(std::clamp(largest[kind], -1.0, 1.0)), ideal)});
    }
    return worst;
  }
};

constexpr int identity[4] = {0, 1, 2, 3};

}  // namespace

double scaled_jacobian(CellType type, const std::vector<Vector3>& points, const Index* nodes) {
  const CellDescriptor& cell = descriptor(type);
  if (type == CellType::tetrahedron) {
    // All corners share the determinant; Verdict divides by the largest product of
    // edge lengths, which is the minimum for a valid tet and the value nearest zero
    // for an inverted one.
    double largest = 0.0;
    for (int corner = 0; corner < cell.corner_count; ++corner) {
      const Corner& local = cell.corners[corner];
      const Vector3& origin = at(points, nodes[local.node]);
      double product = 1.0;
      for (int neighbour : local.neighbours) product *= (at(points, nodes[neighbour]) - origin).norm();
      if (std::isnan(product)) return product;
      largest = std::max(largest, product);
    }
    const double determinant = tetrahedron_volume6(at(points, nodes[0]), at(points, nodes[1]),
                                                   at(points, nodes[2]), at(points, nodes[3]));
    return largest > 0.0 ? verdict_corner_factor * determinant / largest : 0.0;
  }
  double worst = std::numeric_limits<double>::infinity();
  for (int corner = 0; corner < cell.corner_count; ++corner) {
    const Corner& local = cell.corners[corner];
    const Vector3& origin = at(points, nodes[local.node]);
    const double value = normalised_determinant(at(points, nodes[local.neighbours[0]]) - origin,
                                                at(points, nodes[local.neighbours[1]]) - origin,
                                                at(points, nodes[local.neighbours[2]]) - origin);
    if (std::isnan(value)) return value;
    worst = std::min(worst, value);
  }
  if (type == CellType::hexahedron) {
    // Verdict's hex metric also takes the Jacobian at the centre, from the
    // principal axes (sums of the four edges in each direction).
    auto p = [&](int local) -> const Vector3& { return at(points, nodes[local]); };
    const Vector3 xi = (p(1) - p(0)) + (p(2) - p(3)) + (p(5) - p(4)) + (p(6) - p(7));
    const Vector3 eta = (p(3) - p(0)) + (p(2) - p(1)) + (p(7) - p(4)) + (p(6) - p(5));
    const Vector3 zeta = (p(4) - p(0)) + (p(5) - p(1)) + (p(6) - p(2)) + (p(7) - p(3));
    worst = std::min(worst, normalised_determinant(xi, eta, zeta));
  }
  worst *= jacobian_normaliser(type);
  // The base corners of a pyramid taller than the regular one exceed its value.
  if (type == CellType::pyramid) worst = std::min(worst, 1.0);
  return worst;
}

double skewness(CellType type, const std::vector<Vector3>& points, const Index* nodes) {
  const CellDescriptor& cell = descriptor(type);
  CornerCosines cosines;
  for (int face = 0; face < cell.face_count; ++face)
    cosines.add_polygon(points, nodes, cell.faces[face].nodes.data(), cell.faces[face].node_count);
  return cosines.skewness();
}

double aspect_ratio(CellType type, const std::vector<Vector3>& points, const Index* nodes) {
  const CellDescriptor& cell = descriptor(type);
  double shortest = std::numeric_limits<double>::infinity();
  double longest = 0.0;
  for (int edge = 0; edge < cell.edge_count; ++edge) {
    const double length =
        (at(points, nodes[cell.edges[edge][1]]) - at(points, nodes[cell.edges[edge][0]])).norm();
    if (std::isnan(length)) return length;
    shortest = std::min(shortest, length);
    longest = std::max(longest, length);
  }
  return shortest > 0.0 ? longest / shortest : std::numeric_limits<double>::infinity();
}

double sliver(const std::vector<Vector3>& points, const Index* tetrahedron) {
  const Vector3& a = at(points, tetrahedron[0]);
  const Vector3& b = at(points, tetrahedron[1]);
  const Vector3& c = at(points, tetrahedron[2]);
  const Vector3& d = at(points, tetrahedron[3]);
  const double volume = tetrahedron_volume6(a, b, c, d) / 6.0;
  const double area_sum = 0.5 * ((b - a).cross(c - a).norm() + (b - a).cross(d - a).norm() +
                                 (c - b).cross(d - b).norm() + (c - a).cross(d - a).norm());
  // Martineau & Georgala eq. (28): η = V^(1/3) / (¼ Σ A_i)^(1/2).
  return std::cbrt(volume) / std::sqrt(0.25 * area_sum);
}

double scaled_jacobian(FaceType type, const std::vector<Vector3>& points, const Index* nodes) {
  const int count = node_count(type);
  double worst = std::numeric_limits<double>::infinity();
  for (int corner = 0; corner < count; ++corner) {
    const Vector3& here = at(points, nodes[corner]);
    const Vector3 next = at(points, nodes[(corner + 1) % count]) - here;
    const Vector3 previous = at(points, nodes[(corner + count - 1) % count]) - here;
    const double lengths = next.norm() * previous.norm();
    if (std::isnan(lengths)) return lengths;
    worst =
        std::min(worst, lengths > 0.0 ? (next.x() * previous.y() - next.y() * previous.x()) / lengths : 0.0);
  }
  return type == FaceType::triangle ? worst * 2.0 / std::sqrt(3.0) : worst;
}

double skewness(FaceType type, const std::vector<Vector3>& points, const Index* nodes) {
  CornerCosines cosines;
  cosines.add_polygon(points, nodes, identity, node_count(type));
  return cosines.skewness();
}

double aspect_ratio(FaceType type, const std::vector<Vector3>& points, const Index* nodes) {
  const int count = node_count(type);
  double shortest = std::numeric_limits<double>::infinity();
  double longest = 0.0;
  for (int corner = 0; corner < count; ++corner) {
    const double length = (at(points, nodes[(corner + 1) % count]) - at(points, nodes[corner])).norm();
    if (std::isnan(length)) return length;
    shortest = std::min(shortest, length);
    longest = std::max(longest, length);
  }
  return shortest > 0.0 ? longest / shortest : std::numeric_limits<double>::infinity();
}

FaceGeometry face_geometry(const std::vector<Vector3>& points, const Index* nodes, int count) {
  if (count == 3) {
    const Vector3& a = at(points, nodes[0]);
    const Vector3& b = at(points, nodes[1]);
    const Vector3& c = at(points, nodes[2]);
    return {(a + b + c) / 3.0, 0.5 * (b - a).cross(c - a)};
  }
  Vector3 mean = Vector3::Zero();
  for (int corner = 0; corner < count; ++corner) mean += at(points, nodes[corner]);
  mean /= count;
  Vector3 normal_sum = Vector3::Zero();
  Vector3 weighted_centres = Vector3::Zero();
  double weight_sum = 0.0;
  for (int corner = 0; corner < count; ++corner) {
    const Vector3& here = at(points, nodes[corner]);
    const Vector3& next = at(points, nodes[(corner + 1) % count]);
    const Vector3 normal = (next - here).cross(mean - here);
    const double weight = normal.norm();
    normal_sum += normal;
    weight_sum += weight;
    weighted_centres += weight * (here + next + mean);
  }
  const Vector3 centre = weight_sum > 0.0 ? Vector3(weighted_centres / (3.0 * weight_sum)) : mean;
  return {centre, 0.5 * normal_sum};
}

Vector3 cell_centroid(CellType type, const std::vector<Vector3>& points, const Index* nodes) {
  const CellDescriptor& cell = descriptor(type);
  std::array<FaceGeometry, 6> faces;
  Vector3 estimate = Vector3::Zero();
  for (int face = 0; face < cell.face_count; ++face) {
    const LocalFace& local = cell.faces[face];
    Index corners[4];
    for (int corner = 0; corner < local.node_count; ++corner) corners[corner] = nodes[local.nodes[corner]];
    faces[static_cast<std::size_t>(face)] = face_geometry(points, corners, local.node_count);
    estimate += faces[static_cast<std::size_t>(face)].centre;
  }
  estimate /= cell.face_count;
  Vector3 weighted = Vector3::Zero();
  double volume = 0.0;
  for (int face = 0; face < cell.face_count; ++face) {
    const FaceGeometry& geometry = faces[static_cast<std::size_t>(face)];
    // The pyramid from the face to the estimate: 3 × volume, centroid ¾ of the way
    // from the apex.
    const double pyramid = geometry.area.dot(geometry.centre - estimate);
    weighted += pyramid * (0.75 * geometry.centre + 0.25 * estimate);
    volume += pyramid;
  }
  return std::abs(volume) > 0.0 ? Vector3(weighted / volume) : estimate;
}

double layer_height(CellType type, const std::vector<Vector3>& points, const Index* nodes) {
  const int base = type == CellType::prism ? 3 : 4;
  double sum = 0.0;
  for (int node = 0; node < base; ++node)
    sum += (at(points, nodes[node + base]) - at(points, nodes[node])).norm();
  return sum / base;
}

}  // namespace mixmesh
