// The nearest wall faces of the ARA predictor against an exhaustive search, on a
// volume O-grid whose far field encloses the body (the case that makes a k-d search of
// the far-field faces slow, and that the search answers approximately).
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <vector>

#include "deform/dual_mesh.hpp"
#include "deform/wall_faces.hpp"
#include "deform_meshes.hpp"

namespace mixmesh::deform {
namespace {

using testing::OGrid;
using testing::VolumeKind;

struct Exhaustive {
  double distance = std::numeric_limits<double>::infinity();
  double centre_distance = std::numeric_limits<double>::infinity();
};

TEST(DeformWallFaces, NearestBoundaryExactFartherBoundaryWithinTheSearchSlack) {
  OGrid grid;
  grid.around = 40;
  grid.outward = 14;
  grid.layers_z = 3;
  MixedMesh mesh = testing::volume_o_grid(grid, VolumeKind::hex_and_prism);
  const detail::DualMesh dual = detail::build_dual_mesh(mesh);
  std::vector<MarkerRole> roles(mesh.marker_names.size(), MarkerRole::fixed);
  for (std::size_t marker = 0; marker < mesh.marker_names.size(); ++marker)
    if (mesh.marker_names[marker] == "bottom" || mesh.marker_names[marker] == "top")
      roles[marker] = MarkerRole::sliding;
  const detail::WallFaces walls = detail::wall_faces(dual, roles);
  ASSERT_EQ(walls.boundary_count, 2);  // the ellipse and the enclosing far field
  std::vector<Vector3> centres(dual.cell_count());
  for (std::size_t cell = 0; cell < centres.size(); ++cell)
    centres[cell] = detail::cell_centre(dual, cell, mesh.points);
  const NearestFaces nearest = detail::find_nearest_faces(dual, walls, centres, mesh.points, 8);
  std::vector<double> first;
  std::vector<double> second;
  detail::nearest_distances(dual, walls, nearest, centres, mesh.points, first, second);

  int body = -1;  // the ellipse's boundary number
  for (std::size_t wall = 0; wall < walls.faces.size(); ++wall)
    if (dual.face_marker[static_cast<std::size_t>(walls.faces[wall])] == mesh.marker("wall"))
      body = walls.boundary[wall];
  ASSERT_GE(body, 0);
  std::size_t nearer_the_body = 0;
  for (std::size_t cell = 0; cell < centres.size(); ++cell) {
    Exhaustive boundary[2];
    for (std::size_t wall = 0; wall < walls.faces.size(); ++wall) {
      const std::size_t face = static_cast<std::size_t>(walls.faces[wall]);
      const Index* nodes = dual.boundary_nodes(face);
      Vector3 corners[4];
      for (int local = 0; local < dual.face_size(face); ++local)
        corners[local] = mesh.points[static_cast<std::size_t>(nodes[local])];
      Exhaustive& entry = boundary[walls.boundary[wall]];
      entry.distance =
          std::min(entry.distance, detail::point_face_distance(centres[cell], corners, dual.face_size(face)));
      entry.centre_distance = std::min(entry.centre_distance,
                                       (detail::face_centre(dual, face, mesh.points) - centres[cell]).norm());
    }
    const int near = boundary[0].distance <= boundary[1].distance ? 0 : 1;
    const Exhaustive& closer = boundary[near];
    const Exhaustive& farther = boundary[1 - near];
    ASSERT_GE(nearest.faces[cell][1], 0);
    EXPECT_EQ(walls.boundary[static_cast<std::size_t>(nearest.faces[cell][0])], near) << "cell " << cell;
    EXPECT_NEAR(first[cell], closer.distance, 1e-12 * closer.distance + 1e-15) << "cell " << cell;
    // The farther boundary: exact within three times the nearest distance, else a face
    // whose centre lies within 1.5 times the nearest centre.
    EXPECT_GE(second[cell], farther.distance - 1e-12);
    if (farther.distance <= 3.0 * closer.distance)
      EXPECT_NEAR(second[cell], farther.distance, 1e-12 * farther.distance) << "cell " << cell;
    else
      EXPECT_LE(second[cell], 1.5 * farther.centre_distance + 1e-12) << "cell " << cell;
    nearer_the_body += near == body ? 1 : 0;
  }
  EXPECT_GT(nearer_the_body, centres.size() / 2);  // the O-grid's rings crowd at the body
}

}  // namespace
}  // namespace mixmesh::deform
