// validate() on hand-built meshes with one planted fault each.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mixmesh/core/error.hpp"
#include "mixmesh/quality/quality.hpp"
#include "mixmesh/quality/validity.hpp"
#include "reference_cells.hpp"

namespace mixmesh {
namespace {

ValidityOptions with_tolerance(double tolerance) {
  ValidityOptions options;
  options.duplicate_tolerance = tolerance;
  return options;
}

ValidityOptions markers_optional() {
  ValidityOptions options;
  options.require_markers = false;
  return options;
}

std::size_t count_of(const ValidityReport& report, const std::string& check) {
  const Finding* finding = report.find(check);
  EXPECT_NE(finding, nullptr) << check;
  return finding == nullptr ? 0 : finding->count;
}

// Every finding zero except the ones named.
void expect_only(const ValidityReport& report, const std::vector<std::string>& checks) {
  for (const Finding& finding : report.findings) {
    const bool expected = std::find(checks.begin(), checks.end(), finding.check) != checks.end();
    EXPECT_EQ(finding.count > 0, expected) << finding.check << ": " << finding.count;
  }
}

TEST(QualityValidity, FourTypeMeshIsValid) {
  const MixedMesh mesh = reference::four_type_mesh();
  const ValidityReport report = validate(mesh);
  EXPECT_TRUE(report.valid()) << report.summary();
  expect_only(report, {});
  EXPECT_EQ(report.interior_faces, 3u);
  EXPECT_EQ(report.boundary_faces, mesh.face_count());
  double volume = 0.0;
  for (CellType type : all_cell_types) volume += signed_volume(type, mesh.points, mesh.cell(type, 0));
  EXPECT_NEAR(report.total_volume, volume, 1e-12);
  EXPECT_EQ(report.summary(), "valid: 0 errors, 0 warnings");
}

TEST(QualityValidity, InvertedCellIsReportedWithItsIndex) {
  MixedMesh mesh = reference::four_type_mesh();
  // A second tetrahedron block entry, inverted: the fault is at index 1.
  const Index* tetrahedron = mesh.cell(CellType::tetrahedron, 0);
  const Index inverted[4] = {tetrahedron[0], tetrahedron[2], tetrahedron[1], tetrahedron[3]};
  MixedMesh alone;
  alone.points = mesh.points;
  alone.add_cell(CellType::tetrahedron, tetrahedron);
  alone.add_cell(CellType::tetrahedron, inverted);
  const ValidityReport report = validate(alone, markers_optional());
  EXPECT_FALSE(report.valid());
  const Finding* finding = report.find("non_positive_volume");
  ASSERT_NE(finding, nullptr);
  ASSERT_EQ(finding->count, 1u);
  EXPECT_EQ(finding->examples[0].entity, "tetrahedron");
  EXPECT_EQ(finding->examples[0].index, 1u);
  // The same four faces on both cells, wound oppositely: interior, not a crack.
  EXPECT_EQ(report.interior_faces, 4u);
  EXPECT_EQ(count_of(report, "same_orientation"), 0u);
  EXPECT_NE(report.summary().find("INVALID"), std::string::npos);
  EXPECT_NE(report.summary().find("1 cells with non-positive volume"), std::string::npos);
}

TEST(QualityValidity, InvertedCellInMeshWindsItsInteriorFacesWrongly) {
  MixedMesh mesh = reference::four_type_mesh();
  std::swap(mesh.block(CellType::tetrahedron).nodes[0], mesh.block(CellType::tetrahedron).nodes[1]);
  const ValidityReport report = validate(mesh);
  // The tet touches the pyramid and the prism: two interior faces wound alike.
  EXPECT_EQ(count_of(report, "non_positive_volume"), 1u);
  EXPECT_EQ(count_of(report, "same_orientation"), 2u);
  // Its two boundary triangles no longer match their tagged faces' winding, but a
  // marker matches faces by nodes, so they stay tagged.
  EXPECT_EQ(count_of(report, "untagged_boundary_faces"), 0u);
}

// The warped wake hexahedron (reference_cells.hpp): every sub-tetrahedron positive, its
// face pyramids inverted, so checkMesh rejects it.
TEST(QualityValidity, HexahedronWithInvertedFacePyramidsIsTangled) {
  MixedMesh mesh = reference::single_cell(CellType::hexahedron);
  mesh.points = reference::warped_wake_hexahedron();
  ASSERT_TRUE(cell_shape(CellType::hexahedron, mesh.points, mesh.cell(CellType::hexahedron, 0)).valid());
  reference::tag_boundary(mesh);
  const ValidityReport report = validate(mesh);
  EXPECT_FALSE(report.valid());
  expect_only(report, {"tangled_cells"});
}

TEST(QualityValidity, TangledHexahedronWithPositiveVolume) {
  MixedMesh mesh = reference::single_cell(CellType::hexahedron);
  mesh.points[6] = {0.45, 0.45, 0.45};  // folded into the cell: corner 6 inverts
  const CellShape shape = cell_shape(CellType::hexahedron, mesh.points, mesh.cell(CellType::hexahedron, 0));
  ASSERT_GT(shape.volume, 0.0);
  ASSERT_GT(shape.negative_corners, 0);
  reference::tag_boundary(mesh);
  const ValidityReport report = validate(mesh);
  EXPECT_FALSE(report.valid());
  expect_only(report, {"tangled_cells"});
  EXPECT_EQ(report.find("tangled_cells")->examples[0].index, 0u);
}

TEST(QualityValidity, UnusedAndDuplicatePoints) {
  MixedMesh mesh = reference::four_type_mesh();
  const std::size_t original = mesh.points.size();
  mesh.points.push_back(mesh.points[3] + Vector3(1e-15, 0, 0));  // duplicate of 3, unused
  mesh.points.push_back({7, 7, 7});                              // unused
  const ValidityReport report = validate(mesh);
  EXPECT_FALSE(report.valid());
  expect_only(report, {"unused_points", "duplicate_points"});
  const Finding* unused = report.find("unused_points");
  EXPECT_EQ(unused->severity, Finding::Severity::warning);
  ASSERT_EQ(unused->count, 2u);
  EXPECT_EQ(unused->examples[0].index, original);
  EXPECT_EQ(unused->examples[1].index, original + 1);
  EXPECT_EQ(unused->examples[1].location, Vector3(7, 7, 7));
  const Finding* duplicates = report.find("duplicate_points");
  ASSERT_EQ(duplicates->count, 2u);
  EXPECT_EQ(duplicates->examples[0].index, 3u);
  EXPECT_EQ(duplicates->examples[1].index, original);
  // A tolerance below the gap finds no duplicate; a tolerance out of range is an error.
  EXPECT_EQ(count_of(validate(mesh, with_tolerance(0.0)), "duplicate_points"), 0u);
  EXPECT_THROW(validate(mesh, with_tolerance(0.5)), Error);
}

TEST(QualityValidity, DuplicatePointsMatchBruteForce) {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> coordinate(0.0, 1.0);
  MixedMesh mesh = reference::single_cell(CellType::tetrahedron);
  for (int point = 0; point < 3000; ++point)
    mesh.points.push_back({coordinate(random), coordinate(random), coordinate(random)});
  // Planted pairs at distances around the tolerance (1e-4 of the diagonal √3).
  const double tolerance = 1e-4 * std::sqrt(3.0);
  for (double distance : {0.2, 0.9, 0.999, 1.001, 3.0}) {
    const Vector3 base(coordinate(random), coordinate(random), coordinate(random));
    mesh.points.push_back(base);
    mesh.points.push_back(base + distance * tolerance * Vector3(1, 1, 1).normalized());
  }
  mesh.points.push_back({0, 0, 0});  // exact copy of point 0 in a grid corner
  std::size_t expected = 0;
  for (std::size_t a = 0; a < mesh.points.size(); ++a) {
    bool found = false;
    for (std::size_t b = 0; b < mesh.points.size() && !found; ++b)
      found = a != b && (mesh.points[a] - mesh.points[b]).norm() <= tolerance;
    expected += found;
  }
  EXPECT_EQ(expected, 8u);  // three planted pairs within, the exact copy and point 0
  EXPECT_EQ(count_of(validate(mesh, with_tolerance(1e-4)), "duplicate_points"), expected);
}

TEST(QualityValidity, UntaggedAndStrayBoundaryFaces) {
  MixedMesh mesh = reference::four_type_mesh();
  // Drop the last boundary quad: its cell face is untagged.
  FaceBlock& quads = mesh.faces(FaceType::quad);
  quads.nodes.resize(quads.nodes.size() - 4);
  quads.markers.pop_back();
  ValidityReport report = validate(mesh);
  EXPECT_FALSE(report.valid());
  expect_only(report, {"untagged_boundary_faces"});
  EXPECT_EQ(count_of(report, "untagged_boundary_faces"), 1u);
  // Not required: a warning, the mesh stays valid.
  EXPECT_TRUE(validate(mesh, markers_optional()).valid());

  // Tag the interior face between hexahedron and pyramid.
  mesh = reference::four_type_mesh();
  const Index interior[4] = {4, 5, 6, 7};
  mesh.add_face(FaceType::quad, interior, mesh.marker("wall"));
  report = validate(mesh);
  expect_only(report, {"markers_off_boundary"});
  const Finding* stray = report.find("markers_off_boundary");
  EXPECT_EQ(stray->examples[0].entity, "quad face");
  EXPECT_EQ(stray->examples[0].index, mesh.face_count(FaceType::quad) - 1);
  EXPECT_TRUE(stray->examples[0].location.isApprox(Vector3(0.5, 0.5, 1.0)));
}

TEST(QualityValidity, FaceOnThreeCellsAndTriangleAgainstQuad) {
  MixedMesh mesh = reference::four_type_mesh();
  mesh.add_cell(CellType::tetrahedron, mesh.cell(CellType::tetrahedron, 0));  // same tet twice
  EXPECT_GT(count_of(validate(mesh), "faces_on_many_cells"), 0u);

  // A tetrahedron standing on half of the cube's top face, no pyramid between.
  mesh = reference::single_cell(CellType::hexahedron);
  mesh.points.push_back({0.5, 0.5, 2.0});
  const Index tetrahedron[4] = {4, 5, 6, 8};
  mesh.add_cell(CellType::tetrahedron, tetrahedron);
  reference::orient_positively(mesh);
  reference::tag_boundary(mesh);
  const ValidityReport report = validate(mesh);
  EXPECT_FALSE(report.valid());
  EXPECT_EQ(count_of(report, "triangle_against_quad"), 1u);
  EXPECT_EQ(report.find("triangle_against_quad")->examples.size(), 1u);
  // The quad's edge 4-6 diagonal and the triangle's edges do not close the boundary.
  EXPECT_GT(count_of(report, "open_boundary_edges"), 0u);
}

TEST(QualityValidity, CrackBetweenTwoCubesShowsAsDuplicates) {
  // Two unit cubes side by side, each with its own copy of the shared face's points.
  MixedMesh mesh;
  for (double offset : {0.0, 1.0}) {
    const Index base = static_cast<Index>(mesh.points.size());
    for (const Vector3& point : reference::single_cell(CellType::hexahedron).points)
      mesh.points.push_back(point + Vector3(offset, 0, 0));
    const Index hexahedron[8] = {base, base + 1, base + 2, base + 3, base + 4, base + 5, base + 6, base + 7};
    mesh.add_cell(CellType::hexahedron, hexahedron);
  }
  reference::tag_boundary(mesh);
  const ValidityReport report = validate(mesh);
  EXPECT_FALSE(report.valid());
  expect_only(report, {"duplicate_points"});
  EXPECT_EQ(count_of(report, "duplicate_points"), 8u);
}

TEST(QualityValidity, NonFiniteCoordinatesAndBadIndices) {
  MixedMesh mesh = reference::four_type_mesh();
  mesh.points[9].y() = std::nan("");
  ValidityReport report = validate(mesh);
  EXPECT_FALSE(report.valid());
  EXPECT_EQ(count_of(report, "non_finite_coordinates"), 1u);
  EXPECT_EQ(report.find("non_finite_coordinates")->examples[0].index, 9u);

  mesh = reference::four_type_mesh();
  mesh.block(CellType::prism).nodes[2] = 1000;
  report = validate(mesh);  // must not touch point 1000
  EXPECT_FALSE(report.valid());
  ASSERT_EQ(report.findings.size(), 1u);
  EXPECT_EQ(report.findings[0].check, "node_index_out_of_range");
  EXPECT_EQ(report.findings[0].examples[0].entity, "prism");
  EXPECT_THROW(measure_quality(mesh), Error);
  const CheckReport check = check_mesh(mesh);
  EXPECT_FALSE(check.validity.valid());
  EXPECT_TRUE(check.quality.entries.empty());
}

TEST(QualityValidity, EmptyMeshIsInvalid) {
  const ValidityReport report = validate(MixedMesh{});
  EXPECT_FALSE(report.valid());
  expect_only(report, {"no_cells"});
}

// Two triangles on the unit square, counter-clockwise, boundary edges tagged.
MixedMesh planar_square() {
  MixedMesh mesh;
  mesh.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  mesh.planar_cells[0].nodes = {0, 1, 2, 0, 2, 3};
  mesh.planar_cells[0].markers = {0, 0};
  mesh.boundary_edges.nodes = {0, 1, 1, 2, 2, 3, 3, 0};
  mesh.boundary_edges.markers = {0, 0, 0, 0};
  mesh.marker_names = {"wall"};
  return mesh;
}

TEST(QualityValidity, PlanarMeshChecks) {
  MixedMesh mesh = planar_square();
  ValidityReport report = validate(mesh);
  EXPECT_TRUE(report.planar);
  EXPECT_TRUE(report.valid()) << report.summary();
  EXPECT_EQ(report.interior_faces, 1u);
  EXPECT_EQ(report.boundary_faces, 4u);
  EXPECT_NEAR(report.total_volume, 1.0, 1e-15);

  mesh.planar_cells[0].nodes = {0, 2, 1, 0, 2, 3};  // first triangle clockwise
  report = validate(mesh);
  EXPECT_EQ(count_of(report, "non_positive_area"), 1u);
  EXPECT_EQ(count_of(report, "same_orientation"), 1u);

  mesh = planar_square();
  mesh.boundary_edges.nodes.resize(6);
  mesh.boundary_edges.markers.resize(3);
  mesh.points[2].z() = 0.1;
  report = validate(mesh);
  expect_only(report, {"untagged_boundary_edges", "points_off_plane"});
  EXPECT_EQ(report.find("points_off_plane")->examples[0].index, 2u);

  const QualityReport quality = measure_quality(planar_square());
  const QualityEntry* jacobian = quality.find("scaled_jacobian", "triangle");
  ASSERT_NE(jacobian, nullptr);
  // Right isosceles triangles: min corner sin 45° · 2/√3.
  EXPECT_NEAR(jacobian->statistics.min, std::sqrt(2.0 / 3.0), 1e-12);
  const QualityEntry* interior = quality.find("non_orthogonality", "interior edges");
  ASSERT_NE(interior, nullptr);
  EXPECT_NEAR(interior->statistics.max, 0.0, 1e-10);  // centres symmetric about the diagonal
}

}  // namespace
}  // namespace mixmesh
