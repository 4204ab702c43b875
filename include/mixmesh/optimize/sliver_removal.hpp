// Sliver removal: a post-pass over the tetrahedra of a mixed mesh (the far field's and
// the interface's) that flips away tetrahedra with a large dihedral angle and moves
// free far-field points off them.
//
// A sliver is judged by its largest dihedral angle (near 180 degrees): the measure holds
// for anisotropic tetrahedra, where a stretched but well-aligned tetrahedron has right
// or acute dihedral angles only, while the scaled Jacobian would call it bad.
//
// Operations, each taken only where it raises the smallest value of 180 degrees less
// the largest dihedral angle over the tetrahedra it replaces; of the removals, flips and
// splits of a sliver the one leaving the best worst tetrahedron is taken:
//   - edge removal: the tetrahedra round an interior edge (3 to `maximum_ring`) are
//     replaced by the best triangulation of their ring (3 -> 2, 4 -> 4, ... flips);
//     longer rings by the best fan from one of the ring's points (where that point
//     lies on the edge, three boundary points in a line, only a fan mends it);
//   - face flip: two tetrahedra sharing a face become three round the segment between
//     their apexes (2 -> 3);
//   - edge split: a new point where an interior edge of the sliver passes the opposite
//     edge, or lifted from there towards the ring's apexes, cuts every tetrahedron
//     round the edge in two;
//   - point collapse: a point used by tetrahedra only and on no boundary face merges
//     into a neighbour (the tetrahedra round their edge go, the others take the
//     neighbour in its place);
//   - point smoothing: a point used by tetrahedra only moves to the best of a few trial
//     positions (towards its neighbours' mean, off the opposite face by a part of its
//     edges' mean length, or, where none of those helps, by a few times its height over
//     that face); on a flat boundary (all its boundary faces triangles in one plane) it
//     moves within that plane;
//   - point insertion, for a sliver none of the above mends: a new point at its
//     circumcentre or over one of its faces, coned over a cavity grown until it is
//     star-shaped from the point: the tetrahedra whose circumsphere holds it, or, where
//     no trial point's such cavity helps, only the sliver and the tetrahedron holding
//     the point. A failed insertion is tried again in later passes on a tetrahedron
//     flatter than halfway from the target to 180 degrees;
//   - a searched point move, last, for a sliver none of the above mends: lines towards
//     the sliver's other points, then axis steps, for its free points and, above
//     `apex_dihedral_degrees`, for those that are the apex of pyramids and otherwise
//     used by tetrahedra only (an interface cell's split point, a cap's apex), while
//     every such pyramid stays valid and no flatter than `apex_pyramid_quality`;
//   - a pyramid lift, after the passes: such an apex whose flattest pyramid is under
//     `apex_pyramid_quality` moves to raise it, no tetrahedron round it falling below
//     the target (or below itself).
// Faces shared with a pyramid, prism or hexahedron and boundary faces are never
// removed, and no point of them moves off its plane but an apex, whose pyramids move
// with it, so the mesh stays conforming with every face and marker it had.
#pragma once

#include <cstddef>

#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/mesh/mixed_mesh.hpp"

namespace mixmesh {

struct SliverOptions {
  // Tetrahedra whose largest dihedral angle is above this are worked on.
  double target_dihedral_degrees = 160.0;
  int passes = 12;
  int maximum_ring = 7;  // the largest edge ring triangulated at will (tetrahedra round the edge)
  bool smooth_points = true;
  // Where nothing else mends a tetrahedron above the target, its points are searched
  // for a better position (lines towards the sliver's other points, then axis steps):
  // free points, and points of a flat boundary within its plane. For a tetrahedron above
  // apex_dihedral_degrees (the robustness suite's bound on the share of flat tetrahedra)
  // so are split points and cap apexes (points that are apexes of pyramids and otherwise
  // used by tetrahedra only), whose pyramids must stay valid (corners, sub-tetrahedra
  // and checkMesh's face pyramids) with a scaled corner Jacobian of at least
  // apex_pyramid_quality, or their own where that is lower: twice the suite's floor of
  // 1e-3 in Verdict's units.
  bool search_points = true;
  double apex_dihedral_degrees = 170.0;
  double apex_pyramid_quality = 2e-3 / verdict_corner_factor;
  bool insert_points = true;
  // After the passes, every such apex whose flattest pyramid lies under
  // apex_pyramid_quality (a cap lowered to clear the hull, the split point of a cell on a
  // warped base) is searched for a position that raises that pyramid, while no
  // tetrahedron round it falls below the target, or below itself where it already is.
  bool lift_pyramids = true;
};

struct SliverReport {
  std::size_t tetrahedra_before = 0, tetrahedra_after = 0;
  double largest_dihedral_before = 0.0, largest_dihedral_after = 0.0;  // degrees
  std::size_t above_target_before = 0, above_target_after = 0;
  // Operations done; every edge split appends one point to the mesh.
  // Every point collapse removes one point (the mesh's points are renumbered).
  std::size_t edge_removals = 0, face_flips = 0, edge_splits = 0, point_collapses = 0, smoothed_points = 0,
              point_insertions = 0;
  std::size_t lifted_apexes = 0;  // apexes moved to raise their flattest pyramid
  int passes = 0;
};

SliverReport remove_slivers(MixedMesh& mesh, const SliverOptions& options = {});

}  // namespace mixmesh
