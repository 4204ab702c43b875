#include "deform/rotation.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

namespace mixmesh::deform::detail {

Vector3 rotate(const Vector3& rotation, const Vector3& vector) {
  const double angle = rotation.norm();
  if (angle < 1e-300) return vector;
  const Vector3 axis = rotation / angle;
  const double cosine = std::cos(angle);
  return vector * cosine + axis.cross(vector) * std::sin(angle) + axis * axis.dot(vector) * (1.0 - cosine);
}

Eigen::Matrix3d rotation_matrix(const Vector3& rotation) {
  const double angle = rotation.norm();
  if (angle < 1e-300) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, rotation / angle).toRotationMatrix();
}

Vector3 rotation_vector(const Eigen::Matrix3d& rotation) {
  const Eigen::AngleAxisd angle_axis(rotation);
  return angle_axis.axis() * angle_axis.angle();
}

namespace {

// Each offset counts by its direction, not by its length: weight 1/|before|², so the fit
// is that of the unit directions (each scaled alike before and after). Why: a star is
// often far longer in one direction than across it. At a closed trailing edge a wall
// node's star is three nodes on each side along the edge, 0.1 m away, and the upper and
// lower nodes 1.4 mm ahead (a random wing of seed 23): with plain weights the turn about
// the edge is fitted to what the long offsets leave across it, and the bending mode's
// curvature (0.6 mm off a rigid motion over 0.1 m of span, a strain of 0.6 %) turned the
// trailing-edge nodes 17.6 to 19.1 deg where their neighbours turn 5.4 deg. The rotation
// form of IDW averages these rotations over the nearest nodes, and behind the trailing
// edge the jump as one more such node entered the set lifted neighbouring wake nodes 4 cm
// apart 7 mm differently; the warped wake cells, 8 um thick, folded. Weighted by
// direction, a non-rigid strain ε moves the fit by about ε whatever the star's
// proportions (4.9 deg there). A rigid motion is still fitted exactly.
double offset_weight(const Vector3& offset) {
  const double squared = offset.squaredNorm();
  return squared > 0.0 ? 1.0 / squared : 0.0;
}

}  // namespace

Vector3 fit_rotation(const std::vector<Vector3>& before, const std::vector<Vector3>& after, bool planar) {
  if (before.size() < 2 || before.size() != after.size()) return Vector3::Zero();
  if (planar) {
    // Angle maximising Σ cos(θ) (a·b) + sin(θ) (a × b)_z.
    double along = 0.0;
    double across = 0.0;
    for (std::size_t item = 0; item < before.size(); ++item) {
      const double weight = offset_weight(before[item]);
      along += weight * (before[item].x() * after[item].x() + before[item].y() * after[item].y());
      across += weight * (before[item].x() * after[item].y() - before[item].y() * after[item].x());
    }
    if (along == 0.0 && across == 0.0) return Vector3::Zero();
    return Vector3(0.0, 0.0, std::atan2(across, along));
  }
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (std::size_t item = 0; item < before.size(); ++item)
    covariance += offset_weight(before[item]) * after[item] * before[item].transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(covariance, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d correction = Eigen::Matrix3d::Identity();
  if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0) correction(2, 2) = -1.0;
  const Eigen::Matrix3d rotation = svd.matrixU() * correction * svd.matrixV().transpose();
  return rotation_vector(rotation);
}

void project_sliding(const BoundaryMotion& boundary, const std::vector<Vector3>& original, std::size_t node,
                     Vector3& position) {
  if (boundary.roles[node] != NodeRole::sliding) return;
  const Vector3& normal = boundary.slide_normal[node];
  position -= (position - original[node]).dot(normal) * normal;
}

void project_sliding(const BoundaryMotion& boundary, const std::vector<Vector3>& original,
                     std::vector<Vector3>& moved) {
  for (std::size_t node = 0; node < moved.size(); ++node)
    project_sliding(boundary, original, node, moved[node]);
}

// The mirror image of a symmetric mesh moves the other way, so a motion field that is
// symmetric has no component normal to the plane at the plane and a small one near it.
// The methods only hold the plane's own nodes: ARA's rigid transport of the wake's cells
// turned about x by the bending mode's twist moved one node of the ONERA M6's root plane,
// 1.7 cm off it, 2.2 cm towards it (through it) at x = 5 m. The map s → s·exp(−d/s) is
// smooth, keeps small steps (d ≪ s) and leaves every node on its side.
void keep_off_sliding_planes(const BoundaryMotion& boundary, const std::vector<Vector3>& original,
                             std::vector<Vector3>& moved) {
  struct Plane {
    Vector3 normal;
    double offset;
  };
  std::vector<Plane> planes;
  for (std::size_t node = 0; node < original.size(); ++node) {
    if (boundary.roles[node] != NodeRole::sliding) continue;
    const Vector3& normal = boundary.slide_normal[node];
    const double offset = normal.dot(original[node]);
    const bool known = std::any_of(planes.begin(), planes.end(), [&](const Plane& plane) {
      return plane.normal.dot(normal) > 1.0 - 1e-9 &&
             std::abs(plane.offset - offset) <= 1e-9 * (1.0 + std::abs(offset));
    });
    if (!known) planes.push_back({normal, offset});
  }
  if (planes.empty()) return;
  for (std::size_t node = 0; node < original.size(); ++node) {
    if (boundary.roles[node] != NodeRole::interior) continue;
    for (const Plane& plane : planes) {
      const double signed_distance = plane.normal.dot(original[node]) - plane.offset;
      const double distance = std::abs(signed_distance);
      if (distance == 0.0) continue;
      const Vector3 away = signed_distance > 0.0 ? plane.normal : Vector3(-plane.normal);
      const double step = away.dot(moved[node] - original[node]);  // < 0: towards the plane
      if (step >= 0.0) continue;
      moved[node] += (distance * std::exp(step / distance) - (distance + step)) * away;
    }
  }
}

}  // namespace mixmesh::deform::detail
