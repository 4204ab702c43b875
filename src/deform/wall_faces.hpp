// Wall faces of the ARA method and the search for the two nearest boundaries of every
// cell centre (Martineau & Georgala §4.3.1). Internal to the deform module.
#pragma once

#include <vector>

#include "deform/dual_mesh.hpp"
#include "mixmesh/deform/ara.hpp"

namespace mixmesh::deform::detail {

// The boundary faces that are walls (fixed or moving markers), grouped into
// boundaries: connected sets of wall faces (sharing a node).
struct WallFaces {
  std::vector<Index> faces;   // indices into the dual mesh's boundary faces
  std::vector<int> boundary;  // boundary id of each wall face
  int boundary_count = 0;
};
WallFaces wall_faces(const DualMesh& dual, const std::vector<MarkerRole>& marker_roles);

// Exact distance from `point` to a boundary face (triangle, quad as two triangles,
// or segment), given its node positions.
double point_face_distance(const Vector3& point, const Vector3* corners, int corner_count);

// Nearest wall face on each of the two nearest boundaries of every cell centre:
// k-d trees on the face centres of each boundary give `candidates` faces, the exact
// distance chooses among them.
NearestFaces find_nearest_faces(const DualMesh& dual, const WallFaces& walls,
                                const std::vector<Vector3>& centres, const std::vector<Vector3>& points,
                                int candidates);

// d₁, d₂ of every cell centre to its cached faces (d₂ = +inf without a second face).
void nearest_distances(const DualMesh& dual, const WallFaces& walls, const NearestFaces& nearest,
                       const std::vector<Vector3>& centres, const std::vector<Vector3>& points,
                       std::vector<double>& first, std::vector<double>& second);

}  // namespace mixmesh::deform::detail
