#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/mesh/face_connectivity.hpp"
#include "mixmesh/mesh/topology.hpp"
#include "mixmesh/mesh/visible_direction.hpp"
#include "reference_cells.hpp"

using namespace mixmesh;

class EveryCellType : public ::testing::TestWithParam<CellType> {};

INSTANTIATE_TEST_SUITE_P(Topology, EveryCellType,
                         ::testing::ValuesIn(all_cell_types.begin(), all_cell_types.end()),
                         [](const auto& info) { return std::string(name(info.param)); });

TEST_P(EveryCellType, FacesCloseTheCellWithEveryEdgeUsedTwiceInOppositeDirections) {
  const CellDescriptor& cell = descriptor(GetParam());
  std::map<std::pair<int, int>, int> directed;
  int corners = 0;
  for (int face = 0; face < cell.face_count; ++face) {
    const LocalFace& local = cell.faces[face];
    for (int corner = 0; corner < local.node_count; ++corner)
      ++directed[{local.nodes[corner], local.nodes[(corner + 1) % local.node_count]}];
    corners += local.node_count;
  }
  EXPECT_EQ(corners, 2 * cell.edge_count);
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(directed.count({edge.second, edge.first}), 1u);
  }
  for (int edge = 0; edge < cell.edge_count; ++edge) {
    const auto [a, b] = cell.edges[edge];
    EXPECT_EQ(directed.count({a, b}) + directed.count({b, a}), 2u) << "edge " << a << "-" << b;
  }
}

TEST_P(EveryCellType, FaceNormalsPointOutOfTheReferenceCell) {
  const MixedMesh mesh = reference::single_cell(GetParam());
  const Index* nodes = mesh.cell(GetParam(), 0);
  const Vector3 centre = cell_centre(GetParam(), mesh.points, nodes);
  const CellDescriptor& cell = descriptor(GetParam());
  Vector3 closure = Vector3::Zero();
  for (int face = 0; face < cell.face_count; ++face) {
    const LocalFace& local = cell.faces[face];
    Index corners[4];
    Vector3 face_centre = Vector3::Zero();
    for (int corner = 0; corner < local.node_count; ++corner) {
      corners[corner] = nodes[local.nodes[corner]];
      face_centre += mesh.points[static_cast<std::size_t>(corners[corner])] / local.node_count;
    }
    const Vector3 normal = face_area_vector(mesh.points, corners, local.node_count);
    EXPECT_GT(normal.dot(face_centre - centre), 0.0) << "face " << face;
    closure += normal;
  }
  EXPECT_NEAR(closure.norm(), 0.0, 1e-14);
}

TEST(CellGeometry, ReferenceVolumesAreExact) {
  for (auto [type, volume] :
       {std::pair{CellType::tetrahedron, 1.0 / 6.0}, std::pair{CellType::pyramid, 1.0 / 3.0},
        std::pair{CellType::prism, 0.5}, std::pair{CellType::hexahedron, 1.0}}) {
    const MixedMesh mesh = reference::single_cell(type);
    const CellShape shape = cell_shape(type, mesh.points, mesh.cell(type, 0));
    EXPECT_NEAR(shape.volume, volume, 1e-15) << name(type);
    EXPECT_TRUE(shape.valid()) << name(type);
    EXPECT_GT(shape.min_corner_jacobian, 0.0);
  }
}

TEST(CellGeometry, CircumcentreIsEquallyFarFromAllFourPointsAndAbsentForAFlatSet) {
  const Vector3 a(0.3, -1.0, 2.0), b(2.0, 0.5, 1.0), c(-0.5, 1.5, 0.2), d(0.1, 0.2, -1.7);
  const std::optional<Vector3> centre = tetrahedron_circumcentre(a, b, c, d);
  ASSERT_TRUE(centre.has_value());
  const double radius = (a - *centre).norm();
  for (const Vector3& p : {b, c, d}) EXPECT_NEAR((p - *centre).norm(), radius, 1e-12 * radius);
  EXPECT_FALSE(
      tetrahedron_circumcentre(Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(0, 1, 0), Vector3(1, 1, 0))
          .has_value());
}

// The warped wake hexahedron (reference_cells.hpp): every corner and sub-tetrahedron is
// positive, yet OpenFOAM's checkMesh finds its face pyramids on the centroid inverted.
TEST(CellGeometry, ThinWarpedHexahedronHasInvertedFacePyramids) {
  const std::vector<Vector3> points = reference::warped_wake_hexahedron();
  const Index nodes[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  EXPECT_TRUE(cell_shape(CellType::hexahedron, points, nodes).valid());
  EXPECT_GT(inverted_face_pyramids(CellType::hexahedron, points, nodes), 0);
  // The same cell without the warp (its top lifted straight off its bottom) passes.
  std::vector<Vector3> flat = points;
  for (int corner = 0; corner < 4; ++corner) flat[corner + 4] = flat[corner] + Vector3(0.0, 0.0, 8e-6);
  EXPECT_TRUE(cell_shape(CellType::hexahedron, flat, nodes).valid());
  EXPECT_EQ(inverted_face_pyramids(CellType::hexahedron, flat, nodes), 0);
  // Reference cells of every type pass.
  for (CellType type : all_cell_types) {
    const MixedMesh mesh = reference::single_cell(type);
    EXPECT_EQ(inverted_face_pyramids(type, mesh.points, mesh.cell(type, 0)), 0) << name(type);
  }
}

TEST(CellGeometry, MirroredCellsAreInvalid) {
  for (CellType type : all_cell_types) {
    MixedMesh mesh = reference::single_cell(type);
    for (Vector3& point : mesh.points) point.z() = -point.z();
    const CellShape shape = cell_shape(type, mesh.points, mesh.cell(type, 0));
    EXPECT_LT(shape.volume, 0.0) << name(type);
    EXPECT_FALSE(shape.valid()) << name(type);
  }
}

TEST(CellGeometry, TangledHexahedronWithPositiveVolumeIsInvalid) {
  MixedMesh mesh = reference::single_cell(CellType::hexahedron);
  // Push the top corner 6 down through the bottom: the total stays positive but
  // the corners at 6 and its neighbours fold.
  mesh.points[6] = {0.6, 0.6, -0.3};
  const CellShape shape = cell_shape(CellType::hexahedron, mesh.points, mesh.cell(CellType::hexahedron, 0));
  EXPECT_GT(shape.volume, 0.0);
  EXPECT_FALSE(shape.valid());
  EXPECT_GT(shape.negative_corners, 0);
}

TEST(CellGeometry, ShearedPrismStaysValid) {
  MixedMesh mesh = reference::single_cell(CellType::prism);
  for (int top = 3; top < 6; ++top) mesh.points[static_cast<std::size_t>(top)].x() += 0.7;
  const CellShape shape = cell_shape(CellType::prism, mesh.points, mesh.cell(CellType::prism, 0));
  EXPECT_NEAR(shape.volume, 0.5, 1e-14);
  EXPECT_TRUE(shape.valid());
}

TEST(FaceConnectivity, FourTypeMeshIsConformingAndFullyTagged) {
  const MixedMesh mesh = reference::four_type_mesh();
  for (CellType type : all_cell_types) EXPECT_EQ(mesh.cell_count(type), 1u) << name(type);
  const FaceConnectivity faces = match_faces(mesh);
  EXPECT_TRUE(faces.conforming());
  EXPECT_EQ(faces.interior.size(), 3u);  // hex-pyramid, pyramid-tet, tet-prism
  EXPECT_EQ(faces.boundary.size(), 6u + 5u + 4u + 5u - 2u * 3u);
  EXPECT_TRUE(faces.untagged_boundary.empty());
  EXPECT_TRUE(faces.stray_boundary_faces.empty());
  EXPECT_EQ(mesh.face_count(), faces.boundary.size());
  const auto& quad_markers = mesh.faces(FaceType::quad).markers;
  EXPECT_EQ(std::count(quad_markers.begin(), quad_markers.end(), mesh.find_marker("wall")), 1);
}

TEST(FaceConnectivity, DetectsInvertedNeighbourAndUntaggedFaces) {
  MixedMesh mesh = reference::single_cell(CellType::hexahedron);
  // A second hex on top, given with the same winding of the shared face.
  for (int node = 4; node < 8; ++node)
    mesh.points.push_back(mesh.points[static_cast<std::size_t>(node)] + Vector3(0, 0, 1));
  const Index upside_down[8] = {8, 9, 10, 11, 4, 5, 6, 7};
  mesh.add_cell(CellType::hexahedron, upside_down);
  const FaceConnectivity faces = match_faces(mesh);
  EXPECT_EQ(faces.same_orientation.size(), 1u);
  EXPECT_FALSE(faces.conforming());
  EXPECT_EQ(faces.untagged_boundary.size(), 10u);
}

TEST(FaceConnectivity, DetectsTriangleAgainstQuad) {
  MixedMesh mesh = reference::single_cell(CellType::hexahedron);
  mesh.points.push_back({0.5, 0.5, 2.0});
  const Index tetrahedron[4] = {4, 5, 6, 8};
  mesh.add_cell(CellType::tetrahedron, tetrahedron);
  reference::orient_positively(mesh);
  EXPECT_EQ(match_faces(mesh).triangles_in_quads, 1u);
}

TEST(FaceConnectivity, FaceSharedByThreeCellsIsReported) {
  MixedMesh mesh;
  mesh.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, -1}, {1, 1, 1}};
  const Index cells[3][4] = {{0, 1, 2, 3}, {0, 2, 1, 4}, {0, 1, 2, 5}};
  for (const auto& cell : cells) mesh.add_cell(CellType::tetrahedron, cell);
  EXPECT_EQ(match_faces(mesh).shared_by_many.size(), 3u);
}

TEST(MixedMesh, CompactionRemovesUnusedPointsAndRenumbers) {
  MixedMesh mesh;
  mesh.points = {{9, 9, 9}, {0, 0, 0}, {1, 0, 0}, {8, 8, 8}, {0, 1, 0}, {0, 0, 1}};
  const Index tetrahedron[4] = {1, 2, 4, 5};
  mesh.add_cell(CellType::tetrahedron, tetrahedron);
  const Index triangle[3] = {1, 4, 2};
  mesh.add_face(FaceType::triangle, triangle, mesh.marker("wall"));
  const std::vector<Index> renumber = compact_points(mesh);
  EXPECT_EQ(mesh.points.size(), 4u);
  EXPECT_EQ(renumber[0], -1);
  EXPECT_EQ(renumber[3], -1);
  EXPECT_EQ(mesh.block(CellType::tetrahedron).nodes, (std::vector<Index>{0, 1, 2, 3}));
  EXPECT_EQ(mesh.faces(FaceType::triangle).nodes, (std::vector<Index>{0, 2, 1}));
  EXPECT_NEAR(signed_volume(CellType::tetrahedron, mesh.points, mesh.cell(CellType::tetrahedron, 0)),
              1.0 / 6.0, 1e-15);
}

TEST(MixedMesh, MarkersAreFoundOrAdded) {
  MixedMesh mesh;
  EXPECT_EQ(mesh.marker("wall"), 0);
  EXPECT_EQ(mesh.marker("farfield"), 1);
  EXPECT_EQ(mesh.marker("wall"), 0);
  EXPECT_EQ(mesh.find_marker("symmetry"), -1);
}

// A swept base's normal (cos 37.5, -sin 37.5, 0) and a flat tip's (0, 1, 0): the mean
// direction sees the base at 64 degrees and the tip at 116; the best direction sees both
// equally, along their bisector.
TEST(VisibleDirection, SeesEveryFaceEquallyAtItsBest) {
  const double sweep = 37.5 * M_PI / 180.0;
  const Vector3 base(std::cos(sweep), -std::sin(sweep), 0.0), tip(0.0, 1.0, 0.0);
  const Vector3 best = visible_direction({base, tip, base});
  EXPECT_NEAR(best.norm(), 1.0, 1e-12);
  EXPECT_NEAR(best.dot(base), best.dot(tip), 1e-12);
  EXPECT_NEAR(best.dot(tip), std::cos(0.5 * (M_PI / 2.0 + sweep)), 1e-12);
  // One face alone: its normal. A third face inside the cone of the two: no change.
  EXPECT_NEAR((visible_direction({tip}) - tip).norm(), 0.0, 1e-12);
  const Vector3 between = (base + tip).normalized();
  EXPECT_NEAR((visible_direction({base, tip, between}) - best).norm(), 0.0, 1e-12);
  // Three faces: the direction that sees them equally when that is the best.
  const Vector3 up(0.0, 0.0, 1.0);
  const Vector3 three = visible_direction({base, tip, up});
  EXPECT_NEAR(three.dot(base), three.dot(up), 1e-12);
  EXPECT_NEAR(three.dot(tip), three.dot(up), 1e-12);
  EXPECT_GT(three.dot(up), 0.0);
  // Normals all round: no direction sees every face.
  EXPECT_EQ(visible_direction({up, -up, tip}), Vector3::Zero());
  EXPECT_EQ(visible_direction({}), Vector3::Zero());
}
