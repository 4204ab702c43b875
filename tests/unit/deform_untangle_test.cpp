// Untangling after the layer transport (src/deform/untangle.hpp): the free nodes of
// inverted cells go where the affine map of their neighbours' motion takes them.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "mixmesh/deform/deform.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"

namespace mixmesh::deform {
namespace {

constexpr int cells_per_side = 4;

Index grid_node(int i, int j, int k) {
  return static_cast<Index>((k * (cells_per_side + 1) + j) * (cells_per_side + 1) + i);
}

// A block of 4 × 4 × 4 hexahedra on [0, 1]³ whose sides are the wall; the columns from
// the wall reach the opposite side, so no layer line moves a node.
MixedMesh hexahedral_block() {
  MixedMesh mesh;
  mesh.marker_names = {"wall"};
  const double size = 1.0 / cells_per_side;
  for (int k = 0; k <= cells_per_side; ++k)
    for (int j = 0; j <= cells_per_side; ++j)
      for (int i = 0; i <= cells_per_side; ++i) mesh.points.emplace_back(i * size, j * size, k * size);
  for (int k = 0; k < cells_per_side; ++k)
    for (int j = 0; j < cells_per_side; ++j)
      for (int i = 0; i < cells_per_side; ++i) {
        const std::array<Index, 8> hexahedron = {grid_node(i, j, k),
                                                 grid_node(i + 1, j, k),
                                                 grid_node(i + 1, j + 1, k),
                                                 grid_node(i, j + 1, k),
                                                 grid_node(i, j, k + 1),
                                                 grid_node(i + 1, j, k + 1),
                                                 grid_node(i + 1, j + 1, k + 1),
                                                 grid_node(i, j + 1, k + 1)};
        mesh.add_cell(CellType::hexahedron, hexahedron.data());
      }
  // Every side is the wall, so only the 27 inner nodes are free.
  const int last = cells_per_side;
  auto add_quad = [&](Index a, Index b, Index c, Index d) {
    const std::array<Index, 4> quad = {a, b, c, d};
    mesh.add_face(FaceType::quad, quad.data(), 0);
  };
  for (int first = 0; first < cells_per_side; ++first)
    for (int second = 0; second < cells_per_side; ++second) {
      const int p = first;
      const int q = second;
      add_quad(grid_node(p, q, 0), grid_node(p, q + 1, 0), grid_node(p + 1, q + 1, 0),
               grid_node(p + 1, q, 0));
      add_quad(grid_node(p, q, last), grid_node(p + 1, q, last), grid_node(p + 1, q + 1, last),
               grid_node(p, q + 1, last));
      add_quad(grid_node(p, 0, q), grid_node(p + 1, 0, q), grid_node(p + 1, 0, q + 1),
               grid_node(p, 0, q + 1));
      add_quad(grid_node(p, last, q), grid_node(p, last, q + 1), grid_node(p + 1, last, q + 1),
               grid_node(p + 1, last, q));
      add_quad(grid_node(0, p, q), grid_node(0, p, q + 1), grid_node(0, p + 1, q + 1),
               grid_node(0, p + 1, q));
      add_quad(grid_node(last, p, q), grid_node(last, p + 1, q), grid_node(last, p + 1, q + 1),
               grid_node(last, p, q + 1));
    }
  return mesh;
}

// Stands for a method whose field has a kink one node wide: everything moves rigidly
// except `kinked`, pushed `shift` cells aside in x (1.5 cells turns the four cells on
// that side over).
class KinkedMethod : public DeformationMethod {
 public:
  KinkedMethod(RigidPose pose, Index kinked, double shift) : pose_(pose), kinked_(kinked), shift_(shift) {}
  std::string name() const override { return "kinked"; }
  std::vector<Vector3> move(const MixedMesh& mesh, const BoundaryMotion&, const Log&) override {
    std::vector<Vector3> moved(mesh.points.size());
    for (std::size_t node = 0; node < moved.size(); ++node) moved[node] = pose_.apply(mesh.points[node]);
    moved[static_cast<std::size_t>(kinked_)] += Vector3(shift_ / cells_per_side, 0.0, 0.0);
    return moved;
  }

 private:
  RigidPose pose_;
  Index kinked_;
  double shift_;
};

TEST(DeformUntangle, AKinkedNodeGoesBackToItsNeighboursRigidMotion) {
  const MixedMesh mesh = hexahedral_block();
  Body body;
  body.name = "block";
  body.markers = {"wall"};
  body.law = MotionLaw::rigid;
  body.centre = Vector3(0.5, 0.5, 0.0);
  body.axis = Vector3(0.3, -1.0, 0.2).normalized();
  body.angle = 25.0;
  body.translation = Vector3(0.1, 0.2, 0.3);
  Motion motion;
  motion.bodies = {body};
  const RigidPose pose = body_pose(body, 1, 1);
  const Index kinked = grid_node(2, 2, 2);
  KinkedMethod method(pose, kinked, 1.5);
  std::ostringstream report;
  const Log log(&report, Log::Level::verbose);
  const DeformResult result = deform_step(mesh, mesh, motion, 1, method, log);

  EXPECT_NE(report.str().find("untangle: 4 inverted cells after the layer transport, 0 after"),
            std::string::npos)
      << report.str();
  EXPECT_EQ(result.invalid_count, 0u);
  EXPECT_TRUE(result.valid);
  // The affine map of a rigid motion is the motion: the kinked node and the other free
  // nodes of the folded cells settle on it (to what ten sweeps leave of the kink: under
  // three thousandths of it, within the bound of 1/150), and the nodes outside those
  // cells do not move.
  const std::size_t kinked_node = static_cast<std::size_t>(kinked);
  for (std::size_t node = 0; node < mesh.points.size(); ++node) {
    const Vector3 offset = mesh.points[node] - mesh.points[kinked_node];
    const bool beside = offset.cwiseAbs().maxCoeff() < 1.5 / cells_per_side;
    EXPECT_LT((result.mesh.points[node] - pose.apply(mesh.points[node])).norm(),
              beside ? 1e-2 / cells_per_side : 1e-12)
        << "node " << node;
  }
}

TEST(DeformUntangle, AValidMeshIsLeftAsTheMethodGaveIt) {
  // The same kink, only a quarter cell: no cell folds, so nothing is repaired.
  const MixedMesh mesh = hexahedral_block();
  Body body;
  body.name = "block";
  body.markers = {"wall"};
  body.law = MotionLaw::rigid;
  body.translation = Vector3(0.0, 0.0, 0.1);
  Motion motion;
  motion.bodies = {body};
  const RigidPose pose = body_pose(body, 1, 1);
  KinkedMethod method(pose, grid_node(2, 2, 2), 0.25);
  const Log log(nullptr, Log::Level::quiet);
  const DeformResult result = deform_step(mesh, mesh, motion, 1, method, log);
  EXPECT_TRUE(result.valid);
  const std::size_t node = static_cast<std::size_t>(grid_node(2, 2, 2));
  EXPECT_LT(
      (result.mesh.points[node] - pose.apply(mesh.points[node]) - Vector3(0.25 / cells_per_side, 0.0, 0.0))
          .norm(),
      1e-12);
}

// The star of one node: an octahedron of corners (±1, 0, 0), (0, ±1, 0), (0, 0, ±1) cut
// into eight tetrahedra about the centre node 6, its faces the wall.
MixedMesh octahedron_star() {
  MixedMesh mesh;
  mesh.marker_names = {"wall"};
  mesh.points = {Vector3(1, 0, 0), Vector3(-1, 0, 0), Vector3(0, 1, 0), Vector3(0, -1, 0),
                 Vector3(0, 0, 1), Vector3(0, 0, -1), Vector3(0, 0, 0)};
  for (Index along_x : {0, 1})
    for (Index along_y : {2, 3})
      for (Index along_z : {4, 5}) {
        std::array<Index, 4> tetrahedron = {along_x, along_y, along_z, 6};
        if (signed_volume(CellType::tetrahedron, mesh.points, tetrahedron.data()) < 0.0)
          std::swap(tetrahedron[0], tetrahedron[1]);
        mesh.add_cell(CellType::tetrahedron, tetrahedron.data());
        // The face seen from outside: the reverse of the cell's face opposite the centre.
        std::array<Index, 3> face = {tetrahedron[0], tetrahedron[2], tetrahedron[1]};
        mesh.add_face(FaceType::triangle, face.data(), 0);
      }
  return mesh;
}

TEST(DeformUntangle, ANodeWhoseNeighboursDoNotMoveAffinelyGoesWhereItsCellsAreValid) {
  // The corner (1, 0, 0) moves to (−0.3, 0, 0), past the centre: the four cells on it are
  // valid only for a centre with x < −0.3. The affine map of the six corners' motion puts
  // the centre at x = −1.3 / 6 ≈ −0.22, still inverted; the optimisation finds the room
  // between x = −1 and −0.3.
  const MixedMesh mesh = octahedron_star();
  Body body;
  body.name = "star";
  body.markers = {"wall"};
  body.law = MotionLaw::mode;
  for (Index corner = 0; corner < 6; ++corner) {
    body.field.nodes.push_back(corner);
    body.field.values.push_back(corner == 0 ? Vector3(-1.3, 0.0, 0.0) : Vector3::Zero());
  }
  Motion motion;
  motion.bodies = {body};
  class Still : public DeformationMethod {
   public:
    std::string name() const override { return "still"; }
    std::vector<Vector3> move(const MixedMesh& mesh, const BoundaryMotion&, const Log&) override {
      return mesh.points;
    }
  } method;
  std::ostringstream report;
  const Log log(&report, Log::Level::verbose);
  const DeformResult result = deform_step(mesh, mesh, motion, 1, method, log);
  EXPECT_NE(report.str().find("untangle: 4 inverted cells after the layer transport, 0 after"),
            std::string::npos)
      << report.str();
  EXPECT_EQ(result.invalid_count, 0u);
  EXPECT_TRUE(result.valid);
  const Vector3& centre = result.mesh.points[6];
  EXPECT_LT(centre.x(), -0.3);
  EXPECT_GT(centre.x(), -1.0);
}

// Stands for a method whose field has a component normal to a symmetry plane near it:
// everything stays except the nodes in `steps`, moved by their vectors.
class SteppingMethod : public DeformationMethod {
 public:
  explicit SteppingMethod(std::vector<std::pair<Index, Vector3>> steps) : steps_(std::move(steps)) {}
  std::string name() const override { return "stepping"; }
  std::vector<Vector3> move(const MixedMesh& mesh, const BoundaryMotion&, const Log&) override {
    std::vector<Vector3> moved = mesh.points;
    for (const auto& [node, step] : steps_) moved[static_cast<std::size_t>(node)] += step;
    return moved;
  }

 private:
  std::vector<std::pair<Index, Vector3>> steps_;
};

TEST(DeformSymmetry, NoNodeIsCarriedThroughASymmetryPlane) {
  // The block with its side y = 0 a symmetry plane. A node a cell off the plane is sent
  // 1.6 cells towards it (through it), one three cells off a hundredth of a cell towards
  // it, one a cell off away from it: the first ends at s·exp(−d/s) (on its side, the
  // cells between it and the plane thin but not folded), the second within 10⁻⁴ of
  // where it was sent, the third exactly there.
  MixedMesh mesh = hexahedral_block();
  const int plane = mesh.marker("symmetry");
  for (std::size_t face = 0; face < mesh.face_count(FaceType::quad); ++face) {
    const Index* nodes = mesh.face(FaceType::quad, face);
    bool on_plane = true;
    for (int local = 0; local < 4; ++local)
      on_plane = on_plane && mesh.points[static_cast<std::size_t>(nodes[local])].y() == 0.0;
    if (on_plane) mesh.faces(FaceType::quad).markers[face] = plane;
  }
  Body body;
  body.name = "block";
  body.markers = {"wall"};
  body.law = MotionLaw::rigid;
  Motion motion;
  motion.bodies = {body};
  motion.symmetry = {"symmetry"};
  const double cell = 1.0 / cells_per_side;
  const Index through = grid_node(2, 1, 2);
  const Index small = grid_node(2, 3, 2);
  const Index away = grid_node(1, 1, 1);
  SteppingMethod method({{through, Vector3(0.0, -1.6 * cell, 0.0)},
                         {small, Vector3(0.0, -0.01 * cell, 0.0)},
                         {away, Vector3(0.0, 0.3 * cell, 0.0)}});
  std::ostringstream report;
  const Log log(&report, Log::Level::verbose);
  const DeformResult result = deform_step(mesh, mesh, motion, 1, method, log);
  EXPECT_EQ(report.str().find("untangle:"), std::string::npos) << report.str();
  EXPECT_TRUE(result.valid);
  EXPECT_NEAR(result.mesh.points[static_cast<std::size_t>(through)].y(), cell * std::exp(-1.6), 1e-12);
  EXPECT_NEAR(result.mesh.points[static_cast<std::size_t>(small)].y(), 2.99 * cell, 1e-4 * cell);
  EXPECT_DOUBLE_EQ(result.mesh.points[static_cast<std::size_t>(away)].y(), 1.3 * cell);
}

}  // namespace
}  // namespace mixmesh::deform
