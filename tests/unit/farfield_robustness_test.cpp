// Far field on thin bodies: the preconditioning's map back must not leave flat
// tetrahedra on planar boundary parts, and anisotropic layer points must keep clear of
// the hull edges over thin parts of the body (trailing edges, the wake's ends).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <sstream>

#include "mixmesh/core/error.hpp"
#include "mixmesh/farfield/farfield.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/mesh/face_connectivity.hpp"

using namespace mixmesh;

namespace {

// The surface of an axis-aligned box from `lower` with the given size and cells per
// axis, triangles facing outward; `open_bottom` leaves out the face y = lower.y, and
// `sweep_degrees` shears x by tan(sweep) · y (a swept slab).
FarFieldInput slab(const Vector3& lower, const Vector3& size, const std::array<int, 3>& cells,
                   bool open_bottom, double sweep_degrees, double incidence_degrees = 0.0) {
  FarFieldInput input;
  std::map<std::array<int, 3>, Index> lattice;
  auto node = [&](const std::array<int, 3>& at) {
    const auto found = lattice.find(at);
    if (found != lattice.end()) return found->second;
    Vector3 point = lower;
    for (int axis = 0; axis < 3; ++axis)
      point(axis) += size(axis) * at[static_cast<std::size_t>(axis)] / cells[static_cast<std::size_t>(axis)];
    point.x() += std::tan(sweep_degrees * M_PI / 180.0) * (point.y() - lower.y());
    // Incidence: a turn about the y axis, which keeps the plane y = lower.y.
    const double turn = incidence_degrees * M_PI / 180.0;
    point = Vector3(std::cos(turn) * point.x() + std::sin(turn) * point.z(), point.y(),
                    -std::sin(turn) * point.x() + std::cos(turn) * point.z());
    input.points.push_back(point);
    return lattice[at] = static_cast<Index>(input.points.size() - 1);
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      if (open_bottom && axis == 1 && side == 0) continue;
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      for (int i = 0; i < cells[static_cast<std::size_t>(u)]; ++i)
        for (int j = 0; j < cells[static_cast<std::size_t>(v)]; ++j) {
          std::array<Index, 4> quad{};
          const int corners[4][2] = {{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}};
          for (int corner = 0; corner < 4; ++corner) {
            std::array<int, 3> at{};
            at[static_cast<std::size_t>(axis)] = side * cells[static_cast<std::size_t>(axis)];
            at[static_cast<std::size_t>(u)] = corners[corner][0];
            at[static_cast<std::size_t>(v)] = corners[corner][1];
            quad[static_cast<std::size_t>(corner)] = node(at);
          }
          if (side == 1) {
            input.hull.push_back({quad[0], quad[1], quad[2]});
            input.hull.push_back({quad[0], quad[2], quad[3]});
          } else {
            input.hull.push_back({quad[0], quad[2], quad[1]});
            input.hull.push_back({quad[0], quad[3], quad[2]});
          }
        }
    }
  return input;
}

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

FarFieldOptions small_options() {
  FarFieldOptions options;
  options.radius_in_chords = 5.0;
  options.farfield_size_in_chords = 1.5;
  options.size_gradient = 0.4;
  return options;
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
