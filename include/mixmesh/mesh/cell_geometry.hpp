// Signed volume and validity of single cells.
//
// A cell's volume is the sum over its faces of the tetrahedra (face triangle or
// quad-centre fan, cell centre); a cell is valid when that volume, every one of those
// tetrahedra and every corner Jacobian is positive. A total alone is not enough: a
// tangled hex can have a positive volume with a folded corner.
#pragma once

#include <optional>

#include "mixmesh/mesh/mixed_mesh.hpp"

namespace mixmesh {

struct CellShape {
  double volume = 0.0;
  // Smallest corner determinant divided by the product of its edge lengths
  // (the unnormalised scaled Jacobian); 1 for a right-angled corner.
  double min_corner_jacobian = 0.0;
  int negative_subtetrahedra = 0;
  int negative_corners = 0;

  bool valid() const { return volume > 0.0 && negative_subtetrahedra == 0 && negative_corners == 0; }
};

// Verdict's scaled Jacobian of a tetrahedron or a pyramid is min_corner_jacobian times
// this factor (sqrt 2: a regular one's corner then reads 1). check_mesh.py and
// `mixmesh check` print Verdict's value; a floor given in those units is divided by it.
inline constexpr double verdict_corner_factor = 1.41421356237309504880;

// nodes: node_count(type) indices into points.
CellShape cell_shape(CellType type, const std::vector<Vector3>& points, const Index* nodes);

double signed_volume(CellType type, const std::vector<Vector3>& points, const Index* nodes);

// Six times the signed volume of tetrahedron (a, b, c, d).
inline double tetrahedron_volume6(const Vector3& a, const Vector3& b, const Vector3& c, const Vector3& d) {
  return (b - a).cross(c - a).dot(d - a);
}

// Centre of the sphere through the four points; none when they are coplanar.
std::optional<Vector3> tetrahedron_circumcentre(const Vector3& a, const Vector3& b, const Vector3& c,
                                                const Vector3& d);

// The largest dihedral angle of tetrahedron (a, b, c, d), in degrees: near 180 for a
// sliver (four nearly coplanar, well-spread points), at most 90 for a tetrahedron with a
// right-angled corner however it is stretched; 180 for a degenerate one.
double largest_dihedral_degrees(const Vector3& a, const Vector3& b, const Vector3& c, const Vector3& d);

// Area-weighted normal of a face (Newell's method): length = area for a planar face.
Vector3 face_area_vector(const std::vector<Vector3>& points, const Index* nodes, int node_count);

Vector3 cell_centre(CellType type, const std::vector<Vector3>& points, const Index* nodes);

// Faces of the cell whose pyramid on the cell's centroid is not positive, as OpenFOAM's
// checkMesh judges them ("face pyramids incorrectly oriented", a hard error): face centres
// from the triangle fan about the face's vertex average, the centroid from the faces'
// pyramids about the average of the face centres. A very thin cell with warped faces
// (a layer cell a micrometre thick whose nodes a deformation moved apart) can fail this
// while every corner and sub-tetrahedron of cell_shape is positive.
int inverted_face_pyramids(CellType type, const std::vector<Vector3>& points, const Index* nodes);

}  // namespace mixmesh
