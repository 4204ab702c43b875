// Parts of the far-field stage: the size field, the outer boundary, the symmetry
// plane, the anisotropic layer points, the TetGen call and the boundary faces.
#pragma once

#include <array>
#include <vector>

#include "mixmesh/farfield/farfield.hpp"

namespace mixmesh::farfield_detail {

using Triangle = std::array<Index, 3>;

// Target edge length: min(maximum, size_k + gradient · |p − source_k|) over the
// sources (hull nodes with their local edge length), i.e. linear growth away from the
// hull capped at the far-field size.
struct SizeField {
  std::vector<Vector3> sources;
  std::vector<double> sizes;
  double gradient = 0.25;
  double maximum = 1.0;
  double operator()(const Vector3& point) const;
};

// Points are appended to `points`; triangles use indices into it.
struct OuterBoundary {
  std::vector<Triangle> triangles;
  std::vector<Index> rim;  // closed loop on the symmetry plane (half boundaries only)
};

// A sphere or box of half-width `radius` about `centre`, with target edge length
// `size`; `half` keeps only y ≥ centre.y and leaves the face on the plane open.
OuterBoundary outer_boundary(FarFieldShape shape, const Vector3& centre, double radius, double size,
                             bool half, std::vector<Vector3>& points);

// Graded triangulation of the plane y = plane_y between the rim (outer loop) and the
// footprint edges (holes), through the extra points (anisotropic layer points on the
// plane). New points are appended to `points`. Throws mixmesh::Error when a footprint
// edge is lost (the footprint crosses itself or the rim).
std::vector<Triangle> symmetry_plane(double plane_y, const std::vector<Index>& rim,
                                     const std::vector<std::array<Index, 2>>& footprint,
                                     const std::vector<Vector3>& extra_points, const SizeField& size,
                                     double minimum_angle_degrees, std::vector<Vector3>& points);

// Anisotropic layer points grown from the hull nodes (see farfield.hpp), each column
// until its spacing reaches `isotropic_size` (per point of input.points: the isotropic
// size the far field has at a hull node). Points on the symmetry plane (from footprint
// nodes) are returned separately for the plane triangulation.
struct LayerPoints {
  std::vector<Vector3> volume;
  std::vector<Vector3> plane;
};
LayerPoints layer_points(const FarFieldInput& input, const std::vector<std::array<Index, 2>>& footprint,
                         bool symmetric, const std::vector<double>& isotropic_size,
                         const FarFieldOptions& options);

// The candidates farther than ratio × size(candidate) from every one of `near`.
std::vector<Vector3> points_beyond(const std::vector<Vector3>& candidates, const std::vector<Vector3>& near,
                                   const SizeField& size, double ratio);

// The candidates whose distance to the hull surface is at least ratio × their
// distance to the nearest hull node. A point that hugs the middle of a hull triangle
// (relative to the triangle's size) can only make flat tetrahedra with it.
std::vector<Vector3> points_off_hull(const std::vector<Vector3>& candidates,
                                     const std::vector<Vector3>& points, const std::vector<Triangle>& hull,
                                     double ratio);

struct TetgenInput {
  std::vector<Vector3> points;      // boundary points, then isolated volume points
  std::vector<double> sizes;        // one per point (-m)
  std::vector<Triangle> triangles;  // the closed boundary
  std::vector<Vector3> holes;
  double radius_edge_ratio = 1.5;
  double flip_dihedral = FarFieldOptions{}.flip_dihedral;  // TetGen flips tetrahedra above this
  bool quality = true;              // -q and -m; off, TetGen only recovers the boundary
  unsigned time_limit_seconds = 0;  // 0: none
};

// What TetGen's intersection test (-d) found: how many boundary triangles intersect
// and the centre of each (the first first).
struct IntersectionFound {
  std::size_t count = 0;
  Vector3 first = Vector3::Zero();
  std::vector<Vector3> centres;
};

struct TetgenOutput {
  std::vector<Vector3> points;  // the input points first, in order, then TetGen's
  std::vector<std::array<Index, 4>> tetrahedra;
};

// Throws mixmesh::Error naming the stage and a location for an unusable boundary,
// HullIntersectionError for a self-intersecting one.
TetgenOutput run_tetgen(const TetgenInput& input);

// Whether most tetrahedra have negative volume as numbered (TetGen's convention), so
// the whole list is to be turned to VTK's positive orientation.
bool negative_orientation(const std::vector<Vector3>& points,
                          const std::vector<std::array<Index, 4>>& tetrahedra);

// How many tetrahedra have zero volume or the orientation opposite to the majority
// (`negative`: negative_orientation of the same list); `first`, when given, receives the
// centre of the first of them.
std::size_t flat_tetrahedra(const std::vector<Vector3>& points,
                            const std::vector<std::array<Index, 4>>& tetrahedra, bool negative,
                            Vector3* first = nullptr);

// The tetrahedra's boundary faces (faces used by one tetrahedron; `global`: the global
// number of every TetGen point) must be the input triangles, each once: the hull's,
// which the layer cells close and so get no face, and the symmetry plane's and the
// outer boundary's, added with their markers (hull_faces.cpp).
void add_boundary_faces(const std::vector<Index>& global, const std::vector<Triangle>& hull,
                        const std::vector<Triangle>& plane, const std::vector<Triangle>& outer,
                        const FarFieldOptions& options, MixedMesh& mesh);

}  // namespace mixmesh::farfield_detail
