#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "march_surfaces.hpp"
#include "mixmesh/core/error.hpp"

namespace mixmesh {
namespace {

using march_surfaces::invalid_cell_count;

MarchOptions plate_options(int layers, double first, double growth) {
  MarchOptions options;
  options.spacing.layer_count = layers;
  options.spacing.first_spacing = first;
  options.spacing.growth_rate = growth;
  return options;
}

std::size_t marker_faces(const MixedMesh& mesh, const std::string& name) {
  const int marker = mesh.find_marker(name);
  std::size_t count = 0;
  for (FaceType type : all_face_types)
    count += static_cast<std::size_t>(
        std::count(mesh.faces(type).markers.begin(), mesh.faces(type).markers.end(), marker));
  return marker < 0 ? 0 : count;
}

void expect_closed_and_tagged(const MixedMesh& mesh) {
  const FaceConnectivity faces = match_faces(mesh);
  EXPECT_TRUE(faces.conforming());
  EXPECT_TRUE(faces.untagged_boundary.empty());
  EXPECT_TRUE(faces.stray_boundary_faces.empty());
}

TEST(MarchLayers, FlatPlateGivesStraightHexColumnsWithTheGrowthLaw) {
  const SurfaceMesh plate = march_surfaces::flat_plate(11, 9);
  const BoundaryLayer layer = march_layers(plate, plate_options(8, 0.01, 1.2));
  const MixedMesh& mesh = layer.mesh;
  EXPECT_EQ(mesh.cell_count(CellType::hexahedron), 10u * 8u * 8u);
  EXPECT_EQ(invalid_cell_count(mesh), 0);
  EXPECT_EQ(layer.report.layers_completed, 8);
  EXPECT_EQ(layer.report.stopped_faces, 0);
  EXPECT_NEAR(layer.report.total_thickness, 0.01 * (std::pow(1.2, 8) - 1.0) / 0.2, 1e-12);
  for (const auto& column : layer.column_points) {
    ASSERT_EQ(column.size(), 9u);
    double height = 0.0, step = 0.01;
    for (std::size_t k = 1; k < column.size(); ++k) {
      const Vector3 segment = mesh.points[static_cast<std::size_t>(column[k])] -
                              mesh.points[static_cast<std::size_t>(column[k - 1])];
      EXPECT_NEAR(segment.z(), step, 1e-12);
      EXPECT_NEAR(segment.x(), 0.0, 1e-12);
      EXPECT_NEAR(segment.y(), 0.0, 1e-12);
      height += step;
      step *= 1.2;
    }
    EXPECT_NEAR(mesh.points[static_cast<std::size_t>(column.back())].z(), height, 1e-12);
  }
  EXPECT_EQ(marker_faces(mesh, "plate"), 80u);
  EXPECT_EQ(marker_faces(mesh, "outer_hull"), 80u);
  EXPECT_EQ(marker_faces(mesh, "symmetry"), 10u * 8u);               // the root edge y = 0
  EXPECT_EQ(marker_faces(mesh, "hull_side"), (10u + 2u * 8u) * 8u);  // the three other edges
  expect_closed_and_tagged(mesh);
}

// The outermost layer stands at least outer_layer_height times the shortest front edge
// high (the plate's edges are 0.1 and 0.125 long); the layers below keep the growth law.
TEST(MarchLayers, OutermostLayerIsRaisedToAFractionOfTheShortestEdge) {
  const SurfaceMesh plate = march_surfaces::flat_plate(11, 9);
  for (const double fraction : {0.0, 0.25}) {
    MarchOptions options = plate_options(4, 0.001, 1.2);
    options.outer_layer_height = fraction;
    const BoundaryLayer layer = march_layers(plate, options);
    EXPECT_EQ(invalid_cell_count(layer.mesh), 0);
    for (const auto& column : layer.column_points) {
      ASSERT_EQ(column.size(), 5u);
      auto z = [&](std::size_t k) { return layer.mesh.points[static_cast<std::size_t>(column[k])].z(); };
      EXPECT_NEAR(z(3) - z(2), 0.001 * 1.44, 1e-12);
      EXPECT_NEAR(z(4) - z(3), fraction > 0.0 ? 0.25 * 0.1 : 0.001 * 1.728, 1e-12);
    }
  }
}

TEST(MarchLayers, CylinderLinesStayRadial) {
  const int ni = 17, nj = 9;
  const SurfaceMesh cylinder = march_surfaces::cylinder_patch(ni, nj);
  const BoundaryLayer layer = march_layers(cylinder, plate_options(12, 0.01, 1.25));
  EXPECT_EQ(invalid_cell_count(layer.mesh), 0);
  EXPECT_EQ(layer.report.stopped_faces, 0);
  const StructuredPatch& patch = cylinder.structured[0];
  double worst = 0.0;
  for (std::size_t c = 0; c < layer.column_points.size(); ++c) {
    const Vector3 base = layer.mesh.points[static_cast<std::size_t>(layer.column_points[c].front())];
    const Vector3 top = layer.mesh.points[static_cast<std::size_t>(layer.column_points[c].back())];
    // Lines off the free edges i = 0, ni - 1 (the root row j = 0 lies in the symmetry
    // plane and is closed by its mirror image); they lean a little towards the free
    // edge j = nj - 1, whose lines are only direction-averaged.
    const Index node = layer.column_node[c];
    bool interior = false;
    for (int j = 0; j + 1 < nj; ++j)
      for (int i = 1; i + 1 < ni; ++i) interior |= patch.node(i, j) == node;
    if (!interior) continue;
    const Vector3 radial(base.x(), 0.0, base.z());
    worst =
        std::max(worst, std::acos(std::clamp((top - base).normalized().dot(radial.normalized()), -1.0, 1.0)));
  }
  EXPECT_LT(worst * 180.0 / std::acos(-1.0), 3.0);
  expect_closed_and_tagged(layer.mesh);
}

TEST(MarchLayers, CollidingFrontsStopInsteadOfFolding) {
  // Two plates 0.052 apart facing each other; 20 layers would add 0.1 on each.
  SurfaceMesh surface = march_surfaces::flat_plate(6, 6);
  surface.symmetry_tolerance = -1.0;
  StructuredPatch upper = march_surfaces::grid_patch(surface, "upper", 6, 6, [](int i, int j) {
    return Vector3(0.2 * j, 0.2 * i, 0.052);  // i and j swapped: normal -z
  });
  surface.structured.push_back(upper);
  const BoundaryLayer layer = march_layers(surface, plate_options(20, 0.005, 1.0));
  EXPECT_EQ(invalid_cell_count(layer.mesh), 0);
  EXPECT_GT(layer.report.stopped_faces, 0);
  EXPECT_LT(layer.report.layers_completed, 20);
  EXPECT_FALSE(layer.report.stopped.empty());
  // The lower plate's points stay below the upper plate's: the fronts never crossed.
  double lower_top = -1.0, upper_bottom = 1.0;
  for (std::size_t c = 0; c < layer.column_points.size(); ++c)
    for (Index point : layer.column_points[c]) {
      const double z = layer.mesh.points[static_cast<std::size_t>(point)].z();
      if (layer.column_node[c] < 36)
        lower_top = std::max(lower_top, z);
      else
        upper_bottom = std::min(upper_bottom, z);
    }
  EXPECT_LT(lower_top, upper_bottom);
  expect_closed_and_tagged(layer.mesh);
}

TEST(MarchLayers, TrianglePatchGivesValidPrisms) {
  const SurfaceMesh patch = march_surfaces::triangle_patch(4, 0.1);
  const BoundaryLayer layer = march_layers(patch, plate_options(10, 0.005, 1.2));
  EXPECT_EQ(layer.mesh.cell_count(CellType::prism), patch.unstructured[0].triangles.size() / 3 * 10);
  EXPECT_EQ(invalid_cell_count(layer.mesh), 0);
  for (const auto& column : layer.column_points) {
    const Vector3 line = layer.mesh.points[static_cast<std::size_t>(column.back())] -
                         layer.mesh.points[static_cast<std::size_t>(column.front())];
    EXPECT_NEAR(line.normalized().z(), 1.0, 1e-9);
  }
  expect_closed_and_tagged(layer.mesh);
}

TEST(MarchLayers, RejectsBadSurfaces) {
  SurfaceMesh plate = march_surfaces::flat_plate(4, 4);
  plate.structured[0].nodes[5] = 99;
  EXPECT_THROW(march_layers(plate, MarchOptions{}), Error);
  SurfaceMesh flipped = march_surfaces::flat_plate(4, 4);
  TrianglePatch patch;
  patch.name = "flipped";
  // A triangle over the corner quad running its edge (0,0)-(1,0) the same way.
  const StructuredPatch& grid = flipped.structured[0];
  patch.triangles = {grid.node(0, 0), grid.node(1, 0), grid.node(0, 1)};
  flipped.unstructured.push_back(patch);
  EXPECT_THROW(march_layers(flipped, MarchOptions{}), Error);
  SurfaceMesh short_patch = march_surfaces::flat_plate(4, 4);
  short_patch.structured[0].nj = 5;
  EXPECT_THROW(march_layers(short_patch, MarchOptions{}), Error);
  MarchOptions bad;
  bad.sweeps = -1;
  EXPECT_THROW(march_layers(march_surfaces::flat_plate(4, 4), bad), Error);
  for (double turn : {-1.0, 181.0, std::nan("")}) {
    MarchOptions bad_turn;
    bad_turn.maximum_turn_degrees = turn;
    EXPECT_THROW(march_layers(march_surfaces::flat_plate(4, 4), bad_turn), Error);
  }
}

TEST(MarchLayers, TurnLimitBoundsTheTurnOfEveryLine) {
  // Lines round a cylinder patch bend as the layers grow as thick as its cells are
  // wide; with the limit no segment turns by more than it (no step was halved here).
  const SurfaceMesh cylinder = march_surfaces::cylinder_patch(17, 9);
  MarchOptions options = plate_options(24, 0.002, 1.3);
  options.maximum_turn_degrees = 0.0;
  const BoundaryLayer free_lines = march_layers(cylinder, options);
  options.maximum_turn_degrees = 0.5;
  const BoundaryLayer limited = march_layers(cylinder, options);
  ASSERT_EQ(limited.report.reduced_steps, 0);
  EXPECT_EQ(invalid_cell_count(limited.mesh), 0);
  auto largest_turn = [](const BoundaryLayer& layer) {
    double largest = 0.0;
    for (const auto& column : layer.column_points)
      for (std::size_t k = 1; k + 1 < column.size(); ++k) {
        const Vector3 below = layer.mesh.points[static_cast<std::size_t>(column[k])] -
                              layer.mesh.points[static_cast<std::size_t>(column[k - 1])];
        const Vector3 above = layer.mesh.points[static_cast<std::size_t>(column[k + 1])] -
                              layer.mesh.points[static_cast<std::size_t>(column[k])];
        largest = std::max(largest, std::atan2(below.cross(above).norm(), below.dot(above)) * 180.0 / M_PI);
      }
    return largest;
  };
  EXPECT_GT(largest_turn(free_lines), 0.5);
  EXPECT_LE(largest_turn(limited), 0.5 + 1e-9);
}

}  // namespace
}  // namespace mixmesh
