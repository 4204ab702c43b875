// The motion-dependent stages of the ARA predictor–corrector (Martineau & Georgala
// §4.3), each a function on the geometry of the undeformed mesh (AraGeometry) and the
// motion: the rigid-body prediction, the smoothing on the dual mesh, the interpolation
// to nodes and the negative-volume repair. AraMethod::move runs them in this order.
// Internal to the deform module.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "deform/ara_geometry.hpp"
#include "deform/ara_smoothing.hpp"
#include "mixmesh/deform/ara.hpp"

namespace mixmesh::deform::detail {

// Motion of a wall face: its centre's displacement and its rotation (the centre itself is
// AraGeometry::wall_centres).
struct FaceMotion {
  Vector3 displacement;
  Vector3 rotation;
};
std::vector<FaceMotion> wall_motion(const DualMesh& dual, const WallFaces& walls,
                                    const BoundaryMotion& boundary);

// The motion of every cell of the dual mesh.
struct CellMotion {
  std::vector<Vector3> velocity;      // u = x′ − x
  std::vector<Vector3> spin;          // w, rotation vector of the cell
  std::vector<Eigen::Matrix3d> turn;  // R − I from w; empty without the rotation predictor
};

// Rigid-body initialisation (eq. 9–11): every cell moves with the nearest face of its
// nearest boundary, blended with that of the second by distance (d₁, d₂).
CellMotion predict(const AraGeometry& geometry, const NearestFaces& nearest,
                   const std::vector<FaceMotion>& faces, const std::vector<double>& first_distance,
                   const std::vector<double>& second_distance, const AraOptions& options);

// Smoothing of w and u on the dual mesh (eq. 12–21), the prediction as first guess; fills
// `motion.turn`. Builds the Gauss–Seidel colours into `geometry` when first needed.
struct SmoothingOutcome {
  int spin_iterations = 0;
  SolveResult velocity;
};
SmoothingOutcome smooth(AraGeometry& geometry, const std::vector<FaceMotion>& faces,
                        const BoundaryMotion& boundary, const AraOptions& options, CellMotion& motion);

// Interpolation to nodes (eq. 22–26); prescribed nodes take their own motion and
// sliding nodes stay in their plane.
std::vector<Vector3> interpolate_to_nodes(const AraGeometry& geometry, const std::vector<Vector3>& points,
                                          const BoundaryMotion& boundary, const CellMotion& motion);

// Negative-volume repair (eq. 27), up to `passes` passes over the nodes of inverted
// cells; `moved` ends as the pass with the fewest inverted cells.
struct RepairOutcome {
  std::size_t inverted_after_interpolation = 0;
  std::size_t inverted_after_repair = 0;
  int passes = 0;
};
RepairOutcome repair_inverted_cells(const AraGeometry& geometry, const std::vector<Vector3>& points,
                                    const BoundaryMotion& boundary, const CellMotion& motion, int passes,
                                    std::vector<Vector3>& moved);

}  // namespace mixmesh::deform::detail
