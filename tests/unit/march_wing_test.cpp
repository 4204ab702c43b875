#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "march_surfaces.hpp"
#include "mixmesh/march/march_metrics.hpp"
#include "mixmesh/mesh/face_connectivity.hpp"
#include "mixmesh/quality/validity.hpp"

namespace mixmesh {
namespace {

MarchOptions wing_options() {
  MarchOptions options;
  options.spacing.layer_count = 32;
  // y+ = 1 at Re = 1e7 on the unit root chord: about 2.5e-6, 32 layers, 1.25 growth.
  options.spacing.target_y_plus = 1.0;
  options.spacing.reynolds_number = 1e7;
  options.spacing.reference_length = 1.0;
  options.spacing.growth_rate = 1.25;
  return options;
}

void print(const char* name, const BoundaryLayer& layer, const MarchMetrics& m) {
  std::printf(
      "%-9s cells %6zu invalid %d  min s.J. %.4f  first line max/p99 %.2f/%.2f deg  growth jump %.3f  "
      "turn max/p99 %.2f/%.2f deg  stopped faces %d\n",
      name, layer.mesh.cell_count(), m.invalid_cells, m.minimum_scaled_jacobian,
      m.maximum_normal_deviation_degrees, m.percentile99_normal_deviation_degrees, m.maximum_growth_jump,
      m.maximum_line_turn_degrees, m.percentile99_line_turn_degrees, layer.report.stopped_faces);
  for (const StoppedRegion& region : layer.report.stopped)
    std::printf("  %d faces stopped at layer %d near (%.4f, %.4f, %.4f)\n", region.faces, region.layer,
                region.location.x(), region.location.y(), region.location.z());
}

march_surfaces::TestWing coarse_wing(int spanwise_cells) {
  march_surfaces::TestWing wing;
  wing.chordwise_cells = 48;
  wing.spanwise_cells = spanwise_cells;
  return wing;
}

void check_wing(const march_surfaces::TestWing& wing) {
  const SurfaceMesh surface = march_surfaces::wing(wing);
  const BoundaryLayer layer = march_layers(surface, wing_options());
  const MarchMetrics metrics = measure_march(layer, surface, "wing");
  print("smoothed", layer, metrics);
  MarchOptions normal = wing_options();
  normal.method = MarchMethod::normal;
  const BoundaryLayer plain = march_layers(surface, normal);
  const MarchMetrics baseline = measure_march(plain, surface, "wing");
  print("normal", plain, baseline);
  // The smoothed march against plain normal extrusion (docs/march.md, Comparison).
  EXPECT_GT(metrics.minimum_scaled_jacobian, baseline.minimum_scaled_jacobian);
  EXPECT_LT(metrics.percentile99_normal_deviation_degrees, baseline.percentile99_normal_deviation_degrees);
  EXPECT_LT(metrics.maximum_growth_jump, baseline.maximum_growth_jump);
  EXPECT_LT(metrics.maximum_line_turn_degrees, baseline.maximum_line_turn_degrees);
  EXPECT_LE(layer.report.stopped_faces, plain.report.stopped_faces);
  EXPECT_EQ(metrics.invalid_cells, 0);
  EXPECT_EQ(layer.report.thinned_lines, 0);  // a sharp trailing edge is no concave corner
  EXPECT_GE(metrics.fraction_within_2_degrees, 0.99);
  EXPECT_EQ(layer.report.stopped_faces, 0);
  // Lines starting in the symmetry plane stay exactly in it.
  for (std::size_t c = 0; c < layer.column_points.size(); ++c)
    if (surface.points[static_cast<std::size_t>(layer.column_node[c])].y() == 0.0) {
      for (Index point : layer.column_points[c]) {
        EXPECT_EQ(layer.mesh.points[static_cast<std::size_t>(point)].y(), 0.0);
      }
    }
  // The wake sheet is interior: its faces carry cells on both sides and no marker. (Its
  // tip edge's wrap faces, whose first and last lines start at one point, are not sheet faces.)
  EXPECT_LT(layer.mesh.find_marker("wake"), 0);
  std::size_t wake_cells = 0;
  for (std::size_t f = 0; f < layer.face_wall.size(); ++f) {
    const std::vector<int>& columns = layer.face_columns[f];
    const bool wrap = layer.column_node[static_cast<std::size_t>(columns.front())] ==
                      layer.column_node[static_cast<std::size_t>(columns.back())];
    wake_cells += layer.face_wall[f] || wrap ? 0 : 1;
  }
  EXPECT_EQ(wake_cells % 2, 0u);
  EXPECT_GT(wake_cells, 0u);
  const FaceConnectivity faces = match_faces(layer.mesh);
  EXPECT_TRUE(faces.conforming());
  EXPECT_TRUE(faces.untagged_boundary.empty());
  EXPECT_TRUE(faces.stray_boundary_faces.empty());
}

TEST(MarchWing, StraightWing) {
  check_wing({});
}

TEST(MarchWing, SweptTaperedTwistedWing) {
  march_surfaces::TestWing wing;
  wing.sweep_degrees = 45.0;
  wing.taper = 0.3;
  wing.tip_twist_degrees = -5.0;
  check_wing(wing);
}

TEST(MarchWing, ThickWing) {
  march_surfaces::TestWing wing;
  wing.naca = "0021";
  check_wing(wing);
}

// Four layers on the coarse wing with a blunt base and the wake leaving from its middle.
BoundaryLayer blunt_base_layers() {
  march_surfaces::TestWing wing = coarse_wing(8);
  wing.blunt_base = true;
  MarchOptions options = wing_options();
  options.spacing.layer_count = 4;
  return march_layers(march_surfaces::wing(wing), options);
}

// A blunt base with the wake leaving from its middle: at the root the sheet's edge lies
// in the symmetry plane, which closes it, so the base faces there join the lines above
// and below the sheet like the rest of the base; as a free edge of the sheet they got
// a line of their own and the layers' faces on the plane did not close round it.
TEST(MarchWing, BluntBaseLayersCloseOnTheSymmetryPlane) {
  const BoundaryLayer layer = blunt_base_layers();
  EXPECT_EQ(march_surfaces::invalid_cell_count(layer.mesh), 0);
  const FaceConnectivity faces = match_faces(layer.mesh);
  EXPECT_TRUE(faces.conforming());
  EXPECT_TRUE(faces.untagged_boundary.empty());
  EXPECT_TRUE(validate(layer.mesh).valid());
}

// At the tip's end of a blunt base the wake's free edge starts: the base's faces join
// the lines above and below the sheet there too, and the tip triangle across the sheet
// is split between them. Before, that end of the base kept a line of its own, the two
// sheet lines there started as one, and the base's last faces stopped at the first layer.
TEST(MarchWing, BluntBaseWithAWakeGrowsItsFirstLayersAtTheTip) {
  const BoundaryLayer layer = blunt_base_layers();
  EXPECT_EQ(layer.report.stopped_faces, 0);
  EXPECT_EQ(march_surfaces::invalid_cell_count(layer.mesh), 0);
  EXPECT_TRUE(match_faces(layer.mesh).conforming());
}

// A base swept 37.5 degrees looks downstream and inboard while the tip looks outboard,
// and the wake's free edge leaves the base's middle straight downstream. The junction's
// lines took the base's normal (one of them leaned under the split tip triangle), and the
// split triangle had an edge on the base, so its column's corner there was straight:
// the split face stopped at the first layer (random wings with swept bases, seed 13).
TEST(MarchWing, SweptBluntBaseWithAWakeGrowsEveryLayerAtTheTip) {
  march_surfaces::TestWing wing = coarse_wing(8);
  wing.blunt_base = true;
  wing.sweep_degrees = 37.5;
  wing.taper = 0.85;
  MarchOptions options = wing_options();
  options.spacing.layer_count = 8;
  const BoundaryLayer layer = march_layers(march_surfaces::wing(wing), options);
  EXPECT_EQ(layer.report.stopped_faces, 0);
  EXPECT_EQ(march_surfaces::invalid_cell_count(layer.mesh), 0);
  EXPECT_TRUE(match_faces(layer.mesh).conforming());
}

// Thirty-two layers 14 mm thick over a base half 1.26 mm high: offset from the
// base and from the sheet, they swallowed the faces next to the concave corner between
// them, and the base's columns stopped (every random wing with a base and a wake
// stopped). The lines near the corner keep every layer in a thinner stack instead
// (concave_corners.hpp), so the whole front grows all its layers.
TEST(MarchWing, BluntBaseWithAWakeGrowsEveryLayerRoundItsCorners) {
  march_surfaces::TestWing wing = coarse_wing(8);
  wing.blunt_base = true;
  const SurfaceMesh surface = march_surfaces::wing(wing);
  const BoundaryLayer layer = march_layers(surface, wing_options());
  EXPECT_EQ(layer.report.stopped_faces, 0);
  EXPECT_EQ(layer.report.layers_completed, 32);
  EXPECT_GT(layer.report.thinned_lines, 0);
  EXPECT_EQ(march_surfaces::invalid_cell_count(layer.mesh), 0);
  EXPECT_TRUE(match_faces(layer.mesh).conforming());
  // The wing away from its base keeps the full stack: the thinning is local.
  std::size_t full = 0, lines = 0;
  for (std::size_t c = 0; c < layer.column_points.size(); ++c) {
    const Vector3& start = surface.points[static_cast<std::size_t>(layer.column_node[c])];
    if (start.x() > 0.5) continue;
    ++lines;
    const Vector3& top = layer.mesh.points[static_cast<std::size_t>(layer.column_points[c].back())];
    full += (top - start).norm() > 0.95 * layer.report.total_thickness;
  }
  EXPECT_EQ(full, lines);
  // Every line from the wing (the base's included), thinned or not, keeps the wall's
  // first step (its y+); the wake's lines relax theirs downstream by design.
  for (std::size_t c = 0; c < layer.column_points.size(); ++c) {
    if (surface.points[static_cast<std::size_t>(layer.column_node[c])].x() > 1.0 + 1e-9) continue;
    const std::vector<Index>& points = layer.column_points[c];
    ASSERT_GE(points.size(), 2u);
    const double first = (layer.mesh.points[static_cast<std::size_t>(points[1])] -
                          layer.mesh.points[static_cast<std::size_t>(points[0])])
                             .norm();
    EXPECT_NEAR(first, layer.report.first_spacing, 0.01 * layer.report.first_spacing) << "line " << c;
  }
}

// generate lowers the layers round a place where the hull crossed itself. A stop whose
// reach is smaller than the faces at the root's trailing edge (5 mm here) reaches them by
// their nodes: by their centroids alone it reached none and the retries there changed
// nothing (random wing 12 of seed 13, whose root faces are long spanwise).
TEST(MarchWing, AForcedStopReachesTheLongFacesAtTheRoot) {
  MarchOptions options = wing_options();
  options.spacing.layer_count = 8;
  ForcedStop stop;
  stop.centre = Vector3(1.0, 0.0, 0.0);  // the root's trailing edge
  stop.radius = 0.005;
  stop.layer = 2;
  options.forced_stops.push_back(stop);
  const BoundaryLayer layer = march_layers(march_surfaces::wing(coarse_wing(8)), options);
  int stopped = 0;
  for (int layers : layer.face_layers) stopped += layers <= 2;
  EXPECT_GT(stopped, 0);
  EXPECT_EQ(march_surfaces::invalid_cell_count(layer.mesh), 0);
  EXPECT_TRUE(match_faces(layer.mesh).conforming());
}

TEST(MarchWing, WakeEndLinesStayInTheEndPlaneAndTheTipEdgeStaysFree) {
  // Untapered, unswept, twisted: the wake ends in the plane x = const, its sheet tilts
  // from root to tip. Every line from the end stays in that plane to the last bit
  // (within 1e-15 m of it the far field filled the hull with slivers); the lines of
  // the wake's tip edge still turn out round the tip.
  march_surfaces::TestWing wing = coarse_wing(12);
  wing.tip_twist_degrees = 5.0;
  const SurfaceMesh surface = march_surfaces::wing(wing);
  MarchOptions options = wing_options();
  options.spacing.layer_count = 24;
  const BoundaryLayer layer = march_layers(surface, options);
  ASSERT_EQ(layer.report.stopped_faces, 0);
  double end = -1e300, tip = -1e300;
  for (const Vector3& point : surface.points) {
    end = std::max(end, point.x());
    tip = std::max(tip, point.y());
  }
  int end_lines = 0;
  double tip_edge_outboard = 0.0;
  for (std::size_t column = 0; column < layer.column_node.size(); ++column) {
    const Vector3& start = surface.points[static_cast<std::size_t>(layer.column_node[column])];
    const Vector3& top = layer.mesh.points[static_cast<std::size_t>(layer.column_points[column].back())];
    if (start.x() == end) {
      ++end_lines;
      for (Index point : layer.column_points[column])
        EXPECT_EQ(layer.mesh.points[static_cast<std::size_t>(point)].x(), end) << "line " << column;
    } else if (start.y() == tip && start.x() > wing.root_chord + 0.1) {
      tip_edge_outboard = std::max(tip_edge_outboard, top.y() - tip);
    }
  }
  EXPECT_EQ(end_lines, 2 * (wing.spanwise_cells + 1)) << "above and below the sheet";
  EXPECT_GT(tip_edge_outboard, 0.0);
  EXPECT_EQ(march_surfaces::invalid_cell_count(layer.mesh), 0);
}

}  // namespace
}  // namespace mixmesh
