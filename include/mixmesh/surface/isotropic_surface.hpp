// An all-triangle, roughly isotropic wing surface: the surface of the hybrid
// (prism + tetrahedron) baseline that `mixmesh compare` sets against the mixed mesh
// (Wild Table 1: isotropic surface triangles, O-type prism layers, no wake).
//
//   wing   one triangle patch "wing", role wall, O-type round the section (no wake
//          sheet); a blunt trailing edge is closed (close_trailing_edge) so the
//          section is sharp. The root lies in y = 0 (symmetry_tolerance set).
//   tip    triangulate_planar_cap on the tip section, sharing its nodes.
//
// Construction: the wing is unfolded into a plane, meshed there with CGAL's 2D
// Delaunay refinement at a uniform size, and mapped back. Upper surface point
// (arc length s from the leading edge, span y) -> (x_fold(y) + s, y); a lower surface
// point is placed the same way and then reflected across the fold line x = x_fold(y)
// (the straight line through the root and tip leading edges). Folding a sheet along a
// line is an isometry, so distances in the plane are close to distances on the wing
// (exact for a flat-plate wing with a straight leading edge); the outline (root,
// tip, both sides of the trailing edge) is sampled at the target edge length and never
// split, so the root and tip nodes are exactly those placed on the sections and the
// trailing-edge nodes of both sides are shared.
#pragma once

#include "mixmesh/geometry/planform.hpp"
#include "mixmesh/surface/surface_mesh.hpp"
#include "mixmesh/surface/wing_surface.hpp"

namespace mixmesh {

// The default isotropic edge length of a wing surface: the mean chordwise edge length
// of the mixed surface at mid-span, i.e. the section perimeter at y = semi-span / 2
// divided by options.chordwise_cells.
double default_isotropic_edge_length(const WingDefinition& wing, const SurfaceOptions& options);

// The triangulated wing. edge_length (metres) is the target mean edge length; 0 takes
// default_isotropic_edge_length. Uses options.tip (minimum angle, shape; its
// maximum_edge defaults to the target edge length) and ignores the structured-surface
// keys and the wake. Throws mixmesh::Error for an invalid wing, a negative edge length
// or one so small that the mesh would exceed `maximum_triangles`.
SurfaceMesh generate_isotropic_wing_surface(const WingDefinition& wing, const SurfaceOptions& options,
                                            double edge_length, std::size_t maximum_triangles = 20'000'000);

}  // namespace mixmesh
