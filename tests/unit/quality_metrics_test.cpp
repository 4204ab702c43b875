// Cell quality metrics on hand-built cells, against analytic values and VTK's Verdict.
#include <gtest/gtest.h>
#include <vtkHexahedron.h>
#include <vtkMeshQuality.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkTetra.h>

#include <cmath>
#include <random>

#include "mixmesh/core/error.hpp"
#include "mixmesh/quality/cell_quality.hpp"
#include "mixmesh/quality/quality.hpp"
#include "reference_cells.hpp"

namespace mixmesh {
namespace {

constexpr double pi = 3.14159265358979323846;

// Regular cells with unit edges.
MixedMesh regular_cell(CellType type) {
  MixedMesh mesh;
  const double root3 = std::sqrt(3.0);
  switch (type) {
    case CellType::tetrahedron:
      mesh.points = {{0, 0, 0}, {1, 0, 0}, {0.5, root3 / 2, 0}, {0.5, root3 / 6, std::sqrt(2.0 / 3.0)}};
      break;
    case CellType::pyramid:
      mesh.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 1 / std::sqrt(2.0)}};
      break;
    case CellType::prism:  // VTK wedge: bottom clockwise seen from the top
      mesh.points = {{0, 0, 0}, {0.5, root3 / 2, 0}, {1, 0, 0}, {0, 0, 1}, {0.5, root3 / 2, 1}, {1, 0, 1}};
      break;
    case CellType::hexahedron:
      return reference::single_cell(type);
  }
  std::vector<Index> nodes(static_cast<std::size_t>(node_count(type)));
  for (std::size_t local = 0; local < nodes.size(); ++local) nodes[local] = static_cast<Index>(local);
  mesh.add_cell(type, nodes.data());
  return mesh;
}

TEST(QualityMetrics, RegularCellsAreIdeal) {
  for (CellType type : all_cell_types) {
    const MixedMesh mesh = regular_cell(type);
    const Index* nodes = mesh.cell(type, 0);
    SCOPED_TRACE(std::string(name(type)));
    ASSERT_GT(signed_volume(type, mesh.points, nodes), 0.0);
    EXPECT_NEAR(scaled_jacobian(type, mesh.points, nodes), 1.0, 1e-12);
    EXPECT_NEAR(skewness(type, mesh.points, nodes), 0.0, 1e-12);
    EXPECT_NEAR(aspect_ratio(type, mesh.points, nodes), 1.0, 1e-12);
  }
}

TEST(QualityMetrics, SliverOfRegularTetrahedronIsTheStatedValue) {
  const MixedMesh mesh = regular_cell(CellType::tetrahedron);
  // V = 1/(6√2), each face √3/4: η = (6√2)^(-1/3) (√3/4)^(-1/2) ≈ 0.7451 (method.md §7).
  const double expected = std::pow(6 * std::sqrt(2.0), -1.0 / 3.0) / std::sqrt(std::sqrt(3.0) / 4);
  EXPECT_NEAR(sliver(mesh.points, mesh.cell(CellType::tetrahedron, 0)), expected, 1e-12);
  EXPECT_NEAR(expected, 0.7451, 5e-5);
  // A flat tet (all four nodes in one plane) has η = 0; an inverted one is negative.
  MixedMesh flat = mesh;
  flat.points[3].z() = 0.0;
  EXPECT_NEAR(sliver(flat.points, flat.cell(CellType::tetrahedron, 0)), 0.0, 1e-12);
  const Index inverted[4] = {0, 2, 1, 3};
  EXPECT_LT(sliver(mesh.points, inverted), 0.0);
}

TEST(QualityMetrics, ShearedHexahedronScaledJacobianIsAnalytic) {
  // x ← x + s z: every corner spans (1,0,0), (0,1,0), (s,0,1): det 1, lengths √(1+s²).
  for (double shear : {0.25, 1.0, 3.0}) {
    MixedMesh mesh = reference::single_cell(CellType::hexahedron);
    for (Vector3& point : mesh.points) point.x() += shear * point.z();
    const Index* nodes = mesh.cell(CellType::hexahedron, 0);
    EXPECT_NEAR(scaled_jacobian(CellType::hexahedron, mesh.points, nodes),
                1.0 / std::sqrt(1.0 + shear * shear), 1e-12);
    // The sheared faces have corner angles 90° ± atan(s): equiangle skew atan(s)/90°.
    EXPECT_NEAR(skewness(CellType::hexahedron, mesh.points, nodes), std::atan(shear) / (pi / 2), 1e-12);
    EXPECT_NEAR(aspect_ratio(CellType::hexahedron, mesh.points, nodes), std::sqrt(1.0 + shear * shear),
                1e-12);
  }
}

TEST(QualityMetrics, InvertedCellsHaveNegativeScaledJacobian) {
  for (CellType type : all_cell_types) {
    MixedMesh mesh = regular_cell(type);
    for (Vector3& point : mesh.points) point.z() = -point.z();  // mirror: inverts the cell
    EXPECT_LT(scaled_jacobian(type, mesh.points, mesh.cell(type, 0)), 0.0) << name(type);
  }
}

TEST(QualityMetrics, TallPyramidsAreClippedAtOneButRightPrismsAreNot) {
  // A pyramid of height 1 on the unit square: base corners give √2 · 1/√1.5 > 1.
  const MixedMesh pyramid = reference::single_cell(CellType::pyramid);
  EXPECT_DOUBLE_EQ(scaled_jacobian(CellType::pyramid, pyramid.points, pyramid.cell(CellType::pyramid, 0)),
                   1.0);
  // The right-angled unit prism: its 45° corners give sin 45° · 2/√3 = √(2/3).
  const MixedMesh prism = reference::single_cell(CellType::prism);
  EXPECT_NEAR(scaled_jacobian(CellType::prism, prism.points, prism.cell(CellType::prism, 0)),
              std::sqrt(2.0 / 3.0), 1e-12);
}

// Random perturbations of the reference cells, compared with vtkMeshQuality.
// VTK 9.1's hex edge ratio is not the plain longest/shortest edge, so only the
// tetrahedra compare their aspect ratio (edge_ratio may be null).
template <typename VtkCell>
void compare_with_verdict(CellType type, double (*verdict_jacobian)(vtkCell*),
                          double (*verdict_edge_ratio)(vtkCell*)) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> offset(-0.45, 0.45);
  int compared = 0;
  for (int trial = 0; trial < 200; ++trial) {
    MixedMesh mesh = reference::single_cell(type);
    for (Vector3& point : mesh.points) point += Vector3(offset(random), offset(random), offset(random));
    vtkNew<VtkCell> cell;
    for (int local = 0; local < node_count(type); ++local) {
      const Vector3& point = mesh.points[static_cast<std::size_t>(local)];
      cell->GetPoints()->SetPoint(local, point.x(), point.y(), point.z());
      cell->GetPointIds()->SetId(local, local);
    }
    const Index* nodes = mesh.cell(type, 0);
    const double ours = scaled_jacobian(type, mesh.points, nodes);
    EXPECT_NEAR(ours, verdict_jacobian(cell), 1e-9) << name(type) << " trial " << trial;
    if (verdict_edge_ratio != nullptr) {
      EXPECT_NEAR(aspect_ratio(type, mesh.points, nodes), verdict_edge_ratio(cell), 1e-9) << name(type);
    }
    compared += ours < 0.0;
  }
  // The perturbations are large enough to invert some cells: both signs are covered.
  EXPECT_GT(compared, 0);
}

TEST(QualityMetrics, TetrahedraAgreeWithVerdict) {
  compare_with_verdict<vtkTetra>(CellType::tetrahedron, &vtkMeshQuality::TetScaledJacobian,
                                 &vtkMeshQuality::TetEdgeRatio);
}

TEST(QualityMetrics, HexahedraAgreeWithVerdict) {
  compare_with_verdict<vtkHexahedron>(CellType::hexahedron, &vtkMeshQuality::HexScaledJacobian, nullptr);
}

TEST(QualityMetrics, PlanarRegularCellsAreIdeal) {
  const std::vector<Vector3> points = {
      {0, 0, 0}, {1, 0, 0}, {0.5, std::sqrt(3.0) / 2, 0}, {1, 1, 0}, {0, 1, 0}};
  const Index triangle[3] = {0, 1, 2};
  const Index square[4] = {0, 1, 3, 4};
  EXPECT_NEAR(scaled_jacobian(FaceType::triangle, points, triangle), 1.0, 1e-12);
  EXPECT_NEAR(skewness(FaceType::triangle, points, triangle), 0.0, 1e-12);
  EXPECT_NEAR(scaled_jacobian(FaceType::quad, points, square), 1.0, 1e-12);
  EXPECT_NEAR(aspect_ratio(FaceType::quad, points, square), 1.0, 1e-12);
  const Index clockwise[3] = {0, 2, 1};
  EXPECT_LT(scaled_jacobian(FaceType::triangle, points, clockwise), 0.0);
}

// Two hexahedra sharing the face x = 1, their x edges leaning by −u and +t in y:
// centroids (0.5, 0.5 − u/2, 0.5) and (1.5, 0.5 + t/2, 0.5), face normal +x, so the
// non-orthogonality is atan((t + u) / 2).
TEST(QualityMetrics, NonOrthogonalityOfTwoSkewedHexahedra) {
  const double t = 0.6;
  const double u = 0.4;
  MixedMesh mesh;
  for (double x : {0.0, 1.0, 2.0}) {
    const double lean = x == 0.0 ? -u : (x == 2.0 ? t : 0.0);
    for (double z : {0.0, 1.0})
      for (double y : {0.0, 1.0}) mesh.points.push_back({x, y + lean, z});
  }
  // Points: index 4 x + 2 z + y.
  auto point = [](int x, int y, int z) { return static_cast<Index>(4 * x + 2 * z + y); };
  for (int x = 0; x < 2; ++x) {
    const Index hexahedron[8] = {point(x, 0, 0), point(x + 1, 0, 0), point(x + 1, 1, 0), point(x, 1, 0),
                                 point(x, 0, 1), point(x + 1, 0, 1), point(x + 1, 1, 1), point(x, 1, 1)};
    mesh.add_cell(CellType::hexahedron, hexahedron);
  }
  const FaceConnectivity faces = match_faces(mesh);
  ASSERT_EQ(faces.interior.size(), 1u);
  const std::vector<double> angles = non_orthogonality(mesh, faces);
  ASSERT_EQ(angles.size(), 1u);
  EXPECT_NEAR(angles[0], std::atan((t + u) / 2) * 180 / pi, 1e-10);
  EXPECT_NEAR(angles[0], 26.56505117707799, 1e-10);

  const QualityReport report = measure_quality(mesh);
  const QualityEntry* interior = report.find("non_orthogonality", "interior faces");
  ASSERT_NE(interior, nullptr);
  EXPECT_NEAR(interior->statistics.max, angles[0], 1e-12);
  // The faces x = 0 and x = 2 lean against their cells' centroids; the others do not.
  const QualityEntry* boundary = report.find("non_orthogonality", "boundary faces");
  ASSERT_NE(boundary, nullptr);
  EXPECT_EQ(boundary->statistics.count, 10u);
  EXPECT_NEAR(boundary->statistics.min, 0.0, 1e-10);
}

TEST(QualityMetrics, GrowthRatioFollowsStackedLayers) {
  // A column of three hexahedra of heights 1, 1.2, 1.44 and beside it a column of
  // prisms with the same heights: ratio 1.2 between every pair of layers.
  MixedMesh mesh;
  const std::vector<double> levels = {0.0, 1.0, 2.2, 3.64};
  for (double z : levels)
    for (Vector3 corner : {Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(1, 1, 0), Vector3(0, 1, 0)})
      mesh.points.push_back(corner + Vector3(0, 0, z));
  for (Index layer = 0; layer < 3; ++layer) {
    const Index base = 4 * layer;
    const Index hexahedron[8] = {base, base + 1, base + 2, base + 3, base + 4, base + 5, base + 6, base + 7};
    mesh.add_cell(CellType::hexahedron, hexahedron);
    const Index prism[6] = {base,     base + 3, base + 1,
                            base + 4, base + 7, base + 5};  // clockwise from the top
    mesh.add_cell(CellType::prism, prism);
  }
  ASSERT_GT(signed_volume(CellType::prism, mesh.points, mesh.cell(CellType::prism, 0)), 0.0);
  const QualityReport report = measure_quality(mesh);
  for (const char* entity : {"hexahedron", "prism"}) {
    const QualityEntry* growth = report.find("growth_ratio", entity);
    ASSERT_NE(growth, nullptr) << entity;
    EXPECT_EQ(growth->statistics.count, 2u) << entity;
    EXPECT_NEAR(growth->statistics.min, 1.2, 1e-12) << entity;
    EXPECT_NEAR(growth->statistics.max, 1.2, 1e-12) << entity;
  }
}

TEST(QualityStatistics, PercentilesMeanAndHistogram) {
  std::vector<double> values;
  for (int value = 100; value >= 1; --value) values.push_back(value);
  values.push_back(std::nan(""));
  values.push_back(INFINITY);
  const Statistics statistics = compute_statistics(values, 10);
  EXPECT_EQ(statistics.count, 100u);
  EXPECT_EQ(statistics.non_finite, 2u);
  EXPECT_DOUBLE_EQ(statistics.min, 1.0);
  EXPECT_DOUBLE_EQ(statistics.max, 100.0);
  EXPECT_DOUBLE_EQ(statistics.mean, 50.5);
  // numpy.percentile(range(1, 101), [1, 5, 50, 95, 99])
  const std::array<double, 5> expected = {1.99, 5.95, 50.5, 95.05, 99.01};
  for (std::size_t slot = 0; slot < expected.size(); ++slot)
    EXPECT_NEAR(statistics.percentiles[slot], expected[slot], 1e-12) << statistics_percentiles[slot];
  ASSERT_EQ(statistics.histogram.size(), 10u);
  for (std::size_t bin = 0; bin < 9; ++bin) EXPECT_EQ(statistics.histogram[bin], 10u) << bin;
  EXPECT_EQ(statistics.histogram[9], 10u);
}

TEST(QualityStatistics, EmptyAndConstantInput) {
  const Statistics empty = compute_statistics({}, 4);
  EXPECT_EQ(empty.count, 0u);
  EXPECT_EQ(empty.histogram, std::vector<std::size_t>(4, 0));
  const Statistics constant = compute_statistics({2.0, 2.0, 2.0}, 4);
  EXPECT_EQ(constant.histogram[0], 3u);
  EXPECT_DOUBLE_EQ(constant.percentiles[2], 2.0);
  EXPECT_THROW(compute_statistics({1.0}, 0), Error);
}

}  // namespace
}  // namespace mixmesh
