// check_mesh and the report formats on the reference meshes.
#include <gtest/gtest.h>

#include <cmath>

#include "mixmesh/core/error.hpp"
#include "mixmesh/quality/quality.hpp"
#include "mixmesh/quality/report_format.hpp"
#include "reference_cells.hpp"

namespace mixmesh {
namespace {

TEST(QualityReport, CheckMeshCombinesValidityAndQuality) {
  const MixedMesh mesh = reference::four_type_mesh();
  const CheckReport report = check_mesh(mesh);
  EXPECT_TRUE(report.validity.valid());
  for (CellType type : all_cell_types) {
    const QualityEntry* jacobian = report.quality.find("scaled_jacobian", std::string(name(type)));
    ASSERT_NE(jacobian, nullptr) << name(type);
    EXPECT_EQ(jacobian->statistics.count, 1u);
    EXPECT_GT(jacobian->statistics.min, 0.0);
  }
  EXPECT_NE(report.quality.find("sliver", "tetrahedron"), nullptr);
  EXPECT_EQ(report.quality.find("sliver", "hexahedron"), nullptr);
  const QualityEntry* dihedral = report.quality.find("largest_dihedral", "tetrahedron");
  ASSERT_NE(dihedral, nullptr);
  EXPECT_GT(dihedral->statistics.max, 70.0);
  EXPECT_LT(dihedral->statistics.max, 180.0);
  EXPECT_EQ(report.quality.find("largest_dihedral", "pyramid"), nullptr);
  // Three interior faces (hex-pyramid, pyramid-tet, tet-prism); no column of layers.
  EXPECT_EQ(report.quality.find("non_orthogonality", "interior faces")->statistics.count, 3u);
  EXPECT_EQ(report.quality.find("growth_ratio", "prism"), nullptr);

  CheckOptions bad_bins;
  bad_bins.quality.histogram_bins = 0;
  EXPECT_THROW(check_mesh(mesh, bad_bins), Error);
  CheckOptions bad_tolerance;
  bad_tolerance.validity.planar_tolerance = -1.0;
  EXPECT_THROW(check_mesh(mesh, bad_tolerance), Error);
}

TEST(QualityReport, JsonAndTableCarryFindingsAndStatistics) {
  MixedMesh mesh = reference::four_type_mesh();
  mesh.points.push_back({std::nan(""), 0.0, 0.0});  // NaN: reported as such, not also as unused
  const CheckReport report = check_mesh(mesh);
  EXPECT_FALSE(report.validity.valid());
  const std::string json = format_json(mesh, report, {"mesh \"a\".vtu", 0.25});
  EXPECT_NE(json.find("\"file\": \"mesh \\\"a\\\".vtu\""), std::string::npos);
  EXPECT_NE(json.find("\"valid\": false"), std::string::npos);
  EXPECT_NE(json.find("\"read_seconds\": 0.25"), std::string::npos);
  EXPECT_NE(json.find("\"hexahedron\": 1"), std::string::npos);
  EXPECT_NE(
      json.find("{\"check\": \"non_finite_coordinates\", \"description\": \"points with NaN or infinite "
                "coordinates\", \"severity\": \"error\", \"count\": 1, \"examples\": [{\"entity\": "
                "\"point\", \"index\": 13, \"location\": [null, 0, 0], \"detail\": \"\"}]}"),
      std::string::npos)
      << json;
  EXPECT_NE(
      json.find(
          "\"metric\": \"scaled_jacobian\", \"entity\": \"hexahedron\", \"count\": 1, \"non_finite\": 0, "
          "\"min\": 1, \"max\": 1, \"mean\": 1"),
      std::string::npos);
  EXPECT_EQ(json.find("nan"), std::string::npos);

  const std::string table = format_table(mesh, report, {"mesh.vtu", 0.25});
  EXPECT_NE(table.find("non_finite_coordinates             1  ERROR"), std::string::npos) << table;
  EXPECT_NE(table.find("point 13 at (nan, 0.0000, 0.0000)"), std::string::npos) << table;
  EXPECT_NE(table.find("INVALID: 1 error, 0 warnings"), std::string::npos) << table;
}

TEST(QualityReport, PlanarMeshIsCheckedIn2D) {
  MixedMesh mesh;
  mesh.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}};
  mesh.planar_cells[1].nodes = {0, 1, 2, 3, 1, 4, 5, 2};
  mesh.planar_cells[1].markers = {0, 0};
  mesh.boundary_edges.nodes = {0, 1, 1, 4, 4, 5, 5, 2, 2, 3, 3, 0};
  mesh.boundary_edges.markers = {0, 0, 0, 0, 0, 0};
  mesh.marker_names = {"wall"};
  const CheckReport report = check_mesh(mesh);
  EXPECT_TRUE(report.validity.planar);
  EXPECT_TRUE(report.validity.valid()) << report.validity.summary();
  EXPECT_NEAR(report.validity.total_volume, 2.0, 1e-15);
  const QualityEntry* jacobian = report.quality.find("scaled_jacobian", "quad");
  ASSERT_NE(jacobian, nullptr);
  EXPECT_EQ(jacobian->statistics.count, 2u);
  EXPECT_DOUBLE_EQ(jacobian->statistics.min, 1.0);
  EXPECT_EQ(report.quality.find("non_orthogonality", "interior edges")->statistics.count, 1u);
  EXPECT_EQ(report.quality.find("non_orthogonality", "boundary edges")->statistics.count, 6u);
}

}  // namespace
}  // namespace mixmesh
