#include "deform/rotation.hpp"

#include <Eigen/SVD>
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

Vector3 fit_rotation(const std::vector<Vector3>& before, const std::vector<Vector3>& after, bool planar) {
  if (before.size() < 2 || before.size() != after.size()) return Vector3::Zero();
  if (planar) {
    // Angle maximising Σ cos(θ) (a·b) + sin(θ) (a × b)_z.
    double along = 0.0;
    double across = 0.0;
    for (std::size_t item = 0; item < before.size(); ++item) {
      along += before[item].x() * after[item].x() + before[item].y() * after[item].y();
      across += before[item].x() * after[item].y() - before[item].y() * after[item].x();
    }
    if (along == 0.0 && across == 0.0) return Vector3::Zero();
    return Vector3(0.0, 0.0, std::atan2(across, along));
  }
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (std::size_t item = 0; item < before.size(); ++item)
    covariance += after[item] * before[item].transpose();
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

}  // namespace mixmesh::deform::detail
