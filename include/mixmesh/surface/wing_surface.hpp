// The mixed surface mesh of a wing: structured quads on the wing, a structured C-type
// wake sheet, triangles on the tip cap (see surface_mesh.hpp for the conventions).
//
//   wing   (chordwise_cells + 1) x (spanwise_cells + 1) nodes; i from the lower
//          trailing edge round the leading edge (i = leading_edge_i) to the upper
//          trailing edge, Vinokur clustering at both ends of each surface; j from the
//          root (y = 0) to the tip, clustered at both ends. A sharp trailing edge is
//          one node (i = 0 and i = ni - 1 share indices).
//   base   only for a blunt trailing edge kept as a base face: i from the upper to the
//          lower trailing edge (base_cells + 1 nodes, even count of cells), j as the wing.
//   wake   i downstream from the trailing edge (the base's middle line when there is a
//          base) to the plane x = (most downstream trailing edge) + length * root chord,
//          in the plane of each trailing-edge node (z constant along i); j as the wing.
//   tip    CGAL constrained Delaunay triangulation of the tip section in its plane
//          y = semi-span, refined to a minimum angle; every tip-section node of the wing
//          (and base) is a node of the cap, no node is added on its outline. With
//          TipCapOptions::rounded the interior nodes are lifted outward (y > semi-span).
#pragma once

#include <array>
#include <optional>

#include "mixmesh/geometry/planform.hpp"
#include "mixmesh/surface/surface_mesh.hpp"

namespace mixmesh {

struct WakeOptions {
  bool enabled = true;
  double length = 10.0;        // in root chords, behind the most downstream trailing edge
  // Fraction of the local chord; none: the wing's trailing-edge spacing.
  std::optional<double> first_spacing;
  double growth = 1.2;         // cell-to-cell ratio at the root line
};

struct TipCapOptions {
  double minimum_angle_degrees = 20.0;  // refinement shape bound (at most 20.7 for termination)
  double maximum_edge = 0.0;            // metres; 0: the longest edge of the tip section
  // Rounded tip: interior cap nodes are lifted outward onto half-circles spanning the
  // local section thickness (a half body of revolution about the camber line), so the
  // cap meets the wing surfaces tangentially. Flat (in the tip plane) otherwise.
  bool rounded = false;
};

struct SurfaceOptions {
  int chordwise_cells = 200;  // around the section, lower + upper
  int spanwise_cells = 80;
  double leading_edge_spacing = 0.001;   // arc length, fraction of the local chord
  double trailing_edge_spacing = 0.002;  // arc length, fraction of the local chord
  double root_spacing = 0.01;            // fraction of the semi-span
  double tip_spacing = 0.004;            // fraction of the semi-span
  int base_cells = 4;                    // across a blunt base (even)
  // Fewer faces across a base (by twos, down to 2) while its narrowest would be more than
  // this many times shorter than the spanwise faces beside it: the split layer's
  // pyramids there have a scaled Jacobian of about the face's width over the spanwise
  // face's length (docs/surface.md). 0: always base_cells.
  double base_face_aspect = 500.0;
  WakeOptions wake;
  TipCapOptions tip;
};

// Throws mixmesh::Error for options that cannot give a mesh (too few cells, spacings
// that do not fit) or a wing that fails validate_wing.
SurfaceMesh generate_wing_surface(const WingDefinition& wing, const SurfaceOptions& options);

// Triangulates a planar closed outline in the plane y = y_plane: outline holds point
// indices into `points` in order (the last connects back to the first), all with
// y = y_plane. New interior points are appended to `points`. Triangles come out with
// their right-hand normal along +y when `normal_positive_y`, else -y. Each of
// `inner_edges` (pairs of points in the plane, an end either an outline point or a new
// one) becomes an edge of the triangulation, or a chain of edges along it.
std::vector<Index> triangulate_planar_cap(std::vector<Vector3>& points, const std::vector<Index>& outline,
                                          const TipCapOptions& options, bool normal_positive_y,
                                          const std::vector<std::array<Vector3, 2>>& inner_edges = {});

// Lifts points[first_interior ...] off the outline's plane (towards +y or -y) by
// sqrt(h^2 - (z - c)^2), where c and h are the centre and half-height of the outline's
// vertical extent at the point's x.
void round_cap(std::vector<Vector3>& points, const std::vector<Index>& outline, std::size_t first_interior,
               bool towards_positive_y);

}  // namespace mixmesh
