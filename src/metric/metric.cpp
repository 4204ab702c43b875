#include "mixmesh/metric/metric.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <algorithm>
#include <map>
#include <set>
#include <sstream>

#include "mixmesh/core/error.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/mesh/face_connectivity.hpp"

namespace mixmesh {

namespace {

const Vector3& at(const std::vector<Vector3>& points, Index node) {
  return points[static_cast<std::size_t>(node)];
}

// Inverse of an SPD matrix through its eigen-decomposition, refusing anything that is
// not clearly positive definite (a flat or degenerate cell).
Matrix3 spd_inverse(const Matrix3& matrix, const char* what) {
  const Eigen::SelfAdjointEigenSolver<Matrix3> solver(matrix);
  const Vector3 eigenvalues = solver.eigenvalues();
  if (!(eigenvalues.minCoeff() > 1e-14 * eigenvalues.cwiseAbs().maxCoeff()))
    throw Error(std::string("metric: ") + what + " is degenerate (eigenvalues " +
                std::to_string(eigenvalues(0)) + ", " + std::to_string(eigenvalues(1)) + ", " +
                std::to_string(eigenvalues(2)) + ")");
  return solver.eigenvectors() * eigenvalues.cwiseInverse().asDiagonal() * solver.eigenvectors().transpose();
}

}  // namespace

double affine_scale(CellType type) {
  switch (type) {
    case CellType::tetrahedron:
      return 1.0 / 8.0;
    case CellType::pyramid:
      return 8.0 / 55.0;
    case CellType::prism:
      return 3.0 / 16.0;
    case CellType::hexahedron:
      break;
  }
  return 1.0 / 4.0;
}

Matrix3 hexahedron_metric(const std::vector<Vector3>& points, const Index* nodes) {
  // Wild eq. (10): VTK nodes k and k+4 are above each other; 0-1, 3-2 run in i and
  // 0-3, 1-2 in j on each level.
  auto p = [&](int local) -> const Vector3& { return at(points, nodes[local]); };
  Matrix3 basis;
  basis.col(0) = 0.25 * ((p(1) - p(0)) + (p(2) - p(3)) + (p(5) - p(4)) + (p(6) - p(7)));
  basis.col(1) = 0.25 * ((p(3) - p(0)) + (p(2) - p(1)) + (p(7) - p(4)) + (p(6) - p(5)));
  basis.col(2) = 0.25 * ((p(4) - p(0)) + (p(5) - p(1)) + (p(6) - p(2)) + (p(7) - p(3)));
  return spd_inverse(basis * basis.transpose(), "hexahedron basis B Bᵀ");  // M_H⁻¹ = B_H B_Hᵀ
}

Matrix3 affine_metric(CellType type, const std::vector<Vector3>& points, const Index* nodes) {
  // Wild eq. (11): the covariance of the nodes about their mean.
  const int count = node_count(type);
  const Vector3 centre = cell_centre(type, points, nodes);
  Matrix3 covariance = Matrix3::Zero();
  for (int local = 0; local < count; ++local) {
    const Vector3 offset = at(points, nodes[local]) - centre;
    covariance += offset * offset.transpose();
  }
  covariance /= count;
  return affine_scale(type) * spd_inverse(covariance, "affine invariant of the cell nodes");
}

Matrix3 riemannian_metric(const std::vector<Vector3>& points, const Index* nodes) {
  // Wild eq. (12): eᵀ M e = 1 on all six edges, linear in the six entries
  // (m00, m11, m22, m01, m02, m12).
  Eigen::Matrix<double, 6, 6> system;
  const auto& edges = tetrahedron_descriptor.edges;
  for (int edge = 0; edge < 6; ++edge) {
    const Vector3 e = at(points, nodes[edges[static_cast<std::size_t>(edge)][1]]) -
                      at(points, nodes[edges[static_cast<std::size_t>(edge)][0]]);
    system.row(edge) << e.x() * e.x(), e.y() * e.y(), e.z() * e.z(), 2 * e.x() * e.y(), 2 * e.x() * e.z(),
        2 * e.y() * e.z();
  }
  const Eigen::FullPivLU<Eigen::Matrix<double, 6, 6>> solver(system);
  if (!solver.isInvertible()) throw Error("metric: the tetrahedron is degenerate (no Riemannian invariant)");
  const Eigen::Matrix<double, 6, 1> entries = solver.solve(Eigen::Matrix<double, 6, 1>::Ones());
  Matrix3 metric;
  metric << entries(0), entries(3), entries(4), entries(3), entries(1), entries(5), entries(4), entries(5),
      entries(2);
  const Eigen::SelfAdjointEigenSolver<Matrix3> check(metric);
  if (!(check.eigenvalues().minCoeff() > 0.0))
    throw Error("metric: the tetrahedron is degenerate (Riemannian invariant not positive definite)");
  return metric;
}

Matrix3 cell_metric(CellType type, const std::vector<Vector3>& points, const Index* nodes) {
  switch (type) {
    case CellType::hexahedron:
      return hexahedron_metric(points, nodes);
    case CellType::tetrahedron:
      return riemannian_metric(points, nodes);
    case CellType::prism:
    case CellType::pyramid:
      break;
  }
  return affine_metric(type, points, nodes);
}

Matrix3 metric_transform(const Matrix3& metric) {
  const Eigen::SelfAdjointEigenSolver<Matrix3> solver(metric);
  return solver.eigenvalues().cwiseSqrt().asDiagonal() * solver.eigenvectors().transpose();  // Wild eq. (9)
}

Matrix3 spd_log(const Matrix3& metric) {
  const Eigen::SelfAdjointEigenSolver<Matrix3> solver(metric);
  if (!(solver.eigenvalues().minCoeff() > 0.0))
    throw Error("metric: logarithm of a metric that is not positive definite");
  return solver.eigenvectors() * solver.eigenvalues().array().log().matrix().asDiagonal() *
         solver.eigenvectors().transpose();
}

Matrix3 symmetric_exp(const Matrix3& symmetric) {
  const Eigen::SelfAdjointEigenSolver<Matrix3> solver(symmetric);
  return solver.eigenvectors() * solver.eigenvalues().array().exp().matrix().asDiagonal() *
         solver.eigenvectors().transpose();
}

Matrix3 log_euclidean_mean(const std::vector<Matrix3>& metrics, const std::vector<double>& weights) {
  if (metrics.empty()) throw Error("metric: mean of no metrics");
  if (!weights.empty() && weights.size() != metrics.size())
    throw Error("metric: " + std::to_string(weights.size()) + " weights for " +
                std::to_string(metrics.size()) + " metrics");
  Matrix3 sum = Matrix3::Zero();
  double total = 0.0;
  for (std::size_t index = 0; index < metrics.size(); ++index) {
    const double weight = weights.empty() ? 1.0 : weights[index];
    sum += weight * spd_log(metrics[index]);
    total += weight;
  }
  if (!(total > 0.0)) throw Error("metric: the weights of a mean add up to " + std::to_string(total));
  return symmetric_exp(sum / total);
}

std::vector<Matrix3> node_metrics(const MixedMesh& mesh, const std::vector<Index>& nodes,
                                  const NodeMetricOptions& options) {
  const std::size_t point_count = mesh.points.size();
  std::vector<int> slot(point_count, -1);
  for (std::size_t position = 0; position < nodes.size(); ++position) {
    const Index node = nodes[position];
    if (node < 0 || static_cast<std::size_t>(node) >= point_count)
      throw Error("metric: node " + std::to_string(node) + " is not a point of the mesh (" +
                  std::to_string(point_count) + " points)");
    if (slot[static_cast<std::size_t>(node)] >= 0)
      throw Error("metric: node " + std::to_string(node) + " is listed twice");
    slot[static_cast<std::size_t>(node)] = static_cast<int>(position);
  }
  // Accumulate logarithms per node directly: the log-Euclidean mean without storing
  // every cell's metric per node.
  std::vector<Matrix3> log_sum(nodes.size(), Matrix3::Zero());
  std::vector<double> weight_sum(nodes.size(), 0.0);
  for (CellType type : all_cell_types) {
    const int count = node_count(type);
    for (std::size_t cell = 0; cell < mesh.cell_count(type); ++cell) {
      const Index* cell_nodes = mesh.cell(type, cell);
      bool touches = false;
      for (int local = 0; local < count && !touches; ++local)
        touches = slot[static_cast<std::size_t>(cell_nodes[local])] >= 0;
      if (!touches) continue;
      Matrix3 logarithm;
      try {
        logarithm = spd_log(cell_metric(type, mesh.points, cell_nodes));
      } catch (const Error& error) {
        std::ostringstream where;
        where << error.what() << " in " << name(type) << " " << cell;
        throw Error(where.str());
      }
      const double weight = options.volume_weighted ? signed_volume(type, mesh.points, cell_nodes) : 1.0;
      for (int local = 0; local < count; ++local) {
        const int position = slot[static_cast<std::size_t>(cell_nodes[local])];
        if (position < 0) continue;
        log_sum[static_cast<std::size_t>(position)] += weight * logarithm;
        weight_sum[static_cast<std::size_t>(position)] += weight;
      }
    }
  }
  std::vector<Matrix3> metrics(nodes.size());
  for (std::size_t position = 0; position < nodes.size(); ++position) {
    if (!(weight_sum[position] > 0.0))
      throw Error("metric: node " + std::to_string(nodes[position]) +
                  " belongs to no cell of positive volume");
    metrics[position] = symmetric_exp(log_sum[position] / weight_sum[position]);
  }
  return metrics;
}

std::vector<Index> blend_cap_metrics(const MixedMesh& split_mesh,
                                     const std::vector<std::array<Index, 3>>& hull,
                                     const std::vector<Index>& nodes, std::vector<Matrix3>& metrics) {
  std::set<std::array<Index, 4>> hull_faces;
  for (const auto& triangle : hull) hull_faces.insert(sorted_face_key(triangle.data(), 3));
  std::map<Index, std::vector<Matrix3>> caps_at;  // base corner -> metrics of its caps
  for (std::size_t cell = 0; cell < split_mesh.cell_count(CellType::pyramid); ++cell) {
    const Index* pyramid = split_mesh.cell(CellType::pyramid, cell);
    bool cap = false;
    for (int side = 0; side < 4 && !cap; ++side) {
      const Index face[3] = {pyramid[side], pyramid[(side + 1) % 4], pyramid[4]};
      cap = hull_faces.count(sorted_face_key(face, 3)) > 0;
    }
    if (!cap) continue;
    const Matrix3 metric = cell_metric(CellType::pyramid, split_mesh.points, pyramid);
    for (int corner = 0; corner < 4; ++corner) caps_at[pyramid[corner]].push_back(metric);
  }
  std::vector<Index> changed;
  for (std::size_t position = 0; position < nodes.size(); ++position) {
    const auto caps = caps_at.find(nodes[position]);
    if (caps == caps_at.end()) continue;
    metrics[position] = log_euclidean_mean({metrics[position], log_euclidean_mean(caps->second)});
    changed.push_back(nodes[position]);
  }
  std::sort(changed.begin(), changed.end());
  return changed;
}

}  // namespace mixmesh
