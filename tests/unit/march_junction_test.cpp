#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <utility>

#include "march_surfaces.hpp"
#include "mixmesh/march/march_metrics.hpp"
#include "mixmesh/mesh/face_connectivity.hpp"

namespace mixmesh {
namespace {

MarchOptions junction_options() {
  MarchOptions options;
  options.spacing.layer_count = 16;
  options.spacing.first_spacing = 1e-5;
  options.spacing.growth_rate = 1.25;
  return options;
}

march_surfaces::TestWing small_wing() {
  march_surfaces::TestWing wing;
  wing.chordwise_cells = 32;
  wing.spanwise_cells = 8;
  wing.sweep_degrees = 30.0;
  wing.taper = 0.5;
  return wing;
}

// Boundary edges (sorted node pairs) of the cells, each with the number of boundary
// faces on it.
std::map<std::pair<Index, Index>, int> boundary_edges(const MixedMesh& mesh, const FaceConnectivity& faces) {
  std::map<std::pair<Index, Index>, int> edges;
  for (const CellFace& face : faces.boundary) {
    Index nodes[4];
    const int count = face_nodes(mesh, face, nodes);
    for (int k = 0; k < count; ++k) {
      const Index a = nodes[k], b = nodes[(k + 1) % count];
      ++edges[{std::min(a, b), std::max(a, b)}];
    }
  }
  return edges;
}

TEST(MarchJunction, TipTrailingEdgeOfAWingWithWakeIsClosed) {
  const SurfaceMesh surface = march_surfaces::wing(small_wing());
  const BoundaryLayer layer = march_layers(surface, junction_options());
  // One junction: the tip trailing edge, where the wake's free edge meets the tip cap.
  EXPECT_EQ(layer.report.junctions, 1);
  EXPECT_EQ(layer.mesh.cell_count(CellType::tetrahedron), 2u);
  EXPECT_EQ(layer.tetrahedron_face.size(), 2u);
  EXPECT_EQ(layer.report.stopped_faces, 0);
  EXPECT_EQ(march_surfaces::invalid_cell_count(layer.mesh), 0);

  // The split face's stack: its first cell and the hexahedra above it up to some layer
  // below the outermost, four pyramids per layer, in place of those hexahedra. The first
  // cell alone is a first spacing (1e-5) high under a trailing-edge triangle a few
  // hundred times wider: its pieces on that triangle and on its top quad were flat
  // (scaled Jacobian about 1e-3, largest dihedral angle near 180 degrees).
  const std::size_t pyramids = layer.mesh.cell_count(CellType::pyramid);
  EXPECT_EQ(pyramids % 4, 0u);
  EXPECT_GE(pyramids, 4u);
  EXPECT_LE(pyramids, 4u * 15u);
  EXPECT_EQ(layer.pyramid_face.size(), pyramids);
  const int split_face = layer.tetrahedron_face.front();
  std::size_t split_hexahedra = 0;
  for (int face : layer.hexahedron_face) split_hexahedra += face == split_face;
  EXPECT_EQ(split_hexahedra + pyramids / 4, 16u);
  EXPECT_GT(layer.report.junction_minimum_scaled_jacobian, 0.1);
  EXPECT_LT(layer.report.junction_largest_dihedral_degrees, 160.0);

  // The split face: a wall triangle with four lines, two of them from one wall point.
  const int split = split_face;
  const auto& columns = layer.face_columns[static_cast<std::size_t>(split)];
  ASSERT_EQ(columns.size(), 4u);
  EXPECT_EQ(layer.column_node[static_cast<std::size_t>(columns[0])],
            layer.column_node[static_cast<std::size_t>(columns[3])]);
  EXPECT_EQ(layer.column_side[static_cast<std::size_t>(columns[0])],
            -layer.column_side[static_cast<std::size_t>(columns[3])]);
  EXPECT_NE(layer.column_side[static_cast<std::size_t>(columns[0])], 0);
  EXPECT_EQ(layer.face_layers[static_cast<std::size_t>(split)], 16);

  // Conforming, every boundary face tagged, and the boundary closed and edge-manifold.
  const FaceConnectivity faces = match_faces(layer.mesh);
  EXPECT_TRUE(faces.conforming());
  EXPECT_TRUE(faces.untagged_boundary.empty());
  EXPECT_TRUE(faces.stray_boundary_faces.empty());
  int non_manifold = 0;
  for (const auto& [edge, count] : boundary_edges(layer.mesh, faces)) non_manifold += count != 2;
  EXPECT_EQ(non_manifold, 0);

  // Every line but the junction's two starts along its wall normal; those two open the
  // gap between the sheet's sides towards the tip cap, so they lean from the wall normal
  // of the wing face and the cap corner they start from (42.6 degrees on the ONERA M6).
  const MarchMetrics metrics = measure_march(layer, surface, "wing");
  EXPECT_LT(metrics.percentile99_normal_deviation_degrees, 1e-6);
  EXPECT_GE(metrics.fraction_within_2_degrees, 0.99);
  EXPECT_LT(metrics.maximum_normal_deviation_degrees, 50.0);  // 43.8 here
  EXPECT_EQ(metrics.invalid_cells, 0);
  EXPECT_DOUBLE_EQ(metrics.junction_minimum_scaled_jacobian, layer.report.junction_minimum_scaled_jacobian);
}

TEST(MarchJunction, WingWithoutWakeHasNoJunction) {
  march_surfaces::TestWing wing = small_wing();
  SurfaceMesh surface = march_surfaces::wing(wing);
  // Drop the wake patch: the trailing edge is then an ordinary wall edge.
  surface.structured.erase(
      std::remove_if(surface.structured.begin(), surface.structured.end(),
                     [](const StructuredPatch& patch) { return patch.role == PatchRole::wake; }),
      surface.structured.end());
  const BoundaryLayer layer = march_layers(surface, junction_options());
  EXPECT_EQ(layer.report.junctions, 0);
  EXPECT_EQ(layer.mesh.cell_count(CellType::pyramid), 0u);
  EXPECT_EQ(layer.mesh.cell_count(CellType::tetrahedron), 0u);
  EXPECT_DOUBLE_EQ(measure_march(layer, surface, "wing").junction_minimum_scaled_jacobian, 1.0);
}

TEST(MarchJunction, NormalBaselineKeepsTheSameTopology) {
  // The baseline marches the same front: its split face is there too (it may stop, as
  // plain normals give no opening between the two lines), and nothing it emits is invalid.
  const SurfaceMesh surface = march_surfaces::wing(small_wing());
  MarchOptions options = junction_options();
  options.method = MarchMethod::normal;
  const BoundaryLayer layer = march_layers(surface, options);
  EXPECT_EQ(march_surfaces::invalid_cell_count(layer.mesh), 0);
  const FaceConnectivity faces = match_faces(layer.mesh);
  EXPECT_TRUE(faces.conforming());
  EXPECT_TRUE(faces.untagged_boundary.empty());
  int non_manifold = 0;
  for (const auto& [edge, count] : boundary_edges(layer.mesh, faces)) non_manifold += count != 2;
  EXPECT_EQ(non_manifold, 0);
  bool split_face = false;
  for (const auto& columns : layer.face_columns)
    split_face |= columns.size() == 4 && layer.column_node[static_cast<std::size_t>(columns[0])] ==
                                             layer.column_node[static_cast<std::size_t>(columns[3])];
  EXPECT_TRUE(split_face);
}

}  // namespace
}  // namespace mixmesh
