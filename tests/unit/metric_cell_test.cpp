#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>

#include "mixmesh/core/error.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/metric/metric.hpp"
#include "reference_cells.hpp"

using namespace mixmesh;

namespace {

// The unit cube mapped by x ↦ basis · x: a parallelepiped with edge vectors the columns.
MixedMesh mapped_cube(const Matrix3& basis) {
  MixedMesh mesh = reference::single_cell(CellType::hexahedron);
  for (Vector3& point : mesh.points) point = basis * point;
  return mesh;
}

MixedMesh regular_tetrahedron() {
  MixedMesh mesh;
  mesh.points = {
      {0, 0, 0}, {1, 0, 0}, {0.5, std::sqrt(3.0) / 2, 0}, {0.5, std::sqrt(3.0) / 6, std::sqrt(2.0 / 3.0)}};
  const Index nodes[4] = {0, 1, 2, 3};
  mesh.add_cell(CellType::tetrahedron, nodes);
  return mesh;
}

double edge_length(const MixedMesh& mesh, CellType type, const Matrix3& metric, int edge) {
  const auto [a, b] = descriptor(type).edges[static_cast<std::size_t>(edge)];
  const Index* nodes = mesh.cell(type, 0);
  return metric_length(metric, mesh.points[static_cast<std::size_t>(nodes[b])] -
                                   mesh.points[static_cast<std::size_t>(nodes[a])]);
}

}  // namespace

TEST(CellMetric, UnitCubeHasTheIdentityMetric) {
  const MixedMesh cube = reference::single_cell(CellType::hexahedron);
  EXPECT_TRUE(hexahedron_metric(cube.points, cube.cell(CellType::hexahedron, 0))
                  .isApprox(Matrix3::Identity(), 1e-14));
  EXPECT_TRUE(affine_metric(CellType::hexahedron, cube.points, cube.cell(CellType::hexahedron, 0))
                  .isApprox(Matrix3::Identity(), 1e-14));
}

TEST(CellMetric, StretchedHexahedronHasInverseSquaredSpacingsAlongItsAxes) {
  const MixedMesh box = mapped_cube(Vector3(4.0, 0.5, 1e-3).asDiagonal());
  const Matrix3 metric = hexahedron_metric(box.points, box.cell(CellType::hexahedron, 0));
  const Eigen::SelfAdjointEigenSolver<Matrix3> solver(metric);  // ascending eigenvalues
  EXPECT_NEAR(solver.eigenvalues()(0), 1.0 / 16.0, 1e-12);
  EXPECT_NEAR(solver.eigenvalues()(1), 4.0, 1e-10);
  EXPECT_NEAR(solver.eigenvalues()(2), 1e6, 1e-4);
  EXPECT_NEAR(std::abs(solver.eigenvectors().col(0).dot(Vector3::UnitX())), 1.0, 1e-12);
  EXPECT_NEAR(std::abs(solver.eigenvectors().col(1).dot(Vector3::UnitY())), 1.0, 1e-12);
  EXPECT_NEAR(std::abs(solver.eigenvectors().col(2).dot(Vector3::UnitZ())), 1.0, 1e-12);
}

TEST(CellMetric, ShearedHexahedronHasUnitMetricEdgesAlongItsBasis) {
  Matrix3 basis;
  basis << 2.0, 0.8, 0.1, 0.0, 0.5, 0.05, 0.0, 0.0, 0.01;
  const MixedMesh sheared = mapped_cube(basis);
  const Matrix3 metric = hexahedron_metric(sheared.points, sheared.cell(CellType::hexahedron, 0));
  // Bᵀ M B = I: every edge has metric length 1 and the metric is B⁻ᵀ B⁻¹.
  EXPECT_TRUE((basis.transpose() * metric * basis).isApprox(Matrix3::Identity(), 1e-10));
  for (int edge = 0; edge < 12; ++edge)
    EXPECT_NEAR(edge_length(sheared, CellType::hexahedron, metric, edge), 1.0, 1e-10);
  // The axis of largest eigenvalue is (nearly) the normal of the layer plane, with
  // eigenvalue ≈ 1 / thickness².
  const Eigen::SelfAdjointEigenSolver<Matrix3> solver(metric);
  const Vector3 thin_normal = basis.col(0).cross(basis.col(1)).normalized();
  EXPECT_NEAR(std::abs(solver.eigenvectors().col(2).dot(thin_normal)), 1.0, 1e-3);
  EXPECT_NEAR(solver.eigenvalues()(2), 1e4, 0.02 * 1e4);
}

TEST(CellMetric, RegularTetrahedronHasUnitMetricEdgesBothWays) {
  const MixedMesh tetrahedron = regular_tetrahedron();
  const Index* nodes = tetrahedron.cell(CellType::tetrahedron, 0);
  const Matrix3 riemannian = riemannian_metric(tetrahedron.points, nodes);
  const Matrix3 affine = affine_metric(CellType::tetrahedron, tetrahedron.points, nodes);
  EXPECT_TRUE(riemannian.isApprox(Matrix3::Identity(), 1e-12));
  EXPECT_TRUE(affine.isApprox(Matrix3::Identity(), 1e-12));
}

TEST(CellMetric, RiemannianInvariantMakesAnyTetrahedronRegular) {
  MixedMesh tetrahedron;
  tetrahedron.points = {{0, 0, 0}, {3, 0.2, 0}, {0.4, 0.9, 0.05}, {1, 0.3, 0.02}};
  const Index nodes[4] = {0, 1, 2, 3};
  tetrahedron.add_cell(CellType::tetrahedron, nodes);
  reference::orient_positively(tetrahedron);
  const Matrix3 metric =
      cell_metric(CellType::tetrahedron, tetrahedron.points, tetrahedron.cell(CellType::tetrahedron, 0));
  for (int edge = 0; edge < 6; ++edge)
    EXPECT_NEAR(edge_length(tetrahedron, CellType::tetrahedron, metric, edge), 1.0, 1e-10);
}

TEST(CellMetric, AffineScaleGivesRegularCellsAUnitMeanSquaredEdge) {
  const double half_root = std::sqrt(0.5);
  const double third_root = 1.0 / std::sqrt(3.0);
  MixedMesh pyramid;
  pyramid.points = {{-0.5, -0.5, 0}, {0.5, -0.5, 0}, {0.5, 0.5, 0}, {-0.5, 0.5, 0}, {0, 0, half_root}};
  const Index pyramid_nodes[5] = {0, 1, 2, 3, 4};
  pyramid.add_cell(CellType::pyramid, pyramid_nodes);
  MixedMesh prism;
  for (double z : {0.0, 1.0})
    for (int corner : {0, 2, 1})  // clockwise seen from the top, as VTK wants
      prism.points.push_back(
          {third_root * std::cos(2 * M_PI * corner / 3), third_root * std::sin(2 * M_PI * corner / 3), z});
  const Index prism_nodes[6] = {0, 1, 2, 3, 4, 5};
  prism.add_cell(CellType::prism, prism_nodes);
  for (const auto* mesh : {&pyramid, &prism}) {
    const CellType type = mesh->cell_count(CellType::pyramid) ? CellType::pyramid : CellType::prism;
    ASSERT_TRUE(cell_shape(type, mesh->points, mesh->cell(type, 0)).valid());
    const Matrix3 metric = cell_metric(type, mesh->points, mesh->cell(type, 0));
    double squares = 0.0;
    for (int edge = 0; edge < descriptor(type).edge_count; ++edge)
      squares += std::pow(edge_length(*mesh, type, metric, edge), 2);
    EXPECT_NEAR(squares / descriptor(type).edge_count, 1.0, 1e-12) << name(type);
  }
}

TEST(CellMetric, LogEuclideanMeanIsPositiveDefiniteAndBetweenItsInputs) {
  const Matrix3 small = Vector3(1.0, 1.0, 1.0).asDiagonal();
  const Matrix3 large = Vector3(4.0, 16.0, 1.0).asDiagonal();
  EXPECT_TRUE(
      log_euclidean_mean({small, large}).isApprox(Matrix3(Vector3(2.0, 4.0, 1.0).asDiagonal()), 1e-12));

  // Two non-commuting metrics: a stretched metric rotated by 40° about z.
  const Matrix3 rotation = Eigen::AngleAxisd(40.0 * M_PI / 180.0, Vector3::UnitZ()).toRotationMatrix();
  const Matrix3 first = Vector3(1.0, 100.0, 4.0).asDiagonal();
  const Matrix3 second = rotation * Matrix3(Vector3(9.0, 2.0, 0.5).asDiagonal()) * rotation.transpose();
  const Matrix3 mean = log_euclidean_mean({first, second}, {1.0, 3.0});
  EXPECT_TRUE(mean.isApprox(mean.transpose(), 1e-14));
  const Eigen::SelfAdjointEigenSolver<Matrix3> solver(mean);
  EXPECT_GT(solver.eigenvalues().minCoeff(), 0.5);
  EXPECT_LT(solver.eigenvalues().maxCoeff(), 100.0);
  // log det is linear under the mean: det = det₁^¼ det₂^¾.
  EXPECT_NEAR(std::log(mean.determinant()),
              0.25 * std::log(first.determinant()) + 0.75 * std::log(second.determinant()), 1e-12);
  EXPECT_THROW(log_euclidean_mean({first, -first}), Error);
  EXPECT_THROW(log_euclidean_mean({first}, {1.0, 2.0}), Error);
}

TEST(NodeMetrics, NodeBetweenTwoHexahedraGetsTheGeometricMeanOfTheirSpacings) {
  // Two boxes stacked in z, of heights 1 and 0.25: nodes on the shared face see both.
  MixedMesh mesh = mapped_cube(Matrix3::Identity());
  for (int corner = 4; corner < 8; ++corner)
    mesh.points.push_back(mesh.points[static_cast<std::size_t>(corner)] + Vector3(0, 0, 0.25));
  const Index upper[8] = {4, 5, 6, 7, 8, 9, 10, 11};
  mesh.add_cell(CellType::hexahedron, upper);
  const std::vector<Matrix3> metrics = node_metrics(mesh, {0, 5, 9});
  EXPECT_TRUE(metrics[0].isApprox(Matrix3::Identity(), 1e-12));
  EXPECT_TRUE(metrics[1].isApprox(Matrix3(Vector3(1.0, 1.0, 4.0).asDiagonal()), 1e-12));  // √(1 · 16)
  EXPECT_TRUE(metrics[2].isApprox(Matrix3(Vector3(1.0, 1.0, 16.0).asDiagonal()), 1e-12));
  EXPECT_THROW(node_metrics(mesh, {12}), Error);
  EXPECT_THROW(node_metrics(mesh, {3, 3}), Error);
}

TEST(NodeMetrics, FlatCellIsReportedByName) {
  MixedMesh mesh = mapped_cube(Vector3(1.0, 1.0, 0.0).asDiagonal());
  try {
    node_metrics(mesh, {0});
    FAIL() << "a flat hexahedron has no metric";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("hexahedron 0"), std::string::npos) << error.what();
  }
}

// A wake-like layer cell, 1 × 1 × 0.05, with a cap 0.2 high on its top face: the tall
// pyramid's side faces are the hull. Its base corners take a metric between the flat
// cell's and the cap's; a node under no cap keeps its own.
TEST(NodeMetrics, CapCornersBlendTheirCapsMetricAndOthersKeepTheirs) {
  MixedMesh layer = reference::single_cell(CellType::hexahedron);
  for (Vector3& point : layer.points) point.z() *= 0.05;
  MixedMesh split = layer;
  split.points.push_back({0.5, 0.5, 0.25});
  const Index apex = 8;
  const Index cap[5] = {4, 5, 6, 7, apex};
  split.add_cell(CellType::pyramid, cap);
  ASSERT_GT(signed_volume(CellType::pyramid, split.points, cap), 0.0);
  const std::vector<std::array<Index, 3>> hull = {{4, 5, apex}, {5, 6, apex}, {6, 7, apex}, {7, 4, apex}};
  const std::vector<Index> nodes = {0, 4, 5, 6, 7};
  const std::vector<Matrix3> own = node_metrics(layer, nodes);
  std::vector<Matrix3> blended = own;
  EXPECT_EQ(blend_cap_metrics(split, hull, nodes, blended), (std::vector<Index>{4, 5, 6, 7}));
  EXPECT_TRUE(blended[0].isApprox(own[0]));  // node 0 is under no cap

  const Matrix3 cap_metric = cell_metric(CellType::pyramid, split.points, cap);
  const Vector3 side = split.points[apex] - split.points[4];
  const double in_cell = metric_length(own[1], side);
  const double in_cap = metric_length(cap_metric, side);
  const double in_blend = metric_length(blended[1], side);
  EXPECT_GT(in_cell, 2.0 * in_cap);  // the flat cell's metric takes the cap's side for long
  EXPECT_LT(in_blend, in_cell);
  EXPECT_GT(in_blend, in_cap);

  // Without the cap's faces in the hull (a split, not a cap) nothing changes.
  std::vector<Matrix3> untouched = own;
  EXPECT_TRUE(blend_cap_metrics(split, {}, nodes, untouched).empty());
  for (std::size_t position = 0; position < nodes.size(); ++position)
    EXPECT_TRUE(untouched[position].isApprox(own[position]));
}
