// The direction that sees every face of a fan best (a marching line leaving a surface
// node): of all unit vectors v, the one whose smallest dot product with the faces' unit
// normals is largest.
#pragma once

#include <vector>

#include "mixmesh/mesh/mixed_mesh.hpp"

namespace mixmesh {

// Unit normals in, the unit direction out; a zero vector when no direction has a positive
// dot product with every normal (the normals surround the origin). The direction is the
// point of least norm in the normals' convex hull, scaled to unit length: its dot
// product with every normal is at least that norm, and no direction does better.
Vector3 visible_direction(const std::vector<Vector3>& normals);

}  // namespace mixmesh
