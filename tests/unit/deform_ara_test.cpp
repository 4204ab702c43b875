// The ARA method on planar and volume O-grids around an ellipse.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "deform_meshes.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/deform/ara.hpp"

namespace mixmesh::deform {
namespace {

using testing::OGrid;
using testing::VolumeKind;

Motion rotate_wall(double angle, const Vector3& centre = Vector3::Zero()) {
  Body body;
  body.name = "body";
  body.markers = {"wall"};
  body.law = MotionLaw::rigid;
  body.centre = centre;
  body.axis = Vector3::UnitZ();
  body.angle = angle;
  Motion motion;
  motion.bodies = {body};
  return motion;
}

const Log quiet;

TEST(DeformBlend, ReconstructedEquationElevenKeepsItsStatedProperties) {
  for (double gamma : {2.0, 4.0, 8.0}) {
    EXPECT_NEAR(blend(1.0, gamma, BlendForm::exponential), 1.0, 1e-14);
    EXPECT_NEAR(blend(0.5, gamma, BlendForm::exponential), 0.5, 1e-14);
    double previous = 0.0;
    for (double alpha = 0.5; alpha <= 1.0; alpha += 0.01) {
      const double value = blend(alpha, gamma, BlendForm::exponential);
      EXPECT_GE(value, previous);
      EXPECT_GE(value, alpha - 1e-12);  // the near field follows its boundary at least as closely as β = α
      previous = value;
    }
  }
  // A larger γ widens the region that moves with its boundary.
  EXPECT_LT(blend(0.7, 2.0, BlendForm::exponential), blend(0.7, 4.0, BlendForm::exponential));
  EXPECT_LT(blend(0.7, 4.0, BlendForm::exponential), blend(0.7, 8.0, BlendForm::exponential));
  EXPECT_DOUBLE_EQ(blend(0.7, 4.0, BlendForm::linear), 0.7);
  EXPECT_DOUBLE_EQ(blend(0.2, 4.0, BlendForm::linear), 0.5);  // α outside [0.5, 1] is clamped
}

TEST(DeformAra, PlanarRotationKeepsTheMeshValidAndTheFarFieldFixed) {
  OGrid grid;
  const MixedMesh mesh = testing::planar_o_grid(grid);
  AraMethod method;
  const Motion motion = rotate_wall(20.0);
  const DeformResult result = deform_step(mesh, mesh, motion, 1, method, quiet);
  EXPECT_TRUE(result.valid);
  EXPECT_EQ(result.invalid_count, 0u);
  const Eigen::Matrix3d rotation = axis_rotation(Vector3::UnitZ(), 20.0);
  const int around = grid.around;
  for (int i = 0; i < around; ++i) {
    const std::size_t wall = static_cast<std::size_t>(i);
    const std::size_t far = static_cast<std::size_t>((grid.outward - 1) * around + i);
    const std::size_t first_layer = static_cast<std::size_t>(around + i);
    EXPECT_LT((result.mesh.points[wall] - rotation * mesh.points[wall]).norm(), 1e-12);
    EXPECT_LT((result.mesh.points[far] - mesh.points[far]).norm(), 1e-12);
    // The first layer above the wall moves with the body almost rigidly.
    const Vector3 rigid = rotation * mesh.points[first_layer];
    EXPECT_LT((result.mesh.points[first_layer] - rigid).norm(),
              0.02 * (rigid - mesh.points[first_layer]).norm() + 1e-6)
        << "node " << first_layer;
  }
  EXPECT_FALSE(method.last_report().cache_used);
  EXPECT_GT(method.last_report().smoothing_iterations, 0);
}

TEST(DeformAra, RotationTermsKeepWallLinesOrthogonalWhereTranslationOnlySkewsThem) {
  // Rotation about a point off the body's centre (the ellipse's "quarter chord").
  OGrid grid;
  grid.around = 64;
  grid.outward = 24;
  grid.first_spacing = 0.002;
  grid.quad_layers = 12;
  const MixedMesh mesh = testing::planar_o_grid(grid);
  const Motion motion = rotate_wall(20.0, Vector3(-0.5, 0.0, 0.0));
  AraMethod with_rotation;
  AraOptions translation_options;
  translation_options.predictor = Predictor::translation;
  AraMethod translation_only(translation_options);
  const DeformResult rotated = deform_step(mesh, mesh, motion, 1, with_rotation, quiet);
  const DeformResult translated = deform_step(mesh, mesh, motion, 1, translation_only, quiet);
  EXPECT_TRUE(rotated.valid);
  EXPECT_LT(rotated.max_wall_angle_change, 2.0);
  EXPECT_GT(translated.max_wall_angle_change, 10.0 * rotated.max_wall_angle_change);
  // Plain eq. 19 smoothing relaxes the near-wall rotation away.
  AraOptions plain_options;
  plain_options.smoothing = Smoothing::plain;
  AraMethod plain(plain_options);
  const DeformResult plain_result = deform_step(mesh, mesh, motion, 1, plain, quiet);
  EXPECT_GT(plain_result.max_wall_angle_change, rotated.max_wall_angle_change);
}

// A quasi-2D viscous mesh, one cell thick between two sliding planes (hexahedra in
// the layers, prisms outside, first spacing 1e-5 of the chord), deforms as its planar
// section does. Before, every node's interpolation weights were noise: the centres of a
// one-cell-thick mesh's cells all lie half a cell from either plane, so the pseudo-
// Laplacian's λ along z cancelled every weight up to rounding; the two planes then moved
// apart by up to 0.37 chords and the smallest scaled Jacobian at 20° was 0.088 against
// the planar mesh's 0.452. And no wall line was found, since every node lies on a plane.
TEST(DeformAra, OneCellThickMeshDeformsAsItsPlanarSection) {
  OGrid grid;
  grid.around = 64;
  grid.outward = 28;
  grid.first_spacing = 2e-5;  // the ellipse's chord is 2
  grid.quad_layers = 16;
  grid.layers_z = 1;
  grid.height = 0.05;
  const MixedMesh planar = testing::planar_o_grid(grid);
  const MixedMesh slab = testing::volume_o_grid(grid, VolumeKind::hex_and_prism);
  for (double angle : {20.0, 90.0}) {
    Motion motion = rotate_wall(angle, Vector3(-0.5, 0.0, 0.0));
    AraMethod planar_method;
    const DeformResult section = deform_step(planar, planar, motion, 1, planar_method, quiet);
    motion.symmetry = {"bottom", "top"};
    AraMethod slab_method;
    const DeformResult deformed = deform_step(slab, slab, motion, 1, slab_method, quiet);
    ASSERT_TRUE(section.valid) << angle;
    ASSERT_TRUE(deformed.valid) << angle;
    // Both planes move alike, and as the section does up to the smoothing's tolerance
    // beyond the reach of the slab's layer stacks (their height plus a wall face size):
    // the slab's stacks move rigidly with the wall and what the method had at their tops
    // is carried outward from there (layer_lines.hpp); the section has no stacks.
    const std::size_t count = planar.points.size();
    const std::size_t around = static_cast<std::size_t>(grid.around);
    auto wall_distance = [&](const Vector3& point) {
      double nearest = std::numeric_limits<double>::infinity();
      for (std::size_t wall = 0; wall < around; ++wall)
        nearest = std::min(nearest, (point - planar.points[wall]).norm());
      return nearest;
    };
    double face = 0.0, height = 0.0;
    for (std::size_t wall = 0; wall < around; ++wall) {
      face = std::max(
          face, std::hypot((planar.points[(wall + 1) % around] - planar.points[wall]).norm(), grid.height));
      height = std::max(
          height, wall_distance(planar.points[static_cast<std::size_t>(grid.quad_layers) * around + wall]));
    }
    std::size_t compared = 0;
    double between_planes = 0.0, from_section = 0.0;
    for (std::size_t node = 0; node < count; ++node) {
      const Vector3& bottom = deformed.mesh.points[node];
      const Vector3& top = deformed.mesh.points[count + node];
      between_planes = std::max(between_planes, (bottom.head<2>() - top.head<2>()).norm());
      if (wall_distance(planar.points[node]) <= height + face) continue;
      ++compared;
      from_section = std::max(from_section, (bottom.head<2>() - section.mesh.points[node].head<2>()).norm());
      EXPECT_DOUBLE_EQ(bottom.z(), slab.points[node].z());
      EXPECT_DOUBLE_EQ(top.z(), slab.points[count + node].z());
    }
    EXPECT_LT(between_planes, 1e-9) << angle;
    EXPECT_GT(compared, count / 4) << angle;  // the outer nine of 28 rings
    EXPECT_LT(from_section, 1e-3) << angle;
    EXPECT_GT(deformed.after.min_scaled_jacobian, 0.98 * section.after.min_scaled_jacobian) << angle;
    // Wall lines are found on both planes (their angles as in the section) and stay at
    // the wall normal as the section's do.
    EXPECT_NEAR(deformed.before.max_wall_angle, section.before.max_wall_angle, 1e-9) << angle;
    MixedMesh named = slab;
    std::vector<MarkerRole> roles(4, MarkerRole::fixed);
    roles.at(static_cast<std::size_t>(named.marker("wall"))) = MarkerRole::moving;
    roles.at(static_cast<std::size_t>(named.marker("bottom"))) = MarkerRole::sliding;
    roles.at(static_cast<std::size_t>(named.marker("top"))) = MarkerRole::sliding;
    const WallLines lines = wall_lines(slab, roles);
    // Every wall and far-field node of both planes has its line.
    EXPECT_EQ(lines.wall_nodes.size(), static_cast<std::size_t>(4 * grid.around));
    EXPECT_EQ(
        std::count_if(lines.line_ends.begin(), lines.line_ends.end(), [](Index end) { return end >= 0; }),
        4 * grid.around);
    EXPECT_LT(deformed.max_wall_angle_change, 2.0) << angle;
    EXPECT_GT(section.max_wall_angle_change, 0.0);
  }
}

TEST(DeformAra, UniformTranslationOfEveryBoundaryTranslatesTheWholeMesh) {
  const MixedMesh mesh = testing::planar_o_grid(OGrid{});
  Body body;
  body.markers = {"wall", "farfield"};
  body.translation = Vector3(0.3, -0.2, 0.0);
  Motion motion;
  motion.bodies = {body};
  AraMethod method;
  const DeformResult result = deform_step(mesh, mesh, motion, 1, method, quiet);
  for (std::size_t node = 0; node < mesh.points.size(); ++node)
    EXPECT_LT((result.mesh.points[node] - mesh.points[node] - body.translation).norm(), 1e-12);
}

TEST(DeformAra, NoMotionMovesNothing) {
  const MixedMesh mesh = testing::planar_o_grid(OGrid{});
  AraMethod method;
  const DeformResult result = deform_step(mesh, mesh, rotate_wall(0.0), 1, method, quiet);
  for (std::size_t node = 0; node < mesh.points.size(); ++node)
    EXPECT_LT((result.mesh.points[node] - mesh.points[node]).norm(), 1e-12);
}

TEST(DeformAra, CachedNearestFacesGiveTheSameMesh) {
  const MixedMesh mesh = testing::planar_o_grid(OGrid{});
  AraMethod method;
  const Motion motion = rotate_wall(10.0);
  const DeformResult first = deform_step(mesh, mesh, motion, 1, method, quiet);
  EXPECT_FALSE(method.last_report().cache_used);
  const NearestFaces nearest = method.nearest_faces();
  EXPECT_EQ(nearest.faces.size(), nearest.cell_count);
  const DeformResult second = deform_step(mesh, mesh, motion, 1, method, quiet);
  EXPECT_TRUE(method.last_report().cache_used);
  for (std::size_t node = 0; node < mesh.points.size(); ++node)
    EXPECT_EQ(first.mesh.points[node], second.mesh.points[node]);

  // Through a file, and a second method object.
  const auto file = std::filesystem::temp_directory_path() / "mixmesh_deform_cache_test.bin";
  std::filesystem::remove(file);
  AraOptions options;
  options.cache_file = file;
  AraMethod writer(options);
  deform_step(mesh, mesh, motion, 1, writer, quiet);
  EXPECT_FALSE(writer.last_report().cache_used);
  ASSERT_TRUE(std::filesystem::exists(file));
  const NearestFaces stored = read_nearest_faces(file);
  EXPECT_EQ(stored.faces, nearest.faces);
  AraMethod reader(options);
  const DeformResult third = deform_step(mesh, mesh, motion, 1, reader, quiet);
  EXPECT_TRUE(reader.last_report().cache_used);
  for (std::size_t node = 0; node < mesh.points.size(); ++node)
    EXPECT_EQ(first.mesh.points[node], third.mesh.points[node]);
  std::filesystem::remove(file);
}

TEST(DeformAra, CacheFileKeepsTheGeometryOfTheSamePointsOnly) {
  const MixedMesh mesh = testing::volume_o_grid(OGrid{}, testing::VolumeKind::hexahedron);
  const BoundaryMotion boundary = boundary_motion(mesh, mesh, rotate_wall(10.0), 1);
  const auto file = std::filesystem::temp_directory_path() / "mixmesh_deform_geometry_cache.bin";
  std::filesystem::remove(file);
  AraOptions options;
  options.cache_file = file;
  AraMethod writer(options);
  const std::vector<Vector3> first = writer.move(mesh, boundary, quiet);
  EXPECT_FALSE(writer.last_report().geometry_from_file);

  AraMethod reader(options);
  EXPECT_EQ(reader.move(mesh, boundary, quiet), first);
  EXPECT_TRUE(reader.last_report().geometry_from_file);
  EXPECT_TRUE(reader.last_report().cache_used);

  // Without the geometry: a file of nearest faces only, much smaller, the same mesh.
  const auto small_file = std::filesystem::temp_directory_path() / "mixmesh_deform_faces_only.bin";
  std::filesystem::remove(small_file);
  AraOptions faces_only = options;
  faces_only.cache_file = small_file;
  faces_only.cache_geometry = false;
  AraMethod small_writer(faces_only);
  small_writer.move(mesh, boundary, quiet);
  EXPECT_LT(std::filesystem::file_size(small_file) * 10, std::filesystem::file_size(file));
  AraMethod small_reader(faces_only);
  EXPECT_EQ(small_reader.move(mesh, boundary, quiet), first);
  EXPECT_TRUE(small_reader.last_report().cache_used);
  EXPECT_FALSE(small_reader.last_report().geometry_from_file);
  // Read with the geometry wanted, a faces-only file gains it for the run after.
  AraOptions faces_file = options;
  faces_file.cache_file = small_file;
  AraMethod upgrader(faces_file);
  EXPECT_EQ(upgrader.move(mesh, boundary, quiet), first);
  EXPECT_TRUE(upgrader.last_report().cache_used);
  EXPECT_FALSE(upgrader.last_report().geometry_from_file);
  EXPECT_EQ(std::filesystem::file_size(small_file), std::filesystem::file_size(file));
  AraMethod upgraded_reader(faces_file);
  EXPECT_EQ(upgraded_reader.move(mesh, boundary, quiet), first);
  EXPECT_TRUE(upgraded_reader.last_report().geometry_from_file);
  // A geometry block of a format this mixmesh does not know is neither used nor
  // overwritten.
  std::filesystem::remove(small_file);
  AraMethod{faces_only}.move(mesh, boundary, quiet);
  { std::ofstream(small_file, std::ios::binary | std::ios::app) << "MXARAGE9 a later layout"; }
  const auto unknown_size = std::filesystem::file_size(small_file);
  AraMethod unknown_reader(faces_file);
  EXPECT_EQ(unknown_reader.move(mesh, boundary, quiet), first);
  EXPECT_FALSE(unknown_reader.last_report().geometry_from_file);
  EXPECT_EQ(std::filesystem::file_size(small_file), unknown_size);
  std::filesystem::remove(small_file);

  // Moved points: the nearest faces still serve, the geometry is rebuilt.
  MixedMesh moved = mesh;
  for (Vector3& point : moved.points) point *= 1.001;
  AraMethod mover(options);
  mover.move(moved, boundary_motion(moved, moved, rotate_wall(10.0), 1), quiet);
  EXPECT_FALSE(mover.last_report().geometry_from_file);
  EXPECT_TRUE(mover.last_report().cache_used);

  // A damaged or truncated geometry block is refused with one line, not half used.
  const auto size = std::filesystem::file_size(file);
  {
    std::fstream stream(file, std::ios::binary | std::ios::in | std::ios::out);
    stream.seekp(static_cast<std::streamoff>(size - 64));
    stream.put('\x5a');
  }
  for (int damage = 0; damage < 2; ++damage) {
    if (damage == 1) std::filesystem::resize_file(file, size - 1000);
    AraMethod victim(options);
    try {
      victim.move(mesh, boundary, quiet);
      ADD_FAILURE() << "a damaged cache was accepted";
    } catch (const Error& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find("damaged"), std::string::npos) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
  }
  std::filesystem::remove(file);
}

TEST(DeformAra, NearestFacesLieOnTheTwoBoundaries) {
  const OGrid grid;
  const MixedMesh mesh = testing::planar_o_grid(grid);
  AraMethod method;
  deform_step(mesh, mesh, rotate_wall(5.0), 1, method, quiet);
  // Wall faces come first in the edge list order (wall, farfield alternate); the first
  // nearest face of a cell next to the wall is a wall edge, the second a far-field one.
  const NearestFaces& nearest = method.nearest_faces();
  ASSERT_EQ(nearest.wall_face_count, static_cast<std::size_t>(2 * grid.around));
  for (int i = 0; i < grid.around; ++i) {
    const auto& faces = nearest.faces[static_cast<std::size_t>(i)];  // quads of the first ring
    EXPECT_EQ(mesh.boundary_edges.markers[static_cast<std::size_t>(faces[0])], mesh.find_marker("wall"));
    EXPECT_EQ(mesh.boundary_edges.markers[static_cast<std::size_t>(faces[1])], mesh.find_marker("farfield"));
  }
}

TEST(DeformAra, CacheFileRejectsOtherFiles) {
  const auto file = std::filesystem::temp_directory_path() / "mixmesh_deform_not_a_cache.bin";
  {
    std::ofstream stream(file);
    stream << "not a cache";
  }
  EXPECT_THROW(read_nearest_faces(file), Error);
  std::filesystem::remove(file);
  EXPECT_THROW(read_nearest_faces(file), Error);
}

TEST(DeformAra, OlderAndForeignCacheFilesAreRejectedWithOneLine) {
  const auto file = std::filesystem::temp_directory_path() / "mixmesh_deform_foreign_cache.bin";
  std::filesystem::remove(file);
  AraOptions options;
  options.cache_file = file;
  OGrid grid;
  const MixedMesh mesh = testing::planar_o_grid(grid);
  AraMethod writer(options);
  writer.move(mesh, boundary_motion(mesh, mesh, rotate_wall(5.0), 1), quiet);
  ASSERT_TRUE(std::filesystem::exists(file));
  EXPECT_EQ(read_nearest_faces(file).point_count, mesh.points.size());

  // Another mesh with the same file: an error naming the file, nothing overwritten.
  grid.around = 40;
  const MixedMesh other = testing::planar_o_grid(grid);
  AraMethod reader(options);
  try {
    reader.move(other, boundary_motion(other, other, rotate_wall(5.0), 1), quiet);
    ADD_FAILURE() << "a cache made for another mesh was accepted";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(file.string()), std::string::npos) << message;
    EXPECT_NE(message.find("another mesh"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  EXPECT_EQ(read_nearest_faces(file).point_count, mesh.points.size());

  // The same connectivity with other wall markers (the far field slides): other wall faces.
  BoundaryMotion sliding_far_field = boundary_motion(mesh, mesh, rotate_wall(5.0), 1);
  sliding_far_field.marker_roles[static_cast<std::size_t>(mesh.find_marker("farfield"))] =
      MarkerRole::sliding;
  AraMethod third(options);
  EXPECT_THROW(third.move(mesh, sliding_far_field, quiet), Error);

  // A cache file of the first format (no mesh hash).
  {
    std::ofstream stream(file, std::ios::binary);
    stream << "MXARANF1" << std::string(16, '\0');
  }
  EXPECT_THROW(read_nearest_faces(file), Error);
  std::filesystem::remove(file);
}

TEST(DeformAra, GeometryIsKeptForTheSameMeshAndRebuiltForMovedPoints) {
  const MixedMesh mesh = testing::planar_o_grid(OGrid{});
  AraMethod method;
  const Motion motion = rotate_wall(10.0);
  const DeformResult first = deform_step(mesh, mesh, motion, 1, method, quiet);
  EXPECT_FALSE(method.last_report().geometry_cached);
  deform_step(mesh, mesh, motion, 1, method, quiet);
  EXPECT_TRUE(method.last_report().geometry_cached);
  // A deformed mesh has the same connectivity: the nearest faces carry over, the
  // geometry (centres, σ, interpolation weights) is rebuilt.
  const DeformResult moved = deform_step(first.mesh, mesh, rotate_wall(5.0), 1, method, quiet);
  EXPECT_FALSE(method.last_report().geometry_cached);
  EXPECT_TRUE(method.last_report().cache_used);
  EXPECT_TRUE(moved.valid);
  method.clear_cache();
  deform_step(mesh, mesh, motion, 1, method, quiet);
  EXPECT_FALSE(method.last_report().geometry_cached);
  EXPECT_FALSE(method.last_report().cache_used);
}

// Both solvers of the smoothing system, run to a tight tolerance, give the same mesh;
// conjugate gradients in far fewer iterations.
void expect_solvers_agree(const MixedMesh& mesh, const Motion& motion, Smoothing smoothing) {
  AraOptions options;
  options.smoothing = smoothing;
  options.tolerance = 1e-11;
  options.max_iterations = 100000;
  options.solver = Solver::gauss_seidel;
  AraMethod seidel(options);
  const std::vector<Vector3> by_seidel = seidel.move(mesh, boundary_motion(mesh, mesh, motion, 1), quiet);
  options.solver = Solver::conjugate_gradient;
  AraMethod gradients(options);
  const std::vector<Vector3> by_gradients =
      gradients.move(mesh, boundary_motion(mesh, mesh, motion, 1), quiet);
  ASSERT_EQ(by_seidel.size(), by_gradients.size());
  double largest = 0.0;
  double difference = 0.0;
  for (std::size_t node = 0; node < mesh.points.size(); ++node) {
    largest = std::max(largest, (by_seidel[node] - mesh.points[node]).norm());
    difference = std::max(difference, (by_seidel[node] - by_gradients[node]).norm());
  }
  EXPECT_GT(largest, 0.01);
  EXPECT_LT(difference, 1e-7 * largest);
  EXPECT_LE(seidel.last_report().smoothing_residual, 1e-11);
  EXPECT_LE(gradients.last_report().smoothing_residual, 1e-11);
  EXPECT_LT(gradients.last_report().smoothing_iterations, seidel.last_report().smoothing_iterations);
}

TEST(DeformAra, GaussSeidelAndConjugateGradientsConvergeToTheSameMesh) {
  expect_solvers_agree(testing::planar_o_grid(OGrid{}), rotate_wall(15.0), Smoothing::rigid_transport);
  expect_solvers_agree(testing::planar_o_grid(OGrid{}), rotate_wall(15.0), Smoothing::plain);
  OGrid grid;
  grid.around = 24;
  grid.outward = 10;
  grid.first_spacing = 0.02;
  grid.layers_z = 2;
  Motion motion = rotate_wall(10.0);
  motion.symmetry = {"bottom", "top"};
  expect_solvers_agree(testing::volume_o_grid(grid, VolumeKind::hex_and_prism), motion,
                       Smoothing::rigid_transport);
}

class DeformAraVolume : public ::testing::TestWithParam<VolumeKind> {};

TEST_P(DeformAraVolume, RotationWithSymmetryPlanesStaysValid) {
  OGrid grid;
  grid.around = 24;
  grid.outward = 10;
  grid.first_spacing = 0.02;
  grid.quad_layers = 4;
  grid.layers_z = 2;
  const MixedMesh mesh = testing::volume_o_grid(grid, GetParam());
  Motion motion = rotate_wall(15.0);
  motion.symmetry = {"bottom", "top"};
  AraMethod method;
  const DeformResult result = deform_step(mesh, mesh, motion, 1, method, quiet);
  EXPECT_TRUE(result.valid) << result.invalid_count << " invalid cells";
  EXPECT_GT(result.after.min_scaled_jacobian, 0.0);
  const Eigen::Matrix3d rotation = axis_rotation(Vector3::UnitZ(), 15.0);
  bool some_sliding_node_moved = false;
  for (std::size_t node = 0; node < mesh.points.size(); ++node) {
    const Vector3& before = mesh.points[node];
    const Vector3& after = result.mesh.points[node];
    const bool on_end_plane = std::abs(before.z()) < 1e-12 || std::abs(before.z() - grid.height) < 1e-12;
    if (on_end_plane) {
      EXPECT_NEAR(after.z(), before.z(), 1e-12);  // slides in its plane
    }
    const double radius = (before.x() / grid.semi_major) * (before.x() / grid.semi_major) +
                          (before.y() / grid.semi_minor) * (before.y() / grid.semi_minor);
    if (std::abs(radius - 1.0) < 1e-9) {
      EXPECT_LT((after - rotation * before).norm(), 1e-12);
    }
    if (on_end_plane && std::abs(radius - 1.0) > 1e-6 && before.head<2>().norm() < 0.9 * grid.outer_radius &&
        (after - before).norm() > 1e-4)
      some_sliding_node_moved = true;
  }
  EXPECT_TRUE(some_sliding_node_moved);
}

INSTANTIATE_TEST_SUITE_P(CellTypes, DeformAraVolume,
                         ::testing::Values(VolumeKind::hexahedron, VolumeKind::prism, VolumeKind::tetrahedron,
                                           VolumeKind::pyramid, VolumeKind::hex_and_prism));

TEST(DeformAra, RejectsMotionSizedForAnotherMesh) {
  const MixedMesh mesh = testing::planar_o_grid(OGrid{});
  BoundaryMotion boundary = boundary_motion(mesh, mesh, rotate_wall(5.0), 1);
  boundary.roles.pop_back();
  AraMethod method;
  EXPECT_THROW(method.move(mesh, boundary, quiet), Error);
}

TEST(DeformAra, RejectsAMeshWithoutWalls) {
  const MixedMesh mesh = testing::planar_o_grid(OGrid{});
  BoundaryMotion boundary = boundary_motion(mesh, mesh, rotate_wall(5.0), 1);
  for (auto& role : boundary.marker_roles) role = MarkerRole::sliding;
  AraMethod method;
  EXPECT_THROW(method.move(mesh, boundary, quiet), Error);
}

}  // namespace
}  // namespace mixmesh::deform
