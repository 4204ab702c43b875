// Least-squares rigid fits for the IDW rotation form.
//
//   points        #N reference positions x_j
//   displacements #N displacements u_j (targets x_j + u_j)
//   weights       #N non-negative weights α_j (need not sum to 1)
//
// The rotation minimises Σ α_j |R (x_j − x̄) − (x_j + u_j − x̄ − ū)|² (Kabsch); being fitted
// to positions, it keeps a twist about the surface normal that a fit of normals would
// lose.
#pragma once

#include <Eigen/Core>

#include <vector>

#include "mixmesh/mesh/mixed_mesh.hpp"

namespace mixmesh::deform {

struct RigidFit {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Vector3 centre = Vector3::Zero();       // weighted centroid x̄ of the reference points
  Vector3 translation = Vector3::Zero();  // weighted mean displacement ū
};

enum class FitDimension { spatial, planar };  // planar: rotation about z only

// The weighted centroid and mean displacement only (rotation left at the identity).
RigidFit weighted_means(const std::vector<Vector3>& points, const std::vector<Vector3>& displacements,
                        const Index* indices, const double* weights, int count);

// Weighted Kabsch fit over `count` entries of `indices` into points/displacements.
// Degenerate sets are handled: collinear points give the shortest-arc rotation of
// their line, a single point the identity.
RigidFit fit_rigid_motion(const std::vector<Vector3>& points, const std::vector<Vector3>& displacements,
                          const Index* indices, const double* weights, int count, FitDimension dimension);

// The rotation nearest to M (polar decomposition), det +1.
Eigen::Matrix3d nearest_rotation(const Eigen::Matrix3d& matrix);

// Angle in radians of a rotation matrix.
double rotation_angle(const Eigen::Matrix3d& rotation);

}  // namespace mixmesh::deform
