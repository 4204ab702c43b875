// Layer lines (src/deform/layer_lines.hpp): the stacks of a flat plate and of the sheet
// behind it, found from the topology, move with their base after the method.
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include <sstream>
#include <string>

#include "mixmesh/deform/deform.hpp"

namespace mixmesh::deform {
namespace {

// A plate (x in [-1, 0], zero thickness: its nodes at z = 0 twice, above and below)
// and a sheet behind it (x in [0, 2], one node per place); three hexahedral layers of
// growing thickness above and below both, each column capped by a pyramid. The wall
// is the plate's two sides.
struct PlateWithSheet {
  static constexpr int plate_cells = 2;
  static constexpr int sheet_cells = 4;
  static constexpr int span_cells = 2;
  static constexpr int layers = 3;
  MixedMesh mesh;
  // node[side][layer][i][j]: side 0 above, 1 below; layer 0 is the surface.
  std::vector<Index> nodes;
  Index at(int side, int layer, int i, int j) const {
    return nodes[static_cast<std::size_t>(((side * (layers + 1) + layer) * (plate_cells + sheet_cells + 1) + i) *
                                              (span_cells + 1) +
                                          j)];
  }
};

PlateWithSheet plate_with_sheet() {
  PlateWithSheet plate;
  MixedMesh& mesh = plate.mesh;
  mesh.marker_names = {"wall"};
  const int columns = PlateWithSheet::plate_cells + PlateWithSheet::sheet_cells;
  const std::array<double, 4> height = {0.0, 0.01, 0.03, 0.07};
  for (int side = 0; side < 2; ++side)
    for (int layer = 0; layer <= PlateWithSheet::layers; ++layer)
      for (int i = 0; i <= columns; ++i)
        for (int j = 0; j <= PlateWithSheet::span_cells; ++j) {
          const double x = -1.0 + 0.5 * i;
          // The sheet's nodes (x >= 0) and the trailing edge are shared by both sides.
          if (side == 1 && layer == 0 && i >= PlateWithSheet::plate_cells) {
            plate.nodes.push_back(plate.at(0, 0, i, j));
            continue;
          }
          plate.nodes.push_back(static_cast<Index>(mesh.points.size()));
          mesh.points.emplace_back(x, 0.5 * j, side == 0 ? height[static_cast<std::size_t>(layer)]
                                                         : -height[static_cast<std::size_t>(layer)]);
        }
  for (int side = 0; side < 2; ++side)
    for (int i = 0; i < columns; ++i)
      for (int j = 0; j < PlateWithSheet::span_cells; ++j) {
        auto quad = [&](int layer) {
          std::array<Index, 4> quad = {plate.at(side, layer, i, j), plate.at(side, layer, i + 1, j),
                                       plate.at(side, layer, i + 1, j + 1), plate.at(side, layer, i, j + 1)};
          if (side == 1) std::swap(quad[1], quad[3]);  // below: the same turn seen from outside
          return quad;
        };
        for (int layer = 0; layer < PlateWithSheet::layers; ++layer) {
          const std::array<Index, 4> bottom = quad(layer);
          const std::array<Index, 4> top = quad(layer + 1);
          const std::array<Index, 8> hexahedron = {bottom[0], bottom[1], bottom[2], bottom[3],
                                                   top[0],    top[1],    top[2],    top[3]};
          mesh.add_cell(CellType::hexahedron, hexahedron.data());
        }
        const std::array<Index, 4> top = quad(PlateWithSheet::layers);
        const Index apex = static_cast<Index>(mesh.points.size());
        Vector3 centre = Vector3::Zero();
        for (Index node : top) centre += mesh.points[static_cast<std::size_t>(node)] / 4.0;
        mesh.points.push_back(centre + Vector3(0.0, 0.0, side == 0 ? 0.2 : -0.2));
        const std::array<Index, 5> pyramid = {top[0], top[3], top[2], top[1], apex};
        mesh.add_cell(CellType::pyramid, pyramid.data());
        if (i < PlateWithSheet::plate_cells) {
          std::array<Index, 4> wall = quad(0);
          std::swap(wall[1], wall[3]);  // facing into the plate
          mesh.add_face(FaceType::quad, wall.data(), 0);
        }
      }
  return plate;
}

// Stands for a method whose field is smooth on the scale of the cells but not across a
// layer: everything moves with the body, the nodes inside the stacks are sheared by more
// than the first layer is thick, the stacks' outermost nodes are lifted by `lift`, and
// the pyramids' apexes are pushed aside.
class ShearingMethod : public DeformationMethod {
 public:
  ShearingMethod(RigidPose pose, const PlateWithSheet& plate) : pose_(pose), plate_(plate) {}
  std::string name() const override { return "shearing"; }
  std::vector<Vector3> move(const MixedMesh& mesh, const BoundaryMotion&, const Log&) override {
    std::vector<Vector3> moved(mesh.points.size());
    for (std::size_t node = 0; node < moved.size(); ++node) moved[node] = pose_.apply(mesh.points[node]);
    for (int side = 0; side < 2; ++side)
      for (int layer = 1; layer <= PlateWithSheet::layers; ++layer)
        for (int i = 0; i <= PlateWithSheet::plate_cells + PlateWithSheet::sheet_cells; ++i)
          for (int j = 0; j <= PlateWithSheet::span_cells; ++j) {
            const std::size_t node = static_cast<std::size_t>(plate_.at(side, layer, i, j));
            moved[node] += layer == PlateWithSheet::layers ? lift : Vector3(0.05 * ((i + layer) % 3), 0.0, -0.02);
          }
    for (std::size_t node = apex_begin(); node < moved.size(); ++node) moved[node] += aside;
    return moved;
  }
  std::size_t apex_begin() const {
    return static_cast<std::size_t>(plate_.at(1, PlateWithSheet::layers, PlateWithSheet::plate_cells +
                                                                              PlateWithSheet::sheet_cells,
                                              PlateWithSheet::span_cells)) + 1;
  }
  const Vector3 lift{0.0, 0.0, 0.01};
  const Vector3 aside{0.03, 0.0, 0.0};

 private:
  RigidPose pose_;
  const PlateWithSheet& plate_;
};

TEST(DeformLayerLines, StacksOfAWallAndOfASheetMoveWithTheirBase) {
  const PlateWithSheet plate = plate_with_sheet();
  Body body;
  body.name = "plate";
  body.markers = {"wall"};
  body.law = MotionLaw::rigid;
  body.centre = Vector3(0.3, 0.0, 0.0);
  body.axis = Vector3(0.2, -1.0, 0.3).normalized();
  body.angle = 20.0;
  body.translation = Vector3(0.2, 0.1, 0.5);
  Motion motion;
  motion.bodies = {body};
  const RigidPose pose = body_pose(body, 1, 1);
  ShearingMethod method(pose, plate);
  std::ostringstream report;
  const Log log(&report, Log::Level::verbose);
  const DeformResult result = deform_step(plate.mesh, plate.mesh, motion, 1, method, log);

  // Found: every plate face's column on both sides, the sheet's faces grown from the
  // trailing edge, and each of their two columns.
  const int sheet_faces = PlateWithSheet::sheet_cells * PlateWithSheet::span_cells;
  std::ostringstream expected;
  expected << "layer lines: " << 2 * PlateWithSheet::plate_cells * PlateWithSheet::span_cells
           << " wall columns, " << sheet_faces << " sheet faces with " << 2 * sheet_faces << " columns";
  EXPECT_NE(report.str().find(expected.str()), std::string::npos) << report.str();
  EXPECT_NE(report.str().find("0 columns reach a boundary (left to the method), 0 conflicts"), std::string::npos);

  // The wall's lines (the plate's columns, trailing edge included) exactly on their
  // base's rigid motion, tops too. What the method had at their tops (the lift) is taken
  // off the nodes outside the layers instead, by a share between 0 and 1 that fades above
  // and beside the layers (the apexes over the plate keep most of it off: 0.2 above the
  // tops, a third of a face size). The sheet's lines lose the method's shear (0.05 to
  // 0.1 across them): they move with their base and top, both within a lift of the body.
  const std::vector<Vector3>& points = plate.mesh.points;
  for (int side = 0; side < 2; ++side)
    for (int layer = 0; layer <= PlateWithSheet::layers; ++layer)
      for (int i = 0; i <= PlateWithSheet::plate_cells + PlateWithSheet::sheet_cells; ++i)
        for (int j = 0; j <= PlateWithSheet::span_cells; ++j) {
          const std::size_t node = static_cast<std::size_t>(plate.at(side, layer, i, j));
          const double off = (result.mesh.points[node] - pose.apply(points[node])).norm();
          if (i <= PlateWithSheet::plate_cells) {
            EXPECT_LT(off, 1e-12) << "side " << side << " layer " << layer << " i " << i;
          } else {
            EXPECT_LE(off, method.lift.norm() * (1.0 + 1e-9))
                << "side " << side << " layer " << layer << " i " << i;
            // Straight before, straight after: the node stays on the chord from its
            // moved base to its moved top, at the same fraction of the line's length.
            const std::size_t base = static_cast<std::size_t>(plate.at(side, 0, i, j));
            const std::size_t top = static_cast<std::size_t>(plate.at(side, PlateWithSheet::layers, i, j));
            const double fraction = (points[node] - points[base]).norm() / (points[top] - points[base]).norm();
            const Vector3& moved_base = result.mesh.points[base];
            const Vector3& moved_top = result.mesh.points[top];
            EXPECT_LT((result.mesh.points[node] - (moved_base + fraction * (moved_top - moved_base))).norm(), 1e-12)
                << "side " << side << " layer " << layer << " i " << i;
          }
        }
  const Vector3 lift_direction = method.lift.normalized();
  for (std::size_t node = method.apex_begin(); node < points.size(); ++node) {
    const Vector3 taken = pose.apply(points[node]) + method.aside - result.mesh.points[node];
    EXPECT_LT((taken - taken.dot(lift_direction) * lift_direction).norm(), 1e-12) << "apex " << node;
    const double share = taken.dot(lift_direction) / method.lift.norm();
    EXPECT_GE(share, 0.0) << "apex " << node;
    EXPECT_LE(share, 1.0) << "apex " << node;
    if (points[node].x() < 0.0) {
      EXPECT_GT(share, 0.5) << "apex " << node;
    }
  }
}

// Stands for a method that moves everything rigidly except one node of the sheet,
// lifted by `lift` across it: the noise a method's field has at a sheet's free edge.
class NoisySheetMethod : public DeformationMethod {
 public:
  NoisySheetMethod(RigidPose pose, Index noisy) : pose_(pose), noisy_(noisy) {}
  std::string name() const override { return "noisy"; }
  std::vector<Vector3> move(const MixedMesh& mesh, const BoundaryMotion&, const Log&) override {
    std::vector<Vector3> moved(mesh.points.size());
    for (std::size_t node = 0; node < moved.size(); ++node) moved[node] = pose_.apply(mesh.points[node]);
    moved[static_cast<std::size_t>(noisy_)] += lift;
    return moved;
  }
  const Vector3 lift{0.0, 0.0, 0.05};

 private:
  RigidPose pose_;
  Index noisy_;
};

TEST(DeformLayerLines, ACurvedSheetLineKeepsItsShapeWhenItsBasesStarIsNoisy) {
  // The sheet line at x = 0.5, y = 0.5 bent 0.1 in x at its second layer; its base's
  // neighbour at x = 1 lifted 0.05 by the method. The rotation fitted to the base's
  // star tilts and swings the bend with it (1.6e-3 off the rigid motion); the line's
  // own chord (base and top moved rigidly) turns it back, exactly here.
  PlateWithSheet plate = plate_with_sheet();
  const int column = PlateWithSheet::plate_cells + 1;
  const std::size_t bent = static_cast<std::size_t>(plate.at(0, 2, column, 1));
  plate.mesh.points[bent].x() += 0.1;
  Body body;
  body.name = "plate";
  body.markers = {"wall"};
  body.law = MotionLaw::rigid;
  body.centre = Vector3(0.3, 0.0, 0.0);
  body.axis = Vector3(0.0, -1.0, 0.0);
  body.angle = 15.0;
  Motion motion;
  motion.bodies = {body};
  const RigidPose pose = body_pose(body, 1, 1);
  NoisySheetMethod method(pose, plate.at(0, 0, column + 1, 1));
  const Log log(nullptr, Log::Level::quiet);
  const DeformResult result = deform_step(plate.mesh, plate.mesh, motion, 1, method, log);
  EXPECT_LT((result.mesh.points[bent] - pose.apply(plate.mesh.points[bent])).norm(), 1e-12);
}

}  // namespace
}  // namespace mixmesh::deform
