// Far field on thin bodies: the preconditioning's map back must not leave flat
// tetrahedra on planar boundary parts, and anisotropic layer points must keep clear of
// the hull edges over thin parts of the body (trailing edges, the wake's ends).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <sstream>

#include "../support/farfield_hulls.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/farfield/farfield.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/mesh/face_connectivity.hpp"

using namespace mixmesh;

namespace {

using farfield_hulls::slab;
using farfield_hulls::small_options;

// Metric of a layer `normal_spacing` thick under a face `tangential` wide, for every
// hull node, with the normal along the slab's thin axis z.
void add_layer_metrics(FarFieldInput& input, double normal_spacing, double tangential) {
  for (std::size_t node = 0; node < input.points.size(); ++node) {
    input.metric_nodes.push_back(static_cast<Index>(node));
    Matrix3 metric = Matrix3::Zero();
    metric(0, 0) = metric(1, 1) = 1.0 / (tangential * tangential);
    metric(2, 2) = 1.0 / (normal_spacing * normal_spacing);
    input.metrics.push_back(metric);
  }
}

// Every tetrahedron as written has positive volume, and together they fill exactly the
// volume their boundary encloses (no overlap hidden by a reordering of nodes).
void expect_positive_and_filling(const FarFieldInput& input, const FarFieldResult& result) {
  const MixedMesh& mesh = result.mesh;
  ASSERT_GT(mesh.cell_count(CellType::tetrahedron), 0u);
  EXPECT_EQ(result.flat_tetrahedra, 0u);
  double volume6 = 0.0;
  std::size_t non_positive = 0;
  for (std::size_t cell = 0; cell < mesh.cell_count(CellType::tetrahedron); ++cell) {
    const Index* nodes = mesh.cell(CellType::tetrahedron, cell);
    const double part = tetrahedron_volume6(
        mesh.points[static_cast<std::size_t>(nodes[0])], mesh.points[static_cast<std::size_t>(nodes[1])],
        mesh.points[static_cast<std::size_t>(nodes[2])], mesh.points[static_cast<std::size_t>(nodes[3])]);
    non_positive += !(part > 0.0);
    volume6 += part;
  }
  EXPECT_EQ(non_positive, 0u);
  double enclosed6 = 0.0;
  auto face_part = [&](const Index* nodes) {
    return tetrahedron_volume6(Vector3::Zero(), mesh.points[static_cast<std::size_t>(nodes[0])],
                               mesh.points[static_cast<std::size_t>(nodes[1])],
                               mesh.points[static_cast<std::size_t>(nodes[2])]);
  };
  for (std::size_t face = 0; face < mesh.face_count(FaceType::triangle); ++face)
    enclosed6 += face_part(mesh.face(FaceType::triangle, face));
  for (const auto& triangle : input.hull) enclosed6 -= face_part(triangle.data());
  EXPECT_NEAR(volume6, enclosed6, 1e-9 * volume6);
  MixedMesh closed = mesh;
  const int wall = closed.marker("wall");
  for (const auto& triangle : input.hull) closed.add_face(FaceType::triangle, triangle.data(), wall);
  EXPECT_TRUE(match_faces(closed).conforming());
}

}  // namespace

// A swept plate 1 % thick: the whitening map is far from orthogonal, and rounding
// moves the points of the plate's flat faces and of the symmetry plane off their
// planes. TetGen then fills the dents with slivers that are flat or inverted in the
// original coordinates; the stage must triangulate those again where the geometry is exact.
TEST(FarFieldRobustness, PreconditionedThinSweptPlateMapsBackWithoutFlatTetrahedra) {
  const FarFieldInput input = slab({0.0, 0.0, -0.005}, {1.0, 3.0, 0.01}, {16, 24, 1}, true, 30.0, 10.0);
  for (AffineMap affine : {AffineMap::whitening, AffineMap::inverse}) {
    FarFieldOptions options = small_options();
    options.precondition = true;
    options.preconditioning.affine = affine;
    std::ostringstream said;
    const FarFieldResult result = farfield(input, options, Log(&said));
    expect_positive_and_filling(input, result);
    EXPECT_NE(said.str().find("farfield: quality pass"), std::string::npos) << said.str();
  }
}

// A plate 2 % thick with layers a twentieth of a face wide: the layer points near the
// plate's ends must stay above L²/(8τ), or the hull edges there stop being Delaunay.
TEST(FarFieldRobustness, LayerPointsKeepClearOfHullEdgesOverThinParts) {
  FarFieldInput input = slab({-0.5, -0.5, -0.01}, {1.0, 1.0, 0.02}, {8, 8, 1}, false, 0.0);
  add_layer_metrics(input, 0.125 / 20.0, 0.125);
  FarFieldOptions options = small_options();
  options.sizing = FarFieldSizing::anisotropic;
  options.maximum_layers = 40;  // columns that reach above the protected height
  std::ostringstream said;
  const FarFieldResult result = farfield(input, options, Log(&said));
  // The stage prints the hull's metric edge-length distribution and both passes.
  EXPECT_NE(said.str().find("metric edge lengths at the hull"), std::string::npos) << said.str();
  EXPECT_NE(said.str().find("farfield: exact pass"), std::string::npos) << said.str();
  ASSERT_GT(result.hull_lengths.edges, 0u);
  EXPECT_GT(result.hull_lengths.within_range, 0.0);
  // Over the plate's faces (|z| = 0.01) the thickness below is 0.02 and the longest hull
  // edge at a node is a face diagonal: no new point within the protected height there.
  const double longest = 0.125 * std::sqrt(2.0);
  const double protected_height = options.edge_protection * longest * longest / (8.0 * 0.02);
  std::size_t above_faces = 0;
  for (std::size_t node = input.points.size(); node < result.mesh.points.size(); ++node) {
    const Vector3& point = result.mesh.points[node];
    if (std::abs(point.x()) > 0.45 || std::abs(point.y()) > 0.45) continue;  // over the plate's rim
    const double height = std::abs(point.z()) - 0.01;
    if (height > 4.0 * protected_height) continue;
    ++above_faces;
    EXPECT_GE(height, protected_height * (1.0 - 1e-9)) << point.transpose();
  }
  EXPECT_GT(above_faces, 0u);
  expect_positive_and_filling(input, result);
  EXPECT_GT(result.layer_points, 0u);
}

TEST(FarFieldRobustness, ThinPlateWithoutMetricsIsRejectedForAnisotropicSizing) {
  const FarFieldInput input = slab({-0.5, -0.5, -0.01}, {1.0, 1.0, 0.02}, {4, 4, 1}, false, 0.0);
  FarFieldOptions options = small_options();
  options.sizing = FarFieldSizing::anisotropic;
  EXPECT_THROW(farfield(input, options), Error);
  FarFieldOptions negative = small_options();
  negative.edge_protection = -1.0;
  EXPECT_THROW(farfield(input, negative), Error);
}
