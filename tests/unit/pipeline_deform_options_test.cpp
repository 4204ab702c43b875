// Motion files, boundary conditions and sequences of the deformation framework.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "deform_meshes.hpp"
#include "mixmesh/config/config.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/deform/ara.hpp"
#include "mixmesh/pipeline/deform_options.hpp"

namespace mixmesh::deform {
namespace {

using testing::OGrid;

const Log quiet;

Motion parse(const std::string& text) {
  config::Document document = config::Document::parse(text, "motion.toml");
  config::Section root = document.root();
  return read_motion(root);
}

std::filesystem::path write_file(const std::string& name, const std::string& contents) {
  const auto path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path) << contents;
  return path;
}

TEST(DeformMotion, ReadsRigidAndFlutterBodies) {
  const Motion motion = parse(R"(
method = "ara"
steps = 4
symmetry = ["bottom"]
[[body]]
name = "wing"
markers = ["wall"]
centre = [0.25, 0, 0]
angle = 20
[[body]]
name = "flap"
markers = ["flap"]
motion = "pitch_plunge"
pitch_amplitude = 5
plunge_amplitude = 0.1
period_steps = 8
)");
  ASSERT_EQ(motion.bodies.size(), 2u);
  EXPECT_EQ(motion.steps, 4);
  EXPECT_FALSE(motion.incremental);
  EXPECT_EQ(motion.symmetry, std::vector<std::string>{"bottom"});
  EXPECT_EQ(motion.bodies[0].law, MotionLaw::rigid);
  EXPECT_EQ(motion.bodies[1].law, MotionLaw::pitch_plunge);
  // Step 2 of 4 of a 20° ramp is 10° about the quarter chord.
  const RigidPose pose = body_pose(motion.bodies[0], 2, 4);
  EXPECT_NEAR(pose.rotation_vector().z(), 10.0 * M_PI / 180.0, 1e-12);
  EXPECT_LT((pose.apply(Vector3(0.25, 0, 0)) - Vector3(0.25, 0, 0)).norm(), 1e-14);
  // Flutter: a quarter period is the pitch amplitude, a half period is back to zero.
  EXPECT_NEAR(body_pose(motion.bodies[1], 2, 4).rotation_vector().z(), 5.0 * M_PI / 180.0, 1e-12);
  EXPECT_NEAR(body_pose(motion.bodies[1], 2, 4).translation.y(), 0.1, 1e-12);
  EXPECT_NEAR(body_pose(motion.bodies[1], 4, 4).rotation_vector().norm(), 0.0, 1e-12);
}

TEST(DeformMotion, TrajectoriesAreIncrementalAndSetTheStepCount) {
  const auto csv = write_file("mixmesh_deform_trajectory.csv",
                              "tx,ty,tz,roll,pitch,yaw\n0,-0.1,0,0,0,2\n0,-0.2,0,0,0,4\n0,-0.3,0,0,0,6\n");
  const Motion motion =
      parse("[[body]]\nmarkers = [\"wall\"]\nmotion = \"trajectory\"\nfile = \"" + csv.string() + "\"\n");
  EXPECT_TRUE(motion.incremental);
  EXPECT_EQ(motion.steps, 3);
  EXPECT_NEAR(body_pose(motion.bodies[0], 3, 3).translation.y(), -0.3, 1e-15);
  std::filesystem::remove(csv);
}

TEST(DeformMotion, RejectsBadMotionFilesWithTheirPosition) {
  try {
    parse("[[body]]\nmarkers = [\"wall\"]\nmotion = \"wobble\"\n");
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("motion.toml:3"), std::string::npos) << error.what();
  }
  EXPECT_THROW(parse("steps = 2\n"), Error);                                         // no body
  EXPECT_THROW(parse("[[body]]\nangle = 3\n"), Error);                               // no markers
  EXPECT_THROW(parse("[[body]]\nmarkers = [\"wall\"]\naxis = [0, 0, 0]\n"), Error);  // zero axis
  EXPECT_THROW(parse("[[body]]\nmarkers = [\"wall\"]\ncentre = [1, 2]\n"), Error);   // two numbers
  EXPECT_THROW(parse("[[body]]\nmarkers = [\"wall\"]\nangel = 3\n"), Error);         // misspelt key
  EXPECT_THROW(parse("steps = 0\n[[body]]\nmarkers = [\"wall\"]\n"), Error);
  EXPECT_THROW(parse("[[body]]\nmarkers = [\"wall\"]\nmotion = \"mode\"\nfile = \"/nonexistent/mode.csv\"\n"),
               Error);
  const auto bad = write_file("mixmesh_deform_bad_mode.csv", "1,0,0,0\n2,0,zero,0\n");
  try {
    read_node_field(bad);
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find(":2:"), std::string::npos) << error.what();
  }
  std::filesystem::remove(bad);
}

DeformStep parse_step(const std::string& text) {
  config::Document document = config::Document::parse(text, "generate.toml");
  return read_deform_step(document.root().sections("deform").front());
}

TEST(DeformStep, ReadsAGenerationConfigStepAndMakesFreshMethods) {
  const DeformStep step = parse_step(
      "[[deform]]\nname = \"pitch\"\nmethod = \"idw\"\nsteps = 2\n"
      "[[deform.body]]\nmarkers = [\"wall\"]\nangle = 4\n"
      "[deform.idw]\nform = \"simple\"\n");
  EXPECT_EQ(step.name, "pitch");
  EXPECT_EQ(step.motion.steps, 2);
  ASSERT_EQ(step.motion.bodies.size(), 1u);
  EXPECT_EQ(step.motion.bodies[0].angle, 4.0);
  const auto first = step.make_method();
  const auto second = step.make_method();
  EXPECT_EQ(first->name(), "idw");
  EXPECT_NE(first.get(), second.get());
}

TEST(DeformStep, RejectsStepsWithoutANameOrWithUnknownKeys) {
  const std::string body = "[[deform.body]]\nmarkers = [\"wall\"]\n";
  EXPECT_THROW(parse_step("[[deform]]\n" + body), Error);                          // no name
  EXPECT_THROW(parse_step("[[deform]]\nname = \"a/b\"\n" + body), Error);          // a slash
  EXPECT_THROW(parse_step("[[deform]]\nname = \"a\"\nstep = 3\n" + body), Error);  // misspelt key
  try {
    parse_step("[[deform]]\nname = \"a\"\n" + body + "[deform.ara]\ntolerence = 1e-5\n");
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("generate.toml:6"), std::string::npos) << error.what();
  }
}

TEST(DeformBoundary, RolesOfMovingFixedAndSlidingNodes) {
  OGrid grid;
  grid.around = 16;
  grid.outward = 6;
  grid.layers_z = 2;
  const MixedMesh mesh = testing::volume_o_grid(grid, testing::VolumeKind::hexahedron);
  Motion motion;
  Body body;
  body.markers = {"wall"};
  body.translation = Vector3(0.1, 0.0, 0.0);
  motion.bodies = {body};
  motion.symmetry = {"bottom", "top"};
  const BoundaryMotion boundary = boundary_motion(mesh, mesh, motion, 1);
  EXPECT_EQ(boundary.marker_roles[static_cast<std::size_t>(mesh.find_marker("wall"))], MarkerRole::moving);
  EXPECT_EQ(boundary.marker_roles[static_cast<std::size_t>(mesh.find_marker("farfield"))], MarkerRole::fixed);
  EXPECT_EQ(boundary.marker_roles[static_cast<std::size_t>(mesh.find_marker("top"))], MarkerRole::sliding);
  for (std::size_t node = 0; node < mesh.points.size(); ++node) {
    const Vector3& point = mesh.points[node];
    const double r = std::hypot(point.x() / grid.semi_major, point.y() / grid.semi_minor);
    const bool on_wall = std::abs(r - 1.0) < 1e-9;
    const bool on_far = std::abs(point.head<2>().norm() - grid.outer_radius) < 1e-9;
    const bool on_plane = std::abs(point.z()) < 1e-12 || std::abs(point.z() - grid.height) < 1e-12;
    if (on_wall) {
      EXPECT_EQ(boundary.roles[node], NodeRole::prescribed);
      EXPECT_LT((boundary.displacement[node] - body.translation).norm(), 1e-15);
      EXPECT_EQ(boundary.body[node], 0);
    } else if (on_far) {
      EXPECT_EQ(boundary.roles[node], NodeRole::prescribed);
      EXPECT_EQ(boundary.displacement[node], Vector3::Zero());
    } else if (on_plane) {
      EXPECT_EQ(boundary.roles[node], NodeRole::sliding);
      EXPECT_NEAR(std::abs(boundary.slide_normal[node].z()), 1.0, 1e-12);
    } else {
      EXPECT_EQ(boundary.roles[node], NodeRole::interior);
    }
  }
  EXPECT_NEAR(boundary.largest_displacement(), 0.1, 1e-15);
}

TEST(DeformBoundary, RejectsUnknownMarkersConflictsAndCurvedSymmetry) {
  const MixedMesh mesh = testing::planar_o_grid(OGrid{});
  Body body;
  body.name = "wing";
  body.markers = {"flap"};
  Motion motion;
  motion.bodies = {body};
  try {
    boundary_motion(mesh, mesh, motion, 1);
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("'flap'"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("wall, farfield"), std::string::npos) << error.what();
  }
  // Two bodies moving the same node differently.
  Body first;
  first.name = "first";
  first.markers = {"wall"};
  first.translation = Vector3(1, 0, 0);
  Body second = first;
  second.name = "second";
  second.translation = Vector3(0, 1, 0);
  motion.bodies = {first, second};
  EXPECT_THROW(boundary_motion(mesh, mesh, motion, 1), Error);
  // The curved wall cannot be a symmetry plane.
  motion.bodies = {};
  motion.symmetry = {"wall"};
  EXPECT_THROW(boundary_motion(mesh, mesh, motion, 1), Error);
  // A mode row naming a node that is not on the body.
  Body mode;
  mode.name = "mode";
  mode.markers = {"wall"};
  mode.law = MotionLaw::mode;
  mode.field.nodes = {static_cast<Index>(mesh.points.size() - 1)};  // a far-field node
  mode.field.values = {Vector3(0, 0.1, 0)};
  motion.symmetry = {};
  motion.bodies = {mode};
  EXPECT_THROW(boundary_motion(mesh, mesh, motion, 1), Error);
  // A mode row by position that matches no node.
  mode.field.nodes.clear();
  mode.field.positions = {Vector3(0.3, 0.3, 0.0)};
  motion.bodies = {mode};
  EXPECT_THROW(boundary_motion(mesh, mesh, motion, 1), Error);
}

TEST(DeformBoundary, ModeShapeByIndexAndByPositionAgree) {
  const OGrid grid;
  const MixedMesh mesh = testing::planar_o_grid(grid);
  Body by_index;
  by_index.markers = {"wall"};
  by_index.law = MotionLaw::mode;
  by_index.scale = 2.0;
  Body by_position = by_index;
  for (int i = 0; i < grid.around; ++i) {
    const Vector3& point = mesh.points[static_cast<std::size_t>(i)];
    const Vector3 bend(0.0, 0.05 * point.x() * point.x(), 0.0);
    by_index.field.nodes.push_back(i);
    by_index.field.values.push_back(bend);
    by_position.field.positions.push_back(point);
    by_position.field.values.push_back(bend);
  }
  Motion motion;
  motion.steps = 2;
  motion.bodies = {by_index};
  const BoundaryMotion first = boundary_motion(mesh, mesh, motion, 1);
  motion.bodies = {by_position};
  const BoundaryMotion second = boundary_motion(mesh, mesh, motion, 1);
  for (int i = 0; i < grid.around; ++i) {
    const std::size_t node = static_cast<std::size_t>(i);
    // Step 1 of 2 applies half of scale × field.
    EXPECT_NEAR(first.displacement[node].y(), 0.05 * mesh.points[node].x() * mesh.points[node].x(), 1e-15);
    EXPECT_EQ(first.displacement[node], second.displacement[node]);
    EXPECT_EQ(first.rotation[node], second.rotation[node]);
  }
  // The fitted rotation of the bent surface follows the slope d(0.05 x²)/dx = 0.1 x at
  // the ends of the body, where the surface is normal to x.
  EXPECT_GT(first.rotation[0].z(), 0.0);
}

TEST(DeformBoundary, RotationByDirectionFollowsTheSlopeWhereAStarIsThin) {
  // A wall strip like the faces at a closed trailing edge: rows 1.4 mm apart across the
  // edge, 0.1 m apart along it, bent along the edge (z = c y², no slope across it). A
  // node on the edge row sees its neighbours along the edge 0.1 m away and the row ahead
  // 1.4 mm away. The bending is no rigid motion (c · 0.01 m = 0.5 mm off over 0.1 m), and
  // the plain fit turns the edge node about the edge (y) to explain that on its
  // diagonal neighbours, 1.4 mm ahead of it; weighted by direction it keeps to the slope.
  const std::vector<double> xs{-0.0028, -0.0014, 0.0};
  const std::vector<double> ys{0.0, 0.1, 0.2, 0.3};
  MixedMesh mesh;
  for (double y : ys)
    for (double x : xs) mesh.points.emplace_back(x, y, 0.0);
  auto at = [&](std::size_t i, std::size_t j) { return static_cast<Index>(j * xs.size() + i); };
  const int wall = mesh.marker("wall");
  for (std::size_t j = 0; j + 1 < ys.size(); ++j)
    for (std::size_t i = 0; i + 1 < xs.size(); ++i) {
      const Index quad[4]{at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)};
      mesh.add_face(FaceType::quad, quad, wall);
    }
  const double c = 0.05;
  Body bend;
  bend.markers = {"wall"};
  bend.law = MotionLaw::mode;
  for (std::size_t node = 0; node < mesh.points.size(); ++node) {
    bend.field.nodes.push_back(static_cast<Index>(node));
    const double y = mesh.points[node].y();
    bend.field.values.push_back(Vector3(0.0, 0.0, c * y * y));
  }
  Motion motion;
  motion.bodies = {bend};
  const BoundaryMotion boundary = boundary_motion(mesh, mesh, motion, 1);
  ASSERT_EQ(boundary.rotation.size(), mesh.points.size());
  const auto edge = static_cast<std::size_t>(at(2, 1));  // on the edge row, y = 0.1
  const double slope = std::atan(2.0 * c * 0.1);         // about x
  EXPECT_NEAR(boundary.rotation[edge].x(), slope, 0.1 * slope);
  EXPECT_LT(std::abs(boundary.rotation[edge].y()), 0.05 * slope);
}

TEST(DeformSequence, IncrementalStepsDeformThePreviousMesh) {
  const MixedMesh mesh = testing::planar_o_grid(OGrid{});
  Body body;
  body.markers = {"wall"};
  body.law = MotionLaw::trajectory;
  for (int step = 1; step <= 3; ++step) {
    RigidPose pose;
    pose.rotation = axis_rotation(Vector3::UnitZ(), 4.0 * step);
    pose.translation = Vector3(0.0, -0.05 * step, 0.0);
    body.poses.push_back(pose);
  }
  Motion motion;
  motion.bodies = {body};
  motion.steps = 3;
  motion.incremental = true;
  AraMethod method;
  std::vector<MixedMesh> meshes;
  deform_sequence(mesh, motion, method, quiet, {}, [&](int step, const DeformResult& result) {
    EXPECT_TRUE(result.valid) << "step " << step;
    meshes.push_back(result.mesh);
  });
  ASSERT_EQ(meshes.size(), 3u);
  // The wall follows the absolute pose of each step, however the steps were chained.
  for (std::size_t step = 0; step < 3; ++step)
    for (std::size_t node = 0; node < 48; ++node)
      EXPECT_LT((meshes[step].points[node] - body.poses[step].apply(mesh.points[node])).norm(), 1e-12);
  // Steps after the first reuse the nearest faces found in the first.
  EXPECT_TRUE(method.last_report().cache_used);
}

TEST(DeformSequence, FailsWithTheCountAndLocationOfInvertedCells) {
  // Translating the body through the far field folds the mesh beyond repair.
  const MixedMesh mesh = testing::planar_o_grid(OGrid{});
  Body body;
  body.markers = {"wall"};
  body.translation = Vector3(12.0, 0.0, 0.0);
  Motion motion;
  motion.bodies = {body};
  AraMethod method;
  int calls = 0;
  try {
    deform_sequence(mesh, motion, method, quiet, {}, [&](int, const DeformResult&) { ++calls; });
    FAIL() << "no error";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("cells stay inverted"), std::string::npos) << message;
    EXPECT_NE(message.find(" at ("), std::string::npos) << message;
  }
  EXPECT_EQ(calls, 0);
  DeformOptions keep;
  keep.keep_invalid = true;
  deform_sequence(mesh, motion, method, quiet, keep, [&](int, const DeformResult& result) {
    ++calls;
    EXPECT_FALSE(result.valid);
    EXPECT_GT(result.invalid_count, 0u);
  });
  EXPECT_EQ(calls, 1);
}

}  // namespace
}  // namespace mixmesh::deform
