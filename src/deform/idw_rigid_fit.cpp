#include "mixmesh/deform/idw_rigid_fit.hpp"

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>

namespace mixmesh::deform {

namespace {

// Singular values below this fraction of the largest count as zero (collinear or
// coincident reference points).
constexpr double rank_tolerance = 1e-10;

}  // namespace

RigidFit weighted_means(const std::vector<Vector3>& points, const std::vector<Vector3>& displacements,
                        const Index* indices, const double* weights, int count) {
  RigidFit fit;
  double weight_sum = 0.0;
  for (int k = 0; k < count; ++k) {
    const std::size_t j = static_cast<std::size_t>(indices[k]);
    weight_sum += weights[k];
    fit.centre += weights[k] * points[j];
    fit.translation += weights[k] * displacements[j];
  }
  if (weight_sum > 0.0) {
    fit.centre /= weight_sum;
    fit.translation /= weight_sum;
  }
  return fit;
}

RigidFit fit_rigid_motion(const std::vector<Vector3>& points, const std::vector<Vector3>& displacements,
                          const Index* indices, const double* weights, int count, FitDimension dimension) {
  RigidFit fit = weighted_means(points, displacements, indices, weights, count);

  // Cross-covariance H = Σ α p qᵀ of the centred reference and target points.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (int k = 0; k < count; ++k) {
    const std::size_t j = static_cast<std::size_t>(indices[k]);
    const Vector3 reference = points[j] - fit.centre;
    const Vector3 target = reference + displacements[j] - fit.translation;
    covariance += weights[k] * reference * target.transpose();
  }

  if (dimension == FitDimension::planar) {
    // Rotation about z maximising Σ α (R p)·q: θ = atan2(Σ p × q, Σ p · q) in the plane.
    const double sine = covariance(0, 1) - covariance(1, 0);
    const double cosine = covariance(0, 0) + covariance(1, 1);
    if (sine == 0.0 && cosine == 0.0) return fit;
    const double angle = std::atan2(sine, cosine);
    fit.rotation = Eigen::AngleAxisd(angle, Vector3::UnitZ()).toRotationMatrix();
    return fit;
  }

  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(covariance, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Vector3 singular = svd.singularValues();
  if (!(singular[0] > 0.0)) return fit;
  if (singular[1] <= rank_tolerance * singular[0]) {
    // Collinear reference points fix only their line: take the shortest arc turning it.
    const Vector3 from = svd.matrixU().col(0);
    const Vector3 to = svd.matrixV().col(0);
    fit.rotation = Eigen::Quaterniond::FromTwoVectors(from, to).toRotationMatrix();
    return fit;
  }
  // Kabsch: R = V diag(1, 1, det(V Uᵀ)) Uᵀ, so that R is a rotation, not a reflection.
  Eigen::Matrix3d correction = Eigen::Matrix3d::Identity();
  correction(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  fit.rotation = svd.matrixV() * correction * svd.matrixU().transpose();
  return fit;
}

Eigen::Matrix3d nearest_rotation(const Eigen::Matrix3d& matrix) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(matrix, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d correction = Eigen::Matrix3d::Identity();
  correction(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  return svd.matrixU() * correction * svd.matrixV().transpose();
}

double rotation_angle(const Eigen::Matrix3d& rotation) {
  const double cosine = std::clamp(0.5 * (rotation.trace() - 1.0), -1.0, 1.0);
  return std::acos(cosine);
}

}  // namespace mixmesh::deform
