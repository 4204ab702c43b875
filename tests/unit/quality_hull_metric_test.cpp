// The far-field tetrahedra on the hull, judged in the metric of the cell beneath them.
#include <gtest/gtest.h>

#include <array>
#include <utility>

#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/quality/cell_quality.hpp"
#include "mixmesh/quality/quality.hpp"

namespace mixmesh {
namespace {

// A prism (a layer cell) and a tetrahedron on its top triangle with its fourth point
// over the triangle at `apex`, every point mapped by diag(stretch).
MixedMesh prism_and_tetrahedron(const Vector3& stretch, const Vector3& apex) {
  MixedMesh mesh;
  for (const Vector3& point : {Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(0, 1, 0), Vector3(0, 0, 1),
                               Vector3(1, 0, 1), Vector3(0, 1, 1), apex})
    mesh.points.push_back(stretch.cwiseProduct(point));
  std::array<Index, 6> prism{0, 1, 2, 3, 4, 5};
  if (!cell_shape(CellType::prism, mesh.points, prism.data()).valid()) prism = {0, 2, 1, 3, 5, 4};
  mesh.add_cell(CellType::prism, prism.data());
  std::array<Index, 4> tetrahedron{3, 4, 5, 6};
  if (signed_volume(CellType::tetrahedron, mesh.points, tetrahedron.data()) < 0.0) tetrahedron = {3, 5, 4, 6};
  mesh.add_cell(CellType::tetrahedron, tetrahedron.data());
  return mesh;
}

const Statistics& entry(const QualityReport& report, const std::string& metric) {
  const QualityEntry* found = report.find(metric, "hull tetrahedra");
  EXPECT_NE(found, nullptr) << metric;
  static const Statistics none;
  return found ? found->statistics : none;
}

TEST(QualityHullMetric, ATetrahedronStretchedAsItsLayerCellMeasuresAsUnstretched) {
  // Over a layer cell 10 long, 1 wide and 0.01 high, a tetrahedron that continues it
  // (its point 0.8 of a cell height up, as the far field's first layer point stands)
  // has the same metric edge lengths and shape as over a unit prism: the prism's
  // affine invariant (Wild eq. 11) follows any linear map. Its scaled Jacobian is poor.
  const Vector3 stretch(10.0, 1.0, 0.01);
  const Vector3 apex(1.0 / 3.0, 1.0 / 3.0, 1.8);
  const QualityReport unit = measure_quality(prism_and_tetrahedron(Vector3::Ones(), apex));
  const MixedMesh stretched_mesh = prism_and_tetrahedron(stretch, apex);
  const QualityReport stretched = measure_quality(stretched_mesh);
  EXPECT_EQ(entry(stretched, "metric_shape").count, 1u);
  EXPECT_EQ(entry(stretched, "metric_edge_length").count, 6u);
  EXPECT_NEAR(entry(stretched, "metric_shape").min, entry(unit, "metric_shape").min, 1e-9);
  EXPECT_NEAR(entry(stretched, "metric_edge_length").max, entry(unit, "metric_edge_length").max, 1e-9);
  EXPECT_NEAR(entry(stretched, "metric_edge_length").min, entry(unit, "metric_edge_length").min, 1e-9);
  EXPECT_GT(entry(stretched, "metric_shape").min, 0.5);
  EXPECT_LT(stretched.find("scaled_jacobian", "tetrahedron")->statistics.min, 0.05);
}

TEST(QualityHullMetric, AnIsotropicTetrahedronOverAFlatCellMeasuresAsStretched) {
  // The same flat cell under a tetrahedron whose point stands as high as the cell is
  // wide: a regular-looking tetrahedron, far from what the layer continues.
  const Vector3 stretch(1.0, 1.0, 0.01);
  const QualityReport report = measure_quality(prism_and_tetrahedron(stretch, Vector3(1.0 / 3.0, 1.0 / 3.0, 101.0)));
  EXPECT_LT(entry(report, "metric_shape").max, 0.1);
  EXPECT_GT(entry(report, "metric_edge_length").max, 50.0);
  EXPECT_GT(report.find("scaled_jacobian", "tetrahedron")->statistics.min, 0.5);
}

TEST(QualityHullMetric, AnOuterCellSplitWithTwoOuterFacesKeepsItsPiecesOutOfTheHullTetrahedra) {
  // A prism split about its centre with its top and one side on the hull (a layer cell
  // at the edge of a stopped region): two pyramids on the other sides, a tetrahedron on
  // each triangle and two on the outer side. Its pieces are not far-field tetrahedra;
  // the one far-field tetrahedron on the top is measured once, in its piece's metric.
  MixedMesh mesh;
  mesh.points = {Vector3(0, 0, 0),      Vector3(1, 0, 0), Vector3(0, 1, 0),
                 Vector3(0, 0, 1),      Vector3(1, 0, 1), Vector3(0, 1, 1),
                 Vector3(1.0 / 3.0, 1.0 / 3.0, 0.5), Vector3(1.0 / 3.0, 1.0 / 3.0, 1.8)};
  auto tetrahedron = [&](Index a, Index b, Index c, Index d) {
    std::array<Index, 4> nodes{a, b, c, d};
    if (signed_volume(CellType::tetrahedron, mesh.points, nodes.data()) < 0.0) std::swap(nodes[1], nodes[2]);
    mesh.add_cell(CellType::tetrahedron, nodes.data());
  };
  auto pyramid = [&](Index a, Index b, Index c, Index d) {
    std::array<Index, 5> nodes{a, b, c, d, 6};
    if (!cell_shape(CellType::pyramid, mesh.points, nodes.data()).valid()) std::swap(nodes[1], nodes[3]);
    ASSERT_TRUE(cell_shape(CellType::pyramid, mesh.points, nodes.data()).valid());
    mesh.add_cell(CellType::pyramid, nodes.data());
  };
  tetrahedron(0, 1, 2, 6);  // bottom
  tetrahedron(3, 4, 5, 6);  // top, on the hull
  tetrahedron(0, 1, 4, 6);  // the outer side 0-1-4-3, cut along 0-4
  tetrahedron(0, 4, 3, 6);
  pyramid(1, 2, 5, 4);
  pyramid(2, 0, 3, 5);
  tetrahedron(3, 4, 5, 7);  // the far field's
  const QualityReport report = measure_quality(mesh);
  EXPECT_EQ(entry(report, "metric_shape").count, 1u);
  EXPECT_EQ(entry(report, "metric_edge_length").count, 6u);
}

TEST(QualityHullMetric, TetrahedraAloneHaveNoHullEntries) {
  MixedMesh mesh;
  mesh.points = {Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(0, 1, 0), Vector3(0, 0, 1), Vector3(1, 1, 1)};
  const Index first[4] = {0, 1, 2, 3};
  const Index second[4] = {1, 2, 3, 4};
  mesh.add_cell(CellType::tetrahedron, first);
  mesh.add_cell(CellType::tetrahedron, second);
  EXPECT_EQ(measure_quality(mesh).find("metric_shape", "hull tetrahedra"), nullptr);
}

}  // namespace
}  // namespace mixmesh
