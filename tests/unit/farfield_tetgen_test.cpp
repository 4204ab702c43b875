#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <vector>

#include "../support/farfield_hulls.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/farfield/farfield.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/mesh/face_connectivity.hpp"

using namespace mixmesh;

namespace {

using farfield_hulls::small_options;

using Triangles = std::vector<std::array<Index, 3>>;

// Flips triangles so their normals point away from `inside`.
void orient_away(FarFieldInput& input, const Vector3& inside) {
  for (auto& triangle : input.hull) {
    const Vector3 normal = face_area_vector(input.points, triangle.data(), 3);
    const Vector3 centre = (input.points[static_cast<std::size_t>(triangle[0])] +
                            input.points[static_cast<std::size_t>(triangle[1])] +
                            input.points[static_cast<std::size_t>(triangle[2])]) /
                           3.0;
    if (normal.dot(centre - inside) < 0) std::swap(triangle[1], triangle[2]);
  }
}

// The surface of the box [x0, x0+1] × [y0, y0+1] × [-0.5, 0.5] on an n × n grid per
// face; `open_bottom` leaves out the face y = y0.
FarFieldInput box_hull(int n, double x0, double y0, bool open_bottom) {
  FarFieldInput input;
  std::map<std::array<int, 3>, Index> lattice;
  auto node = [&](std::array<int, 3> at) {
    const auto found = lattice.find(at);
    if (found != lattice.end()) return found->second;
    input.points.emplace_back(x0 + double(at[0]) / n, y0 + double(at[1]) / n, -0.5 + double(at[2]) / n);
    return lattice[at] = static_cast<Index>(input.points.size() - 1);
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      if (open_bottom && axis == 1 && side == 0) continue;
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          std::array<Index, 4> quad{};
          const int corners[4][2] = {{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}};
          for (int corner = 0; corner < 4; ++corner) {
            std::array<int, 3> at{};
            at[axis] = side * n;
            at[u] = corners[corner][0];
            at[v] = corners[corner][1];
            quad[corner] = node(at);
          }
          input.hull.push_back({quad[0], quad[1], quad[2]});
          input.hull.push_back({quad[0], quad[2], quad[3]});
        }
    }
  orient_away(input, Vector3(x0 + 0.5, y0 + 0.5, 0.0));
  return input;
}

// A hemisphere of radius 0.5 on y = 0 (pole at +y), with the metrics of a thin layer
// of prisms beneath it.
FarFieldInput hemisphere_hull(int rings, int sectors) {
  FarFieldInput input;
  input.points.emplace_back(0.0, 0.5, 0.0);
  for (int ring = 1; ring <= rings; ++ring) {
    const double polar = M_PI / 2 * ring / rings;
    for (int sector = 0; sector < sectors; ++sector) {
      const double azimuth = 2 * M_PI * sector / sectors;
      input.points.emplace_back(0.5 * std::sin(polar) * std::cos(azimuth),
                                ring == rings ? 0.0 : 0.5 * std::cos(polar),
                                0.5 * std::sin(polar) * std::sin(azimuth));
    }
  }
  auto at = [&](int ring, int sector) {
    return static_cast<Index>(1 + (ring - 1) * sectors + (sector % sectors));
  };
  for (int sector = 0; sector < sectors; ++sector)
    input.hull.push_back({0, at(1, sector), at(1, sector + 1)});
  for (int ring = 1; ring < rings; ++ring)
    for (int sector = 0; sector < sectors; ++sector) {
      input.hull.push_back({at(ring, sector), at(ring + 1, sector), at(ring + 1, sector + 1)});
      input.hull.push_back({at(ring, sector), at(ring + 1, sector + 1), at(ring, sector + 1)});
    }
  orient_away(input, Vector3::Zero());
  // Metrics from a layer of prisms beneath the hull, a fifth of a hull edge thick.
  MixedMesh layer;
  layer.points = input.points;
  const double thickness = 0.2 * (0.5 * M_PI / 2 / rings);
  for (const Vector3& point : input.points) {
    Vector3 inner = point * (0.5 - thickness) / 0.5;
    if (point.y() == 0.0) inner.y() = 0.0;
    layer.points.push_back(inner);
  }
  const Index inner_offset = static_cast<Index>(input.points.size());
  for (const auto& triangle : input.hull) {
    Index prism[6] = {triangle[0] + inner_offset,
                      triangle[2] + inner_offset,
                      triangle[1] + inner_offset,
                      triangle[0],
                      triangle[2],
                      triangle[1]};
    if (signed_volume(CellType::prism, layer.points, prism) < 0) {
      std::swap(prism[1], prism[2]);
      std::swap(prism[4], prism[5]);
    }
    layer.add_cell(CellType::prism, prism);
  }
  for (std::size_t node = 0; node < input.points.size(); ++node)
    input.metric_nodes.push_back(static_cast<Index>(node));
  input.metrics = node_metrics(layer, input.metric_nodes);
  return input;
}

// The far field plus the hull as tagged faces: a closed, conforming, valid mesh whose
// volume equals the volume its boundary encloses.
void expect_sound_farfield(const FarFieldInput& input, const FarFieldResult& result, bool symmetric) {
  MixedMesh mesh = result.mesh;
  ASSERT_GT(mesh.cell_count(CellType::tetrahedron), 0u);
  for (std::size_t node = 0; node < input.points.size(); ++node)
    ASSERT_EQ(mesh.points[node], input.points[node]);
  const int wall = mesh.marker("wall");
  for (const auto& triangle : input.hull) mesh.add_face(FaceType::triangle, triangle.data(), wall);

  int invalid = 0;
  double volume = 0.0;
  for (std::size_t cell = 0; cell < mesh.cell_count(CellType::tetrahedron); ++cell) {
    const CellShape shape =
        cell_shape(CellType::tetrahedron, mesh.points, mesh.cell(CellType::tetrahedron, cell));
    invalid += !shape.valid();
    volume += shape.volume;
  }
  EXPECT_EQ(invalid, 0);

  const FaceConnectivity faces = match_faces(mesh);
  EXPECT_TRUE(faces.conforming());
  EXPECT_TRUE(faces.untagged_boundary.empty());
  EXPECT_TRUE(faces.stray_boundary_faces.empty());
  EXPECT_EQ(faces.boundary.size(), mesh.face_count());

  // Divergence theorem over the tagged faces (far field and symmetry are written
  // outward from the tetrahedra; the hull points into the domain, so it counts negative).
  double enclosed6 = 0.0;
  const int symmetry = mesh.find_marker("symmetry");
  std::size_t symmetry_faces = 0;
  for (std::size_t face = 0; face < mesh.face_count(FaceType::triangle); ++face) {
    const Index* nodes = mesh.face(FaceType::triangle, face);
    const double part = tetrahedron_volume6(Vector3::Zero(), mesh.points[static_cast<std::size_t>(nodes[0])],
                                            mesh.points[static_cast<std::size_t>(nodes[1])],
                                            mesh.points[static_cast<std::size_t>(nodes[2])]);
    enclosed6 += mesh.faces(FaceType::triangle).markers[face] == wall ? -part : part;
    if (mesh.faces(FaceType::triangle).markers[face] == symmetry) {
      ++symmetry_faces;
      for (int corner = 0; corner < 3; ++corner)
        EXPECT_EQ(mesh.points[static_cast<std::size_t>(nodes[corner])].y(), 0.0);
    }
  }
  EXPECT_NEAR(volume, enclosed6 / 6.0, 1e-9 * volume);
  EXPECT_EQ(symmetry_faces > 0, symmetric);
}

}  // namespace

TEST(FarField, BoxOnTheSymmetryPlaneGivesAConformingHalfSphereMesh) {
  const FarFieldInput input = box_hull(3, -0.5, 0.0, true);
  const FarFieldResult result = farfield(input, small_options());
  EXPECT_DOUBLE_EQ(result.chord, 1.0);
  expect_sound_farfield(input, result, true);
  for (const Vector3& point : result.mesh.points) EXPECT_GE(point.y(), 0.0);
}

TEST(FarField, ClosedHullGetsAFullSphereOrABox) {
  const FarFieldInput input = box_hull(2, -0.5, 0.5, false);
  FarFieldOptions options = small_options();
  expect_sound_farfield(input, farfield(input, options), false);
  options.shape = FarFieldShape::box;
  const FarFieldResult boxed = farfield(input, options);
  expect_sound_farfield(input, boxed, false);
  double extreme = 0.0;
  for (const Vector3& point : boxed.mesh.points) extreme = std::max(extreme, point.cwiseAbs().maxCoeff());
  EXPECT_NEAR(extreme, 5.0 + 1.0, 1e-12);  // half-width 5 chords about the hull centre (0, 1, 0)
}

TEST(FarField, EveryPreconditioningMapsBackToTheSameBoundary) {
  const FarFieldInput input = box_hull(3, -0.5, 0.0, true);
  for (AffineMap affine : {AffineMap::none, AffineMap::whitening, AffineMap::inverse}) {
    FarFieldOptions options = small_options();
    options.precondition = true;
    options.preconditioning.sweep_degrees = 30.0;
    options.preconditioning.affine = affine;
    expect_sound_farfield(input, farfield(input, options), true);
  }
  FarFieldOptions plain = small_options();
  plain.precondition = false;
  expect_sound_farfield(input, farfield(input, plain), true);
}

TEST(FarField, DumpsTheBoundaryAfterEachTransform) {
  FarFieldOptions options = small_options();
  options.precondition = true;  // the sheared and preconditioned stages exist only then
  options.dump_directory = std::filesystem::path(::testing::TempDir()) / "farfield_dump";
  std::filesystem::create_directories(options.dump_directory);
  farfield(box_hull(2, -0.5, 0.0, true), options);
  for (const char* stage : {"boundary.vtk", "sheared.vtk", "preconditioned.vtk"})
    EXPECT_GT(std::filesystem::file_size(options.dump_directory / stage), 100u) << stage;
  std::filesystem::remove_all(options.dump_directory);
}

TEST(FarField, AnisotropicPointsFollowTheHullMetric) {
  const FarFieldInput input = hemisphere_hull(6, 24);
  FarFieldOptions options = small_options();
  const FarFieldResult isotropic = farfield(input, options);
  options.sizing = FarFieldSizing::anisotropic;
  const FarFieldResult anisotropic = farfield(input, options);
  expect_sound_farfield(input, isotropic, true);
  expect_sound_farfield(input, anisotropic, true);
  EXPECT_GT(anisotropic.layer_points, 0u);
  ASSERT_GT(anisotropic.hull_lengths.edges, 0u);
  // Isotropic tetrahedra on a hull whose cells are five times thinner than wide have
  // metric lengths far above 1 across the layer; the anisotropic ones mostly match.
  EXPECT_GT(anisotropic.hull_lengths.within_range, 0.75);
  EXPECT_LT(isotropic.hull_lengths.within_range, anisotropic.hull_lengths.within_range);
  EXPECT_GT(isotropic.hull_lengths.upper_decile, 2.0);
  EXPECT_LT(anisotropic.hull_lengths.median, 1.3);
  EXPECT_LT(anisotropic.hull_lengths.upper_decile, 0.5 * isotropic.hull_lengths.upper_decile);
}

// The first layer point stands first_layer_height of its normal spacing over its node.
// Lower than a whole spacing, the tetrahedra that reach a node a cell away across a
// diagonal come within the metric range.
TEST(FarField, LayerPointsStandAtTheirFirstHeight) {
  const FarFieldInput input = hemisphere_hull(6, 24);
  const double thickness = 0.2 * (0.5 * M_PI / 2 / 6);  // of hemisphere_hull's layer
  FarFieldOptions options = small_options();
  options.sizing = FarFieldSizing::anisotropic;
  std::map<double, FarFieldResult> results;
  std::map<double, double> median_height;
  for (double height : {1.0, 0.7}) {
    options.first_layer_height = height;
    const FarFieldResult& result = results[height] = farfield(input, options);
    expect_sound_farfield(input, result, true);
    // The new points within three layer thicknesses of the hemisphere: its layer points.
    std::vector<double> heights;
    for (std::size_t node = input.points.size(); node < result.mesh.points.size(); ++node)
      if (result.mesh.points[node].norm() < 0.5 + 3.0 * thickness)
        heights.push_back(result.mesh.points[node].norm() - 0.5);
    ASSERT_EQ(heights.size(), result.layer_points) << "first_layer_height " << height;
    ASSERT_GT(heights.size(), 0u);
    std::nth_element(heights.begin(), heights.begin() + heights.size() / 2, heights.end());
    median_height[height] = heights[heights.size() / 2];
  }
  EXPECT_NEAR(median_height[0.7] / median_height[1.0], 0.7, 0.02);
  EXPECT_GT(results[0.7].hull_lengths.within_range, results[1.0].hull_lengths.within_range);
  EXPECT_LT(results[0.7].hull_lengths.upper_decile, results[1.0].hull_lengths.upper_decile);
  for (double height : {0.0, 1.5}) {
    options.first_layer_height = height;
    EXPECT_THROW(farfield(input, options), Error) << height;
  }
}

TEST(FarField, SelfIntersectingHullIsReportedWithEveryCrossing) {
  FarFieldInput input = box_hull(2, -0.5, 0.5, false);
  const FarFieldInput second = box_hull(2, -0.2, 0.7, false);
  const Index offset = static_cast<Index>(input.points.size());
  input.points.insert(input.points.end(), second.points.begin(), second.points.end());
  for (auto triangle : second.hull)
    input.hull.push_back({triangle[0] + offset, triangle[1] + offset, triangle[2] + offset});
  try {
    farfield(input, small_options());
    FAIL() << "two overlapping boxes must be rejected";
  } catch (const HullIntersectionError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("farfield: the boundary intersects itself"), std::string::npos) << message;
    EXPECT_NE(message.find("near ("), std::string::npos) << message;
    // Every crossing triangle's centre comes with the error (generate stops the layers
    // round each): the boxes cross along a closed loop, so the centres spread round it.
    ASSERT_GE(error.locations.size(), 4u);
    EXPECT_EQ(error.locations.front(), error.location);
    double spread = 0.0;
    for (const Vector3& where : error.locations) spread = std::max(spread, (where - error.location).norm());
    EXPECT_GT(spread, 0.3);
  }
}

TEST(FarField, BadInputsAreRejected) {
  FarFieldInput lifted = box_hull(2, -0.5, 0.25, true);  // open, but 0.25 above the plane
  EXPECT_THROW(farfield(lifted, small_options()), Error);
  FarFieldInput out_of_range = box_hull(2, -0.5, 0.5, false);
  out_of_range.hull.front()[0] = 1000;
  EXPECT_THROW(farfield(out_of_range, small_options()), Error);
  FarFieldInput empty;
  EXPECT_THROW(farfield(empty, small_options()), Error);
  FarFieldInput without_metrics = box_hull(2, -0.5, 0.5, false);
  FarFieldOptions anisotropic = small_options();
  anisotropic.sizing = FarFieldSizing::anisotropic;
  EXPECT_THROW(farfield(without_metrics, anisotropic), Error);
}

// A radius too small for the hull (0.6 chords round a unit box) is raised to 2.2 times
// the hull's extent from its centre, instead of stopping the run.
TEST(FarField, BoundaryStandsAtLeastTwiceTheHullsExtentAway) {
  const FarFieldInput input = box_hull(2, -0.5, 0.5, false);
  FarFieldOptions tiny = small_options();
  tiny.radius_in_chords = 0.6;
  const FarFieldResult result = farfield(input, tiny);
  expect_sound_farfield(input, result, false);
  Vector3 low = input.points.front(), high = low;
  for (const Vector3& point : input.points) {
    low = low.cwiseMin(point);
    high = high.cwiseMax(point);
  }
  const Vector3 centre = 0.5 * (low + high);
  double extent = 0.0, farthest = 0.0;
  for (const Vector3& point : input.points) extent = std::max(extent, (point - centre).norm());
  for (const Vector3& point : result.mesh.points) farthest = std::max(farthest, (point - centre).norm());
  EXPECT_GT(farthest, 2.0 * extent);
  EXPECT_LT(farthest, 2.3 * extent);
}
