// Rotation vectors and small helpers shared by the framework and the methods.
// Internal to the deform module.
#pragma once

#include <vector>

#include "mixmesh/deform/deform.hpp"

namespace mixmesh::deform::detail {

// The rotation by rotation vector `rotation` (axis × angle, radians) applied to `vector`
// (Rodrigues' formula).
Vector3 rotate(const Vector3& rotation, const Vector3& vector);

// The rotation matrix of a rotation vector.
Eigen::Matrix3d rotation_matrix(const Vector3& rotation);

// Rotation vector of a rotation matrix.
Vector3 rotation_vector(const Eigen::Matrix3d& rotation);

// Least-squares rotation taking the offsets `before` to `after` (Kabsch), each offset
// weighted by 1/|before|² (by its direction, not its length; rotation.cpp says why);
// when `planar`, the rotation about z only. Zero for fewer than two usable offsets.
Vector3 fit_rotation(const std::vector<Vector3>& before, const std::vector<Vector3>& after, bool planar);

// Moves sliding nodes of `moved` back into their symmetry plane through their position
// in `original` (removes the normal part of their displacement).
void project_sliding(const BoundaryMotion& boundary, const std::vector<Vector3>& original,
                     std::vector<Vector3>& moved);
// The same for one node's position (nodes that do not slide keep it).
void project_sliding(const BoundaryMotion& boundary, const std::vector<Vector3>& original, std::size_t node,
                     Vector3& position);

// Keeps interior nodes of `moved` on their side of every symmetry plane: a step of
// length d towards a plane from distance s becomes one to s·exp(−d/s), the same to first
// order in d/s and never through the plane (rotation.cpp says why). Nodes on a plane and
// prescribed nodes are left as they are.
void keep_off_sliding_planes(const BoundaryMotion& boundary, const std::vector<Vector3>& original,
                             std::vector<Vector3>& moved);

}  // namespace mixmesh::deform::detail
