#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <random>
#include <string>

#include "mixmesh/core/error.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/mesh/face_connectivity.hpp"
#include "mixmesh/optimize/sliver_removal.hpp"

namespace mixmesh {
namespace {

// Tags every boundary face of the cells "wall".
void tag_boundary_walls(MixedMesh& mesh) {
  const int wall = mesh.marker("wall");
  for (const CellFace& face : match_faces(mesh).boundary) {
    Index nodes[4];
    const int count = face_nodes(mesh, face, nodes);
    mesh.add_face(count == 3 ? FaceType::triangle : FaceType::quad, nodes, wall);
  }
}

// A block of n^3 unit cubes, each cut into six tetrahedra round its main diagonal,
// every boundary face tagged "wall".
MixedMesh cube_block(int n) {
  MixedMesh mesh;
  auto id = [&](int i, int j, int k) { return static_cast<Index>((k * (n + 1) + j) * (n + 1) + i); };
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) mesh.points.emplace_back(i, j, k);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Index c[8] = {
            id(i, j, k),     id(i + 1, j, k),     id(i + 1, j + 1, k),     id(i, j + 1, k),
            id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)};
        // Kuhn's six tetrahedra round the diagonal 0-6.
        const int paths[6][2] = {{1, 2}, {2, 3}, {3, 7}, {7, 4}, {4, 5}, {5, 1}};
        for (const auto& path : paths) {
          Index t[4] = {c[0], c[path[0]], c[path[1]], c[6]};
          if (tetrahedron_volume6(mesh.points[static_cast<std::size_t>(t[0])],
                                  mesh.points[static_cast<std::size_t>(t[1])],
                                  mesh.points[static_cast<std::size_t>(t[2])],
                                  mesh.points[static_cast<std::size_t>(t[3])]) < 0.0)
            std::swap(t[1], t[2]);
          mesh.add_cell(CellType::tetrahedron, t);
        }
      }
  tag_boundary_walls(mesh);
  return mesh;
}

double largest_dihedral(const MixedMesh& mesh, std::size_t& above_160) {
  double largest = 0.0;
  above_160 = 0;
  for (std::size_t t = 0; t < mesh.cell_count(CellType::tetrahedron); ++t) {
    const Index* n = mesh.cell(CellType::tetrahedron, t);
    const double angle = largest_dihedral_degrees(
        mesh.points[static_cast<std::size_t>(n[0])], mesh.points[static_cast<std::size_t>(n[1])],
        mesh.points[static_cast<std::size_t>(n[2])], mesh.points[static_cast<std::size_t>(n[3])]);
    largest = std::max(largest, angle);
    above_160 += angle > 160.0 ? 1 : 0;
  }
  return largest;
}

// The largest dihedral angle of the tetrahedra whose centroid lies within `radius` of
// the origin, and how many of them are above 170 degrees.
double largest_dihedral_within(const MixedMesh& mesh, double radius, std::size_t& above_170) {
  double largest = 0.0;
  above_170 = 0;
  for (std::size_t t = 0; t < mesh.cell_count(CellType::tetrahedron); ++t) {
    const Index* n = mesh.cell(CellType::tetrahedron, t);
    const Vector3 &a = mesh.points[static_cast<std::size_t>(n[0])],
                  &b = mesh.points[static_cast<std::size_t>(n[1])],
                  &c = mesh.points[static_cast<std::size_t>(n[2])],
                  &d = mesh.points[static_cast<std::size_t>(n[3])];
    if ((0.25 * (a + b + c + d)).norm() > radius) continue;
    const double angle = largest_dihedral_degrees(a, b, c, d);
    largest = std::max(largest, angle);
    above_170 += angle > 170.0 ? 1 : 0;
  }
  return largest;
}

double total_volume(const MixedMesh& mesh) {
  double volume = 0.0;
  for (std::size_t t = 0; t < mesh.cell_count(CellType::tetrahedron); ++t)
    volume += signed_volume(CellType::tetrahedron, mesh.points, mesh.cell(CellType::tetrahedron, t));
  return volume;
}

TEST(LargestDihedral, RightCornerStretchedStaysAtNinetyAndASliverNearsOneEighty) {
  const Vector3 o(0, 0, 0);
  EXPECT_NEAR(largest_dihedral_degrees(o, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}), 90.0, 1e-9);
  EXPECT_NEAR(largest_dihedral_degrees(o, {1000, 0, 0}, {0, 1, 0}, {0, 0, 0.001}), 90.0, 1e-9);
  // A square with a tiny lift on two opposite corners: two dihedral angles near 180.
  EXPECT_GT(largest_dihedral_degrees({0, 0, 0}, {1, 0, 1e-3}, {1, 1, 0}, {0, 1, 1e-3}), 179.0);
  EXPECT_NEAR(largest_dihedral_degrees({0, 0, 0}, {1, 0, 0}, {0.5, std::sqrt(0.75), 0},
                                       {0.5, std::sqrt(0.75) / 3.0, std::sqrt(2.0 / 3.0)}),
              std::acos(1.0 / 3.0) * 180.0 / M_PI, 1e-9);
}

TEST(SliverRemoval, PerturbedBlockLosesItsSliversAndKeepsItsBoundaryAndVolume) {
  MixedMesh mesh = cube_block(6);
  // Interior points pushed towards a neighbour's plane make slivers; every cell stays valid.
  std::mt19937 random(7);
  std::uniform_real_distribution<double> shift(-0.49, 0.49);
  for (std::size_t p = 0; p < mesh.points.size(); ++p) {
    Vector3& x = mesh.points[p];
    if (x.minCoeff() == 0.0 || x.maxCoeff() == 6.0) continue;
    const Vector3 start = x;
    x += Vector3(shift(random), shift(random), shift(random));
    bool valid = true;
    for (std::size_t t = 0; t < mesh.cell_count(CellType::tetrahedron) && valid; ++t)
      valid = signed_volume(CellType::tetrahedron, mesh.points, mesh.cell(CellType::tetrahedron, t)) > 0.0;
    if (!valid) x = start;
  }
  std::size_t above_before = 0, above_after = 0;
  const double before = largest_dihedral(mesh, above_before);
  ASSERT_GT(above_before, 10u);
  const std::size_t boundary_faces = mesh.face_count();
  const double volume = total_volume(mesh);

  const SliverReport report = remove_slivers(mesh, SliverOptions{});
  const double after = largest_dihedral(mesh, above_after);
  std::printf(
      "largest dihedral %.2f -> %.2f deg, above 160: %zu -> %zu, %zu edge removals, %zu flips, %zu moves\n",
      before, after, above_before, above_after, report.edge_removals, report.face_flips,
      report.smoothed_points);
  EXPECT_EQ(report.above_target_before, above_before);
  EXPECT_EQ(report.above_target_after, above_after);
  EXPECT_LT(after, before);
  EXPECT_LT(above_after * 4, above_before);
  EXPECT_NEAR(total_volume(mesh), volume, 1e-9 * volume);
  for (std::size_t t = 0; t < mesh.cell_count(CellType::tetrahedron); ++t)
    EXPECT_TRUE(cell_shape(CellType::tetrahedron, mesh.points, mesh.cell(CellType::tetrahedron, t)).valid());
  // The same boundary faces, every one on a cell, the mesh conforming.
  EXPECT_EQ(mesh.face_count(), boundary_faces);
  const FaceConnectivity faces = match_faces(mesh);
  EXPECT_TRUE(faces.conforming());
  EXPECT_TRUE(faces.untagged_boundary.empty());
  EXPECT_TRUE(faces.stray_boundary_faces.empty());
  // Boundary points never move.
  for (std::size_t p = 0; p < mesh.points.size(); ++p) {
    const Vector3& x = mesh.points[p];
    if (x.minCoeff() == 0.0 || x.maxCoeff() == 6.0) {
      EXPECT_EQ(x, Vector3(x.array().round().matrix()));
    }
  }
}

TEST(SliverRemoval, APointOnAnEdgeIsMendedByTheFanFromIt) {
  // Nine tetrahedra round the edge a-c, every point on the boundary: the ring's point
  // r lies a hair off the edge's middle (three hull points in a line, as at a trailing
  // edge), so the two tetrahedra with r are flat. The ring is longer than maximum_ring;
  // the fan of the ring polygon from r cuts the other seven in two at r and mends both,
  // with no new point.
  MixedMesh mesh;
  mesh.points = {{-1, 0, 0}, {1, 0, 0}, {0, 0, 1e-3}};  // a, c, r
  for (int k = 1; k <= 8; ++k) {
    const double angle = 40.0 * k * M_PI / 180.0;
    mesh.points.emplace_back(0.0, std::sin(angle), std::cos(angle));
  }
  for (Index k = 0; k < 9; ++k) {
    Index t[4] = {0, 1, static_cast<Index>(2 + k), static_cast<Index>(2 + (k + 1) % 9)};
    if (tetrahedron_volume6(mesh.points[static_cast<std::size_t>(t[0])], mesh.points[static_cast<std::size_t>(t[1])],
                            mesh.points[static_cast<std::size_t>(t[2])],
                            mesh.points[static_cast<std::size_t>(t[3])]) < 0.0)
      std::swap(t[0], t[1]);
    mesh.add_cell(CellType::tetrahedron, t);
  }
  tag_boundary_walls(mesh);
  std::size_t above = 0;
  ASSERT_GT(largest_dihedral(mesh, above), 179.0);
  const double volume = std::abs(total_volume(mesh));
  SliverOptions options;
  options.smooth_points = false;
  options.search_points = false;
  options.insert_points = false;
  const SliverReport report = remove_slivers(mesh, options);
  EXPECT_LT(largest_dihedral(mesh, above), 150.0);
  EXPECT_EQ(report.edge_removals, 1u);
  EXPECT_EQ(mesh.points.size(), 11u);
  EXPECT_EQ(mesh.cell_count(CellType::tetrahedron), 14u);
  EXPECT_NEAR(std::abs(total_volume(mesh)), volume, 1e-12);
  EXPECT_TRUE(match_faces(mesh).conforming());
}

TEST(SliverRemoval, AFreePointJustAboveAFaceIsCollapsedAndDropped) {
  // One tetrahedron coned from an inner point a hair above its base: the cone on the
  // base is flat, and no flip of the four mends it (the point lies inside), but merging
  // the point into a corner gives back the one tetrahedron.
  MixedMesh mesh;
  mesh.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.3, 0.3, 1e-3}};
  const Index cone[4][4] = {{0, 2, 1, 4}, {0, 1, 3, 4}, {1, 2, 3, 4}, {0, 3, 2, 4}};
  for (const auto& t : cone) mesh.add_cell(CellType::tetrahedron, t);
  const int wall = mesh.marker("wall");
  for (const CellFace& face : match_faces(mesh).boundary) {
    Index nodes[4];
    face_nodes(mesh, face, nodes);
    mesh.add_face(FaceType::triangle, nodes, wall);
  }
  std::size_t above = 0;
  ASSERT_GT(largest_dihedral(mesh, above), 179.0);
  SliverOptions options;
  options.smooth_points = false;
  const SliverReport report = remove_slivers(mesh, options);
  EXPECT_EQ(report.point_collapses, 1u);
  EXPECT_EQ(mesh.cell_count(CellType::tetrahedron), 1u);
  EXPECT_EQ(mesh.points.size(), 4u);
  EXPECT_NEAR(std::abs(total_volume(mesh)), 1.0 / 6.0, 1e-12);  // the cones are negatively oriented
  EXPECT_TRUE(match_faces(mesh).conforming());
  EXPECT_EQ(mesh.face_count(), 4u);
}

TEST(SliverRemoval, APointOnAFlatBoundaryMovesWithinItsPlane) {
  // A point of the block's bottom face pushed along the face until its boundary
  // triangles are needles: only moving it mends them, and it must stay in the plane.
  MixedMesh mesh = cube_block(3);
  const auto moved = static_cast<std::size_t>(1 * 4 + 1);  // (1, 1, 0)
  ASSERT_EQ(mesh.points[moved], Vector3(1, 1, 0));
  std::size_t above = 0;
  for (double step = 0.0; step < 1.0; step += 0.01) {
    mesh.points[moved] = Vector3(1 + step, 1 + step, 0);
    bool valid = true;
    for (std::size_t t = 0; t < mesh.cell_count(CellType::tetrahedron) && valid; ++t)
      valid = signed_volume(CellType::tetrahedron, mesh.points, mesh.cell(CellType::tetrahedron, t)) > 0.0;
    if (!valid) {
      mesh.points[moved] = Vector3(1 + step - 0.01, 1 + step - 0.01, 0);
      break;
    }
  }
  const double before = largest_dihedral(mesh, above);
  ASSERT_GT(before, 170.0);
  const Vector3 pushed = mesh.points[moved];
  remove_slivers(mesh, SliverOptions{});
  EXPECT_LT((mesh.points[moved] - Vector3(1, 1, 0)).norm(), (pushed - Vector3(1, 1, 0)).norm());
  const double after = largest_dihedral(mesh, above);
  std::printf("largest dihedral %.2f -> %.2f deg\n", before, after);
  EXPECT_LT(after, 160.0);
  EXPECT_EQ(mesh.points[moved].z(), 0.0);
  EXPECT_TRUE(match_faces(mesh).conforming());
}

// The tetrahedra of tests/unit/data/NAME.txt, its outer faces tagged "wall".
MixedMesh sliver_patch(const std::string& name = "sliver_patch_behind_trailing_edge") {
  std::ifstream in(std::string(MIXMESH_SOURCE_DIR) + "/tests/unit/data/" + name + ".txt");
  std::string line;
  while (in.peek() == '#') std::getline(in, line);
  MixedMesh mesh;
  std::size_t count = 0;
  in >> count;
  mesh.points.resize(count);
  for (Vector3& point : mesh.points) in >> point.x() >> point.y() >> point.z();
  in >> count;
  for (std::size_t k = 0; k < count; ++k) {
    Index nodes[4];
    in >> nodes[0] >> nodes[1] >> nodes[2] >> nodes[3];
    mesh.add_cell(CellType::tetrahedron, nodes);
  }
  in >> count;
  const int wall = mesh.marker("wall");
  for (std::size_t k = 0; k < count; ++k) {
    Index nodes[3];
    in >> nodes[0] >> nodes[1] >> nodes[2];
    mesh.add_face(FaceType::triangle, nodes, wall);
  }
  EXPECT_TRUE(in) << "cannot read the sliver patch";
  return mesh;
}

// The default pass on the patch tests/unit/data/NAME.txt, judged on the tetrahedra whose
// centroid lies within `radius` of the patch's centre (its cut faces are walls, so the
// tetrahedra next to them may stay flat). The volume, the conformity and the boundary
// faces must be kept.
struct PatchResult {
  double before = 0.0, after = 0.0;  // the largest dihedral angle, degrees
  std::size_t above_170_before = 0, above_170_after = 0;
  SliverReport report;
};

PatchResult remove_slivers_round_centre(const std::string& name, double radius,
                                        const SliverOptions& options = SliverOptions{}) {
  MixedMesh mesh = sliver_patch(name);
  PatchResult result;
  result.before = largest_dihedral_within(mesh, radius, result.above_170_before);
  const double volume = total_volume(mesh);
  const std::size_t faces = mesh.face_count();
  result.report = remove_slivers(mesh, options);
  result.after = largest_dihedral_within(mesh, radius, result.above_170_after);
  std::printf(
      "within %.2f m of the centre: largest dihedral %.2f -> %.2f deg, above 170 deg %zu -> %zu, "
      "%zu points inserted\n",
      radius, result.before, result.after, result.above_170_before, result.above_170_after,
      result.report.point_insertions);
  EXPECT_NEAR(total_volume(mesh) / volume, 1.0, 1e-9);
  EXPECT_TRUE(match_faces(mesh).conforming());
  EXPECT_EQ(mesh.face_count(), faces);
  return result;
}

TEST(SliverRemoval, SliversOnTheHullBehindATrailingEdgeNeedNewPoints) {
  // A wing's far field behind its trailing edge, where the hull's quads are long and
  // narrow and nearly flat: tetrahedra lie on two hull triangles of a shallow fold, or
  // between neighbouring caps, and no flip, split, collapse or move brings the worst
  // under 170 degrees; points inserted above them do, and further than the moves.
  MixedMesh without = sliver_patch();
  std::size_t above = 0;
  const double before = largest_dihedral(without, above);
  ASSERT_GT(before, 179.0);
  const double volume = total_volume(without);
  SliverOptions options;
  options.insert_points = false;
  const SliverReport plain = remove_slivers(without, options);
  EXPECT_EQ(plain.point_insertions, 0u);
  // Moves at the slivers' own scale and the searched moves bring the worst to 171.5
  // degrees, still above 170.
  EXPECT_GT(largest_dihedral(without, above), 170.0);
  std::size_t plain_above_170 = 0;
  largest_dihedral_within(without, 1e9, plain_above_170);

  MixedMesh mesh = sliver_patch();
  const std::size_t points = mesh.points.size();
  const SliverReport report = remove_slivers(mesh, SliverOptions{});
  const double after = largest_dihedral(mesh, above);
  std::printf("largest dihedral %.2f -> %.2f deg (without insertion %.2f), %zu points inserted\n", before,
              after, plain.largest_dihedral_after, report.point_insertions);
  EXPECT_GE(report.point_insertions, 1u);
  EXPECT_LT(after, std::min(175.0, plain.largest_dihedral_after));
  // Fewer above 170 degrees, the suite's bound on the share of flat tetrahedra. (Above
  // the 160-degree target the two are alike since the searched moves: 411 and 408 of
  // 1,464, most against the patch's walls; 9 insertions and fewer above 160 without
  // them.)
  std::size_t above_170 = 0;
  largest_dihedral_within(mesh, 1e9, above_170);
  std::printf("above 170 deg: %zu, without insertion %zu\n", above_170, plain_above_170);
  EXPECT_LT(above_170, plain_above_170);
  EXPECT_LE(mesh.points.size(), points + report.point_insertions + report.edge_splits);
  EXPECT_NEAR(total_volume(mesh) / volume, 1.0, 1e-9);
  EXPECT_TRUE(match_faces(mesh).conforming());
  EXPECT_EQ(mesh.face_count(), sliver_patch().face_count());
}

TEST(SliverRemoval, SliversOnThreeNearlyCollinearHullNodesNeedAPointAtTheirOwnScale) {
  // Over a large swept wing the hull's quads are 2 m along the span and 4 cm along the
  // chord: three consecutive hull nodes of one station lie nearly on a line, and
  // TetGen's tetrahedra on their triangle (with a point of the next station) are flat
  // on both sides of it. A point a chord-wise cell above them mends them; one a tenth
  // of the sliver's longest edge up (20 cm, five cells) does not. The patch's cut faces
  // are walls, so only the slivers round its centre (the middle node) are judged.
  const PatchResult result = remove_slivers_round_centre("sliver_patch_leading_edge_station", 1.0);
  ASSERT_GT(result.before, 179.0);
  ASSERT_GT(result.above_170_before, 10u);
  EXPECT_GE(result.report.point_insertions, 1u);
  // Long-scale trial points only: 178.8 degrees and 22 above 170.
  EXPECT_LT(result.after, 175.0);
  EXPECT_LE(result.above_170_after, 2u);
}

TEST(SliverRemoval, FlatTetrahedraOnANearlyFlatHullGetASmallCavity) {
  // Just ahead of a trailing edge the hull is nearly flat and its quads are 7 mm by
  // 11 cm: TetGen lays tetrahedra of four hull nodes on it, and the circumspheres of
  // those flat tetrahedra are huge. A point over the sliver lies in dozens of them, so
  // its Bowyer-Watson cavity runs to its limit and is not star-shaped; the cavity of
  // the sliver and the tetrahedron holding the point, grown until star-shaped, is. With
  // the Bowyer-Watson cavity alone the sliver at the centre stays at 178.8 degrees.
  const PatchResult result = remove_slivers_round_centre("sliver_patch_flat_hull_near_trailing_edge", 0.06);
  ASSERT_GT(result.before, 178.0);
  EXPECT_GE(result.report.point_insertions, 1u);
  EXPECT_LT(result.after, 175.0);
  EXPECT_EQ(result.above_170_after, 0u);
}

TEST(SliverRemoval, PointsInACornerUnderLongEdgesMoveAtTheirOwnScale) {
  // Where a wake's first cap meets the wing's hull at a closed trailing edge, the cap's
  // face rises straight from the hull: a concave corner along a 61 mm edge, with the
  // hull's cells a few tenths of a millimetre across. A point inserted there lies a
  // millimetre off the cap's face, so its steps of a twentieth of its edges' mean length
  // (tens of millimetres) all cross the hull; steps of a few times its height over the
  // opposite face mend it. Without them the pass leaves 177.4 degrees within 1 cm of
  // the corner (176.1 on a patch cut twice as wide); with them 173.8 (174.5). In the
  // whole mesh, whose far field has room to move, the pass ends at 165 degrees instead
  // of 175.3. The searched moves are left out: on this patch, whose cut faces are walls
  // a centimetre from the corner, they trim slivers the insertions would mend (175.5
  // degrees with them), while on the whole wing they end at 167.3 degrees.
  SliverOptions options;
  options.search_points = false;
  const PatchResult result = remove_slivers_round_centre("sliver_patch_wake_cap_corner", 0.01, options);
  ASSERT_GT(result.before, 178.0);
  EXPECT_LT(result.after, 175.0);
}

TEST(SliverRemoval, AClusterOverNeedleHullFacesNeedsSearchedMoves) {
  // Behind the leading edge of a swept wing near its tip the hull's faces are 2.5 mm by
  // 95 mm under layers 4 mm thick (seed 74 wing 13), and TetGen leaves a cluster of
  // slivers between the layer points: flips, splits, collapses and insertions leave
  // some above 175 degrees, and the ordinary moves of their far-field points all cross
  // a neighbour. The searched moves (lines towards the sliver's other points, then axis
  // steps) find the thin slab of positions that mends them.
  SliverOptions plain;
  plain.search_points = false;
  const PatchResult without = remove_slivers_round_centre("sliver_patch_needle_hull_cluster", 0.01, plain);
  // Without them 176.6 degrees and 54 above 170 within 1 cm of the centre; with them 159.6 and none.
  const PatchResult with = remove_slivers_round_centre("sliver_patch_needle_hull_cluster", 0.01);
  ASSERT_GT(without.before, 178.0);
  EXPECT_GT(without.after, 175.0);
  EXPECT_LT(with.after, 175.0);
  EXPECT_LT(with.above_170_after, without.above_170_after);
}

// The pieces of an outer cell split about a point, its walls tagged: points 0-3 are the
// inner quad, 4-7 the outer one above them, 8 the split point; a pyramid on each kept
// quad, and two tetrahedra on the outer quad, cut along its diagonal 4-6.
void add_split_cell(MixedMesh& mesh) {
  for (const std::array<Index, 5>& pyramid : std::vector<std::array<Index, 5>>{
           {0, 1, 2, 3, 8}, {0, 4, 5, 1, 8}, {1, 5, 6, 2, 8}, {2, 6, 7, 3, 8}, {3, 7, 4, 0, 8}})
    mesh.add_cell(CellType::pyramid, pyramid.data());
  for (const std::array<Index, 4>& tetrahedron :
       std::vector<std::array<Index, 4>>{{4, 6, 5, 8}, {4, 7, 6, 8}})
    mesh.add_cell(CellType::tetrahedron, tetrahedron.data());
  tag_boundary_walls(mesh);
}

// The outermost layer cell of a random wing (seed 71, wing 64) at its flat tip's trailing
// edge, split about its centre: its outer quad narrows from 47 mm to 4 mm over 230 mm
// and twists, and the tetrahedron on the quad's narrow half is a sliver that no flip
// can reach (its faces are pyramids' and the quad's). Metres, about the split point.
MixedMesh twisted_tip_cell() {
  MixedMesh mesh;
  const Vector3 centre(4.5563713140527415, 23.390266184156925, 1.54811020978844);
  for (const Vector3& point : {Vector3(4.553659031813586, 23.2720066569659, 1.569957053363615),
                               Vector3(4.557819246182786, 23.26986101979523, 1.5692178880869498),
                               Vector3(4.553050507652694, 23.475145652805434, 1.505619448899794),
                               Vector3(4.547454578544482, 23.494704357746617, 1.4748800896865961),
                               Vector3(4.562406306101147, 23.28421581138744, 1.614911951649289),
                               Vector3(4.563876641261688, 23.28068146666267, 1.6149644402354248),
                               Vector3(4.559757578062668, 23.509919035301596, 1.5371210078345108),
                               Vector3(4.552946622802878, 23.535595472590508, 1.4982097985513398), centre})
    mesh.points.push_back(point - centre);
  add_split_cell(mesh);
  return mesh;
}

double smallest_pyramid_corner(const MixedMesh& mesh) {
  double smallest = 1.0;
  for (std::size_t pyramid = 0; pyramid < mesh.cell_count(CellType::pyramid); ++pyramid) {
    const CellShape shape = cell_shape(CellType::pyramid, mesh.points, mesh.cell(CellType::pyramid, pyramid));
    smallest = std::min(smallest, shape.valid() ? shape.min_corner_jacobian : -1.0);
  }
  return smallest;
}

// The volume of the tetrahedra and the pyramids together.
double volume_with_pyramids(const MixedMesh& mesh) {
  double volume = total_volume(mesh);
  for (std::size_t pyramid = 0; pyramid < mesh.cell_count(CellType::pyramid); ++pyramid)
    volume += signed_volume(CellType::pyramid, mesh.points, mesh.cell(CellType::pyramid, pyramid));
  return volume;
}

// Every pyramid passes checkMesh's face-pyramid test.
void expect_face_pyramids_positive(const MixedMesh& mesh) {
  for (std::size_t pyramid = 0; pyramid < mesh.cell_count(CellType::pyramid); ++pyramid)
    EXPECT_EQ(inverted_face_pyramids(CellType::pyramid, mesh.points, mesh.cell(CellType::pyramid, pyramid)),
              0)
        << "pyramid " << pyramid;
}

TEST(SliverRemoval, ASplitPointMovesWithinItsPyramidsWhereNothingElseMendsASliver) {
  MixedMesh fixed = twisted_tip_cell();
  std::size_t above = 0;
  const double before = largest_dihedral(fixed, above);
  ASSERT_GT(before, 177.0);
  const double pyramids_before = smallest_pyramid_corner(fixed);
  ASSERT_GT(pyramids_before, 2e-3 / std::sqrt(2.0));
  SliverOptions options;
  options.search_points = false;
  remove_slivers(fixed, options);
  EXPECT_NEAR(largest_dihedral(fixed, above), before, 1e-9);

  MixedMesh mesh = twisted_tip_cell();
  const SliverReport report = remove_slivers(mesh, SliverOptions{});
  const double after = largest_dihedral(mesh, above);
  const double pyramids_after = smallest_pyramid_corner(mesh);
  std::printf("largest dihedral %.2f -> %.2f deg, smallest pyramid corner %.2e -> %.2e\n", before, after,
              pyramids_before, pyramids_after);
  EXPECT_GE(report.smoothed_points, 1u);
  EXPECT_LT(after, 170.0);
  // The pyramids stay valid and no flatter than the bound (twice the robustness floor).
  EXPECT_GE(pyramids_after, SliverOptions{}.apex_pyramid_quality);
  expect_face_pyramids_positive(mesh);
  // Only the split point moved; the cell's faces are where they were, so its pieces
  // still fill it, each the way round it was.
  const MixedMesh original = twisted_tip_cell();
  for (std::size_t point = 0; point < 8; ++point) EXPECT_EQ(mesh.points[point], original.points[point]);
  EXPECT_TRUE(match_faces(mesh).conforming());
  EXPECT_NEAR(volume_with_pyramids(mesh) / volume_with_pyramids(original), 1.0, 1e-9);
  ASSERT_EQ(mesh.cell_count(CellType::tetrahedron), original.cell_count(CellType::tetrahedron));
  for (std::size_t t = 0; t < mesh.cell_count(CellType::tetrahedron); ++t)
    EXPECT_GT(
        signed_volume(CellType::tetrahedron, mesh.points, mesh.cell(CellType::tetrahedron, t)) *
            signed_volume(CellType::tetrahedron, original.points, original.cell(CellType::tetrahedron, t)),
        0.0);
}

// The outermost layer cell of a random wing (seed 79, wing 167) where its flat tip meets
// the trailing edge, split about its centre: 14 mm long and 0.3 mm wide at one end,
// 1.1 mm at the other, where its outer quad stands on edge, so it twists by some 70
// degrees. The positions where the split point keeps its pyramids above the bound and
// mends the sliver on the quad form a slab that no line towards the sliver's points and
// no axis step from the centre reaches. Metres.
MixedMesh tip_trailing_edge_cell() {
  MixedMesh mesh;
  for (const Vector3& point : {Vector3(0.31980287277855424, 2.258511918933776, 0.27677122045761904),
                               Vector3(0.32012829503455564, 2.258406290615468, 0.27671027049673874),
                               Vector3(0.31897064742273495, 2.2713423058492386, 0.27594397077108),
                               Vector3(0.3187113092959849, 2.271994893533611, 0.2750391531024199),
                               Vector3(0.3200016262406762, 2.2586697762468546, 0.2781552030527231),
                               Vector3(0.32026997774628696, 2.2585196290488847, 0.2781055877016266),
                               Vector3(0.31908838178544197, 2.2723468509772586, 0.27692216165181754),
                               Vector3(0.31881049363712805, 2.27313965603186, 0.2758512559177234)})
    mesh.points.push_back(point);
  // Where the split point stood once the pass had moved it 1.1 mm from the cell's centre
  // towards the narrow end.
  mesh.points.push_back(Vector3(0.319473, 2.264538, 0.276687));
  add_split_cell(mesh);
  return mesh;
}

TEST(SliverRemoval, ASplitPointInAThinSlabIsFoundBySpreadDirections) {
  MixedMesh mesh = tip_trailing_edge_cell();
  std::size_t above = 0;
  const double before = largest_dihedral(mesh, above);
  ASSERT_GT(before, 175.0);
  ASSERT_GT(smallest_pyramid_corner(mesh), SliverOptions{}.apex_pyramid_quality);
  remove_slivers(mesh, SliverOptions{});
  const double after = largest_dihedral(mesh, above);
  const double pyramids = smallest_pyramid_corner(mesh);
  std::printf("largest dihedral %.2f -> %.2f deg, smallest pyramid corner %.2e\n", before, after, pyramids);
  // Lines and axis steps alone stop at 176 degrees with a pyramid at the bound.
  EXPECT_LT(after, 170.0);
  EXPECT_GE(pyramids, SliverOptions{}.apex_pyramid_quality);
  expect_face_pyramids_positive(mesh);
  EXPECT_TRUE(match_faces(mesh).conforming());
}

// A cap over a quad 1 long and 0.2 wide, its apex 1e-4 over the quad's middle (a cap
// lowered to clear the hull), under four tetrahedra up to a point 0.3 above: no
// tetrahedron is above the target, so only the pyramid calls for the apex to move.
MixedMesh flat_cap() {
  MixedMesh mesh;
  mesh.points = {Vector3(0, 0, 0),   Vector3(1, 0, 0),        Vector3(1, 0.2, 0),
                 Vector3(0, 0.2, 0), Vector3(0.5, 0.1, 1e-4), Vector3(0.5, 0.1, 0.3)};
  const std::array<Index, 5> pyramid{0, 1, 2, 3, 4};
  mesh.add_cell(CellType::pyramid, pyramid.data());
  for (Index corner = 0; corner < 4; ++corner) {
    const std::array<Index, 4> tetrahedron{corner, static_cast<Index>((corner + 1) % 4), 4, 5};
    mesh.add_cell(CellType::tetrahedron, tetrahedron.data());
  }
  tag_boundary_walls(mesh);
  return mesh;
}

TEST(SliverRemoval, AFlatCapIsLiftedWithoutMakingSlivers) {
  const SliverOptions defaults;
  MixedMesh fixed = flat_cap();
  std::size_t above = 0;
  const double dihedral_before = largest_dihedral(fixed, above);
  const double pyramid_before = smallest_pyramid_corner(fixed);
  ASSERT_LT(dihedral_before, defaults.target_dihedral_degrees);
  ASSERT_LT(pyramid_before, 1e-3 / std::sqrt(2.0));
  SliverOptions off;
  off.lift_pyramids = false;
  EXPECT_EQ(remove_slivers(fixed, off).lifted_apexes, 0u);
  EXPECT_EQ(fixed.points[4], flat_cap().points[4]);

  MixedMesh mesh = flat_cap();
  const double volume = volume_with_pyramids(mesh);
  const SliverReport report = remove_slivers(mesh, defaults);
  const double pyramid_after = smallest_pyramid_corner(mesh);
  const double dihedral_after = largest_dihedral(mesh, above);
  std::printf("pyramid %.2e -> %.2e, largest dihedral %.2f -> %.2f deg\n", pyramid_before, pyramid_after,
              dihedral_before, dihedral_after);
  EXPECT_EQ(report.lifted_apexes, 1u);
  EXPECT_GE(pyramid_after, defaults.apex_pyramid_quality);
  EXPECT_LE(dihedral_after, defaults.target_dihedral_degrees);
  expect_face_pyramids_positive(mesh);
  for (std::size_t point = 0; point < 6; ++point)
    if (point != 4) {
      EXPECT_EQ(mesh.points[point], flat_cap().points[point]);
    }
  EXPECT_NEAR(volume_with_pyramids(mesh) / volume, 1.0, 1e-9);
  EXPECT_TRUE(match_faces(mesh).conforming());
}

TEST(SliverRemoval, BadOptionsAreRejected) {
  MixedMesh mesh = cube_block(1);
  SliverOptions options;
  options.target_dihedral_degrees = 185.0;
  EXPECT_THROW(remove_slivers(mesh, options), Error);
  options = SliverOptions{};
  options.maximum_ring = 2;
  EXPECT_THROW(remove_slivers(mesh, options), Error);
  options = SliverOptions{};
  options.apex_dihedral_degrees = 60.0;
  EXPECT_THROW(remove_slivers(mesh, options), Error);
  options = SliverOptions{};
  options.apex_pyramid_quality = 0.0;
  EXPECT_THROW(remove_slivers(mesh, options), Error);
}

}  // namespace
}  // namespace mixmesh
