// The ARA predictor and the corrector's smoothing (Martineau & Georgala eq. 9–21):
// see ara_stages.hpp.
#include <algorithm>

#include "deform/ara_stages.hpp"
#include "deform/rotation.hpp"

namespace mixmesh::deform::detail {

std::vector<FaceMotion> wall_motion(const DualMesh& dual, const WallFaces& walls,
                                    const BoundaryMotion& boundary) {
  std::vector<FaceMotion> motion(walls.faces.size());
  for (std::size_t wall = 0; wall < walls.faces.size(); ++wall) {
    const std::size_t face = static_cast<std::size_t>(walls.faces[wall]);
    const Index* nodes = dual.boundary_nodes(face);
    const int count = dual.face_size(face);
    FaceMotion& entry = motion[wall];
    entry = {Vector3::Zero(), Vector3::Zero()};
    for (int local = 0; local < count; ++local) {
      const std::size_t node = static_cast<std::size_t>(nodes[local]);
      entry.displacement += boundary.displacement[node];
      entry.rotation += boundary.rotation[node];
    }
    entry.displacement /= count;  // exact for rigid motion: the centre is affine in the nodes
    entry.rotation /= count;
  }
  return motion;
}

CellMotion predict(const AraGeometry& geometry, const NearestFaces& nearest,
                   const std::vector<FaceMotion>& faces, const std::vector<double>& first_distance,
                   const std::vector<double>& second_distance, const AraOptions& options) {
  const std::size_t cells = geometry.dual.cell_count();
  const bool rotate = options.predictor == Predictor::rotation;
  CellMotion motion;
  motion.velocity.resize(cells);
  motion.spin.resize(cells);
  parallel_items(cells, [&](std::size_t cell) {
    const Vector3& x = geometry.centres[cell];
    Vector3 moved[2] = {x, x};
    Vector3 rotation[2] = {Vector3::Zero(), Vector3::Zero()};
    for (int side = 0; side < 2; ++side) {
      const Index wall = nearest.faces[cell][static_cast<std::size_t>(side)];
      if (wall < 0) continue;
      const FaceMotion& face = faces[static_cast<std::size_t>(wall)];
      if (rotate) {
        // x′_n = R_n(x) + Δx_n: rotate about the face centre, then translate with it (eq. 9).
        rotation[side] = face.rotation;
        const Vector3& centre = geometry.wall_centres[static_cast<std::size_t>(wall)];
        moved[side] = detail::rotate(face.rotation, x - centre) + centre + face.displacement;
      } else {
        moved[side] = x + face.displacement;  // the original algorithm's eq. 1
      }
    }
    double beta = 1.0;
    if (nearest.faces[cell][1] >= 0) {
      const double d1 = first_distance[cell];
      const double d2 = second_distance[cell];
      const double alpha = d1 + d2 > 0.0 ? std::clamp(d2 / (d1 + d2), 0.5, 1.0) : 1.0;  // eq. 2
      beta = blend(alpha, options.gamma, options.blend_form);                           // eq. 11
    }
    motion.velocity[cell] = beta * moved[0] + (1.0 - beta) * moved[1] - x;  // eq. 10
    motion.spin[cell] = beta * rotation[0] + (1.0 - beta) * rotation[1];
  });
  return motion;
}

SmoothingOutcome smooth(AraGeometry& geometry, const std::vector<FaceMotion>& faces,
                        const BoundaryMotion& boundary, const AraOptions& options, CellMotion& motion) {
  const std::size_t cells = geometry.dual.cell_count();
  const bool rotate = options.predictor == Predictor::rotation;
  std::vector<Vector3> wall_velocity(faces.size());
  std::vector<Vector3> wall_spin(faces.size(), Vector3::Zero());
  double largest_spin = 0.0;
  for (std::size_t wall = 0; wall < faces.size(); ++wall) {
    wall_velocity[wall] = faces[wall].displacement;
    if (rotate) wall_spin[wall] = faces[wall].rotation;
    largest_spin = std::max(largest_spin, wall_spin[wall].norm());
  }
  const bool point_relaxation = options.solver == Solver::gauss_seidel;
  if (point_relaxation && geometry.colours.empty()) geometry.colours = colour_cells(geometry.dual);
  auto solve = [&](std::vector<Vector3>& values, const std::vector<Vector3>& source, double scale) {
    SolveSettings settings;
    settings.relaxation = options.relaxation;
    settings.tolerance = options.tolerance;
    settings.scale = scale;
    settings.max_iterations = options.max_iterations;
    return point_relaxation ? gauss_seidel(values, source, geometry.stencil, geometry.colours, settings)
                            : conjugate_gradient(values, source, geometry.stencil, settings);
  };
  SmoothingOutcome outcome;
  // The angular velocity first (eq. 21), so that the velocity smoothing can transport
  // neighbour velocities rigidly with it.
  if (rotate) {
    const SolveResult spun =
        solve(motion.spin, smoothing_source(geometry.stencil, wall_spin, {}), largest_spin);
    outcome.spin_iterations = spun.iterations;
  }
  // R − I of every cell, for the transport and the interpolation to nodes.
  Transport transport;
  std::vector<Eigen::Matrix3d> wall_turn;
  if (rotate) {
    motion.turn.resize(cells);
    parallel_items(cells, [&](std::size_t cell) {
      motion.turn[cell] = rotation_matrix(motion.spin[cell]) - Eigen::Matrix3d::Identity();
    });
    if (options.smoothing == Smoothing::rigid_transport) {
      wall_turn.resize(faces.size());
      for (std::size_t wall = 0; wall < faces.size(); ++wall)
        wall_turn[wall] = rotation_matrix(wall_spin[wall]) - Eigen::Matrix3d::Identity();
      transport = {&motion.turn, &wall_turn, &geometry.centres, &geometry.wall_centres};
    }
  }
  outcome.velocity = solve(motion.velocity, smoothing_source(geometry.stencil, wall_velocity, transport),
                           boundary.largest_displacement());
  return outcome;
}

}  // namespace mixmesh::deform::detail
