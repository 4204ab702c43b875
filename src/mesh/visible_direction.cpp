#include "mixmesh/mesh/visible_direction.hpp"

#include <cmath>
#include <limits>

#include <Eigen/Dense>

namespace mixmesh {

namespace {

// The point of least norm on the simplex spanned by `corners` (one, two or three points),
// if it lies inside the simplex (else no point: a smaller simplex of the same corners
// holds it).
bool least_point_on_simplex(const std::vector<Vector3>& corners, Vector3& point) {
  const Vector3& origin = corners.front();
  if (corners.size() == 1) {
    point = origin;
    return true;
  }
  const int count = static_cast<int>(corners.size()) - 1;
  Eigen::MatrixXd edges(3, count);
  for (int k = 0; k < count; ++k) edges.col(k) = corners[static_cast<std::size_t>(k + 1)] - origin;
  const Eigen::MatrixXd gram = edges.transpose() * edges;
  if (std::abs(gram.determinant()) <= 1e-14 * std::pow(gram.trace(), count)) return false;
  const Eigen::VectorXd weights = gram.ldlt().solve(-edges.transpose() * origin);
  if (weights.minCoeff() < 0.0 || weights.sum() > 1.0) return false;
  point = origin + edges * weights;
  return true;
}

}  // namespace

Vector3 visible_direction(const std::vector<Vector3>& normals) {
  // The least-norm point p of the hull satisfies p . n >= |p|^2 for every normal n (the
  // hull lies beyond the plane through p orthogonal to it); in three dimensions it lies
  // on a vertex, an edge or a triangle of the normals, so the small fans of a surface
  // node are searched over all of those.
  const std::size_t count = normals.size();
  if (count == 0) return Vector3::Zero();
  Vector3 best = Vector3::Zero();
  double best_norm = std::numeric_limits<double>::infinity();
  auto consider = [&](const std::vector<Vector3>& corners) {
    Vector3 point;
    if (!least_point_on_simplex(corners, point)) return;
    const double norm = point.squaredNorm();
    if (norm >= best_norm) return;
    for (const Vector3& normal : normals)
      if (point.dot(normal) < norm - 1e-12) return;
    best = point;
    best_norm = norm;
  };
  for (std::size_t a = 0; a < count; ++a) {
    consider({normals[a]});
    for (std::size_t b = a + 1; b < count; ++b) {
      consider({normals[a], normals[b]});
      for (std::size_t c = b + 1; c < count; ++c) consider({normals[a], normals[b], normals[c]});
    }
  }
  if (!(best_norm < std::numeric_limits<double>::infinity()) || best.norm() < 1e-9) return Vector3::Zero();
  return best.normalized();
}

}  // namespace mixmesh
