// Preconditioning of the volume triangulation (Wild §II.E, method.md §5): one global
// linear map of the boundary point set that removes the wing sweep and the mean
// anisotropy of the boundary triangles before the Delaunay step; the tetrahedra are
// mapped back with the inverse afterwards (a linear map keeps the connectivity, and
// with a positive determinant the orientation).
//
//   shear   S = [[1, sin φ, 0], [0, 1, 0], [0, 0, 1]] (Wild eq. 14), P₁ = S⁻¹ P (eq. 13);
//           φ from the options, or estimated from the leading-edge slope of the points
//   affine  Ā = Σ_i A_i / Σ_j |x_j − x_c|² over the triangles (eqs. 16–17): each
//           triangle's node covariance normalised to unit trace, so large far-field
//           triangles do not mask the small anisotropic ones
//   forward P̄ = F P with F = Ā_map · S⁻¹ (eq. 18), Ā_map = Ā^{-1/2} (whitening: the mean
//           ellipsoid becomes a sphere) or Ā⁻¹ (the paper's eq. 15), scaled to det F = 1
//           so sizes keep their scale
#pragma once

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <vector>

#include "mixmesh/mesh/mixed_mesh.hpp"

namespace mixmesh {

enum class AffineMap {
  none,
  whitening,  // Ā^{-1/2}
  inverse,    // Ā⁻¹, as printed in Wild eq. (15)
};

struct PreconditionOptions {
  bool shear = true;
  // Sweep angle in degrees; NaN: estimated from the points (Preconditioning::sweep_degrees).
  double sweep_degrees = std::numeric_limits<double>::quiet_NaN();
  AffineMap affine = AffineMap::whitening;
};

struct Preconditioning {
  double sweep_degrees = 0.0;
  Eigen::Matrix3d shear = Eigen::Matrix3d::Identity();        // S
  Eigen::Matrix3d mean_affine = Eigen::Matrix3d::Identity();  // Ā (unit trace)
  Eigen::Matrix3d forward = Eigen::Matrix3d::Identity();      // F, det F = 1
  Eigen::Matrix3d backward = Eigen::Matrix3d::Identity();     // F⁻¹
};

// The sweep φ whose shear removes the leading-edge slope: the points are cut into ten
// span stations in y, the smallest x of each is fitted by x = a + b y, φ = asin(b).
// Returns 0 when the points span no y range.
double estimate_sweep_degrees(const std::vector<Vector3>& points);

// Throws mixmesh::Error when no triangle has positive area or Ā is singular (all
// triangles in one plane).
Preconditioning precondition(const std::vector<Vector3>& points,
                             const std::vector<std::array<Index, 3>>& triangles,
                             const PreconditionOptions& options = {});

std::vector<Vector3> transform_points(const Eigen::Matrix3d& map, const std::vector<Vector3>& points);

// Writes a triangulated surface as legacy ASCII VTK (for --dump-stages), atomically.
void dump_surface(const std::filesystem::path& path, const std::vector<Vector3>& points,
                  const std::vector<std::array<Index, 3>>& triangles);

}  // namespace mixmesh
