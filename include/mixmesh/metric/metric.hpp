// Metrics of the interface (Wild §II.D): symmetric positive definite 3×3 tensors M
// that measure edge lengths as ℓ_M(e) = √(eᵀ M e); a cell that fits its metric has
// edges of metric length ≈ 1. M = E diag(λ) Eᵀ (Wild eq. 8); the map into metric space
// is T = diag(√λ) Eᵀ (eq. 9), see metric_transform.
//
//   hexahedron_metric   M⁻¹ = B Bᵀ, B = the averaged edge vectors in i, j, k (eq. 10)
//   affine_metric       M⁻¹ ∝ (1/n) Σ (x_k − x_c)(x_k − x_c)ᵀ (eq. 11), any cell
//   riemannian_metric   the M with unit metric length on all six tetrahedron edges (eq. 12)
//   cell_metric         the rule of the paper per type: eq. 10 hexahedra, eq. 11 prisms
//                       and pyramids, eq. 12 tetrahedra
//   node_metrics        per requested node, the log-Euclidean mean of the metrics of
//                       the cells around it
#pragma once

#include <array>

#include <Eigen/Core>

#include <cmath>
#include <vector>

#include "mixmesh/mesh/mixed_mesh.hpp"

namespace mixmesh {

using Matrix3 = Eigen::Matrix3d;

// Scale of the affine invariant: M_A = scale · C⁻¹ with C the covariance of the
// cell's nodes. The scale makes the regular cell of unit edges have a mean squared
// metric edge length of exactly 1 (tetrahedron 1/8, pyramid 8/55, prism 3/16,
// hexahedron 1/4). The regular tetrahedron and the unit cube then have unit metric
// length on every edge; the regular pyramid and prism cannot (their covariance is
// not isotropic) and get 0.85/1.13 (pyramid base/lateral) and 1.06/0.87 (prism
// triangle/side edges).
double affine_scale(CellType type);

Matrix3 hexahedron_metric(const std::vector<Vector3>& points, const Index* nodes);
Matrix3 affine_metric(CellType type, const std::vector<Vector3>& points, const Index* nodes);
Matrix3 riemannian_metric(const std::vector<Vector3>& points, const Index* nodes);
Matrix3 cell_metric(CellType type, const std::vector<Vector3>& points, const Index* nodes);

inline double metric_length(const Matrix3& metric, const Vector3& edge) {
  return std::sqrt(edge.dot(metric * edge));
}

// T = diag(√λ) Eᵀ (Wild eq. 9): |T e| = ℓ_M(e).
Matrix3 metric_transform(const Matrix3& metric);

// Matrix logarithm and exponential of symmetric matrices (eigen-decomposition).
Matrix3 spd_log(const Matrix3& metric);
Matrix3 symmetric_exp(const Matrix3& symmetric);

// exp(Σ w_i log M_i / Σ w_i): stays SPD, its determinant is the weighted geometric
// mean of the determinants, and it interpolates sizes geometrically (a plain
// average of tensors would favour the smallest cells). Equal weights when weights
// is empty.
Matrix3 log_euclidean_mean(const std::vector<Matrix3>& metrics, const std::vector<double>& weights = {});

struct NodeMetricOptions {
  // Weight each cell's metric by its volume (true) or equally (false).
  bool volume_weighted = false;
};

// The metric at each of `nodes` from every cell of `mesh` that uses it (the
// boundary-layer mesh before the interface split gives the hexahedra's own metrics).
// Throws mixmesh::Error for a node out of range, a node no cell uses, or a cell whose
// metric is not positive definite (naming the cell).
std::vector<Matrix3> node_metrics(const MixedMesh& mesh, const std::vector<Index>& nodes,
                                  const NodeMetricOptions& options = {});

// Where the interface capped a cell instead of splitting it, the hull is the side
// faces of a pyramid standing on the cell's outer quad, and the tetrahedra on them
// stand on the cap, not on the flat cell below. So the metric of each of `nodes` that
// is a base corner of such a cap (a pyramid of `split_mesh` with a face in `hull`)
// becomes the log-Euclidean mean of its own metric (`metrics`, from the layer cells)
// and the mean metric of its caps. Returns the nodes that changed, sorted.
std::vector<Index> blend_cap_metrics(const MixedMesh& split_mesh,
                                     const std::vector<std::array<Index, 3>>& hull,
                                     const std::vector<Index>& nodes, std::vector<Matrix3>& metrics);

}  // namespace mixmesh
