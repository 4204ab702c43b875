// The ARA predictor–corrector (Martineau & Georgala §4.3): distances, rigid-body
// initialisation, dual-mesh smoothing, interpolation to nodes, negative-volume repair.
// Everything that depends only on the undeformed mesh is kept between calls
// (AraGeometry), as are the nearest faces, so a repeat deformation redoes only the
// motion-dependent work.
#include "mixmesh/deform/ara.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>

#include "deform/ara_geometry.hpp"
#include "deform/ara_smoothing.hpp"
#include "deform/ara_stages.hpp"
#include "deform/dual_mesh.hpp"
#include "deform/rotation.hpp"
#include "deform/wall_faces.hpp"
#include "mixmesh/core/error.hpp"

namespace mixmesh::deform {

namespace {

using detail::DualMesh;
using detail::WallFaces;

// Pseudo-Laplacian weights of the cells around one node (eq. 24–26):
// ω_j = 1 + λᵀ(x_j − x_i), λ = −I⁻¹ R, R = Σ (x_j − x_i), I = Σ (x_j − x_i)(x_j − x_i)ᵀ;
// clipped to [0, 2] as in Holmes & Connell so no cell counts negatively.
void pseudo_laplacian_weights(const Vector3& node, const Index* cells, std::size_t count,
                              const std::vector<Vector3>& centres, bool planar, double* weights) {
  Vector3 first = Vector3::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (std::size_t slot = 0; slot < count; ++slot) {
    const Vector3 offset = centres[static_cast<std::size_t>(cells[slot])] - node;
    first += offset;
    second += offset * offset.transpose();
  }
  // The directions the weights are fitted in: all three, but not one in which the
  // centres do not spread (their covariance has no extent there). In such a direction
  // every centre lies at the same offset h, λ's component there is −1/h and every weight
  // is 1 − 1 up to rounding: noise, clipped to [0, 2]. That is every node of a
  // one-cell-thick quasi-2D mesh (its cells' centres lie half a cell from both planes)
  // and a sliding node whose cells are one equal-width row beside the plane; their
  // weights then come from the directions the centres do spread in, as in 2D. "No
  // extent" is a spread under 1/1000 of the widest one (eigenvalues, squared lengths,
  // under 1e-6 of the largest): a fit along so thin a spread is as ill-posed as none.
  Eigen::Matrix3d kept = Eigen::Matrix3d::Identity();
  if (planar) {  // no z extent: solve the 2×2 system
    kept(2, 2) = 0.0;
  } else if (count > 0) {
    const Eigen::Matrix3d spread = second - first * first.transpose() / static_cast<double>(count);
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> axes;
    axes.computeDirect(spread);
    const double largest = axes.eigenvalues().maxCoeff();
    for (int axis = 0; axis < 3; ++axis)
      if (!(axes.eigenvalues()(axis) > 1e-6 * largest))
        kept -= axes.eigenvectors().col(axis) * axes.eigenvectors().col(axis).transpose();
  }
  if (planar) {
    second(2, 2) = 1.0;
    second(0, 2) = second(2, 0) = second(1, 2) = second(2, 1) = 0.0;
    first.z() = 0.0;
  } else {
    // The dropped directions get the kept ones' scale, so that the solver's pivot test
    // does not take a mesh of tiny cells for a singular one; λ has no part in them.
    second = kept * second * kept + (second.trace() / 3.0) * (Eigen::Matrix3d::Identity() - kept);
    first = kept * first;
  }
  Vector3 lambda = Vector3::Zero();
  const Eigen::FullPivLU<Eigen::Matrix3d> solver(second);
  if (solver.isInvertible()) lambda = -solver.solve(first);
  for (std::size_t slot = 0; slot < count; ++slot) {
    const Vector3 offset = kept * (centres[static_cast<std::size_t>(cells[slot])] - node);
    weights[slot] = std::clamp(1.0 + lambda.dot(offset), 0.0, 2.0);
  }
}

}  // namespace

namespace {

std::shared_ptr<detail::AraGeometry> prepare_geometry(const MixedMesh& mesh,
                                                      const std::vector<MarkerRole>& marker_roles,
                                                      std::uint64_t connectivity, std::uint64_t point_bits,
                                                      const DualMesh* offered_dual) {
  auto geometry = std::make_shared<detail::AraGeometry>();
  detail::AraGeometry& entry = *geometry;
  entry.connectivity = connectivity;
  entry.points = point_bits;
  entry.marker_roles = marker_roles;
  entry.dual = offered_dual ? *offered_dual : detail::build_dual_mesh(mesh);
  entry.walls = detail::wall_faces(entry.dual, marker_roles);
  if (entry.walls.faces.empty()) throw Error("ara: the mesh has no wall boundary (every marker slides)");
  entry.nearest_key = detail::combine_hash(connectivity, entry.walls.faces);
  const DualMesh& dual = entry.dual;
  const std::vector<Vector3>& points = mesh.points;
  const std::size_t cells = dual.cell_count();

  entry.centres.resize(cells);
  std::vector<double> volume(cells);
  detail::parallel_items(cells, [&](std::size_t cell) {
    entry.centres[cell] = detail::cell_centre(dual, cell, points);
    volume[cell] = std::abs(detail::cell_measure(dual, cell, points));
  });
  entry.wall_centres.resize(entry.walls.faces.size());
  for (std::size_t wall = 0; wall < entry.walls.faces.size(); ++wall)
    entry.wall_centres[wall] =
        detail::face_centre(dual, static_cast<std::size_t>(entry.walls.faces[wall]), points);

  // Baker's diffusivity τ = 1 + (V_max − V_min)/V of the undeformed mesh, eq. 13.
  const auto [smallest, largest] = std::minmax_element(volume.begin(), volume.end());
  std::vector<double> diffusivity(cells);
  for (std::size_t cell = 0; cell < cells; ++cell)
    diffusivity[cell] = 1.0 + (*largest - *smallest) / std::max(volume[cell], 1e-300);
  entry.stencil = detail::build_smoothing_stencil(dual, entry.walls, entry.centres, entry.wall_centres,
                                                  diffusivity, points);

  entry.node_weights.resize(dual.point_cells.size());
  detail::parallel_items(points.size(), [&](std::size_t node) {
    const std::size_t begin = dual.point_cell_offsets[node];
    const std::size_t end = dual.point_cell_offsets[node + 1];
    if (begin == end) return;
    pseudo_laplacian_weights(points[node], dual.point_cells.data() + begin, end - begin, entry.centres,
                             dual.planar, entry.node_weights.data() + begin);
  });
  return geometry;
}

}  // namespace

bool AraMethod::prepare(const MixedMesh& mesh, const BoundaryMotion& boundary, const Log& log) {
  const std::uint64_t connectivity = detail::connectivity_hash(mesh);
  const std::uint64_t point_bits = detail::points_hash(mesh.points);
  report_.geometry_cached = geometry_ && geometry_->connectivity == connectivity &&
                            geometry_->points == point_bits &&
                            geometry_->marker_roles == boundary.marker_roles;
  // A cache file of nearest faces only (written with cache_geometry off, or by an older
  // mixmesh) gets the geometry added once it is built, so the next run reads it.
  bool add_geometry_to_file = false;
  if (report_.geometry_cached) return add_geometry_to_file;
  geometry_.reset();  // release the old one before building the new one
  if (options_.cache_geometry && !options_.cache_file.empty() &&
      std::filesystem::exists(options_.cache_file)) {
    detail::StoredGeometry stored =
        detail::read_ara_geometry(options_.cache_file, connectivity, point_bits, boundary.marker_roles);
    geometry_ = std::move(stored.geometry);
    report_.geometry_from_file = geometry_ != nullptr;
    add_geometry_to_file = stored.faces_only;
    log.detail("ara: geometry " + (geometry_ ? "read from " + options_.cache_file.string()
                                             : "rebuilt (" + stored.why_not + ")"));
  }
  if (!geometry_)
    geometry_ = prepare_geometry(mesh, boundary.marker_roles, connectivity, point_bits, offered_dual_);
  return add_geometry_to_file;
}

void AraMethod::find_nearest(const std::vector<Vector3>& points, bool add_geometry_to_file, const Log& log) {
  const detail::AraGeometry& geometry = *geometry_;
  const std::size_t cells = geometry.dual.cell_count();
  auto fits = [&](const NearestFaces& nearest) {
    return nearest.mesh_hash == geometry.nearest_key && nearest.point_count == points.size() &&
           nearest.cell_count == cells && nearest.wall_face_count == geometry.walls.faces.size() &&
           nearest.faces.size() == cells;
  };
  const bool from_file =
      !fits(nearest_) && !options_.cache_file.empty() && std::filesystem::exists(options_.cache_file);
  if (from_file) {
    NearestFaces stored = read_nearest_faces(options_.cache_file);
    if (!fits(stored)) {
      std::ostringstream message;
      message << options_.cache_file.string() << ": nearest-face cache made for another mesh ("
              << stored.point_count << " points, " << stored.cell_count << " cells, "
              << stored.wall_face_count << " wall faces, hash " << std::hex << stored.mesh_hash << std::dec
              << "; this mesh has " << points.size() << ", " << cells << ", " << geometry.walls.faces.size()
              << ", hash " << std::hex << geometry.nearest_key << "); delete it to search again";
      throw Error(message.str());
    }
    nearest_ = std::move(stored);
    log.detail("ara: nearest faces read from " + options_.cache_file.string());
    if (add_geometry_to_file) {
      // Only a saving for the next run: a cache file that cannot be rewritten (a
      // read-only folder) leaves this run as it was.
      try {
        detail::write_ara_cache(nearest_, geometry, options_.cache_file);
        log.detail("ara: geometry added to " + options_.cache_file.string());
      } catch (const Error& error) {
        log.warning(std::string("ara: geometry not added to the cache: ") + error.what());
      }
    }
  }
  report_.cache_used = fits(nearest_);
  if (report_.cache_used) return;
  nearest_ = detail::find_nearest_faces(geometry.dual, geometry.walls, geometry.centres, points,
                                        options_.candidates);
  nearest_.point_count = points.size();
  nearest_.mesh_hash = geometry.nearest_key;
  if (options_.cache_file.empty()) return;
  if (options_.cache_geometry)
    detail::write_ara_cache(nearest_, geometry, options_.cache_file);
  else
    write_nearest_faces(nearest_, options_.cache_file);
}

std::vector<Vector3> AraMethod::move(const MixedMesh& mesh, const BoundaryMotion& boundary, const Log& log) {
  report_ = {};
  Stopwatch total_clock;
  Stopwatch stage_clock;
  if (boundary.roles.size() != mesh.points.size() || boundary.displacement.size() != mesh.points.size() ||
      boundary.rotation.size() != mesh.points.size())
    throw Error("ara: boundary motion does not match the mesh (" + std::to_string(boundary.roles.size()) +
                " entries for " + std::to_string(mesh.points.size()) + " points)");
  const bool add_geometry_to_file = prepare(mesh, boundary, log);
  detail::AraGeometry& geometry = *geometry_;
  const std::vector<Vector3>& points = mesh.points;
  report_.setup_seconds = stage_clock.seconds();

  // 1. Distance metrics: nearest faces from memory or the cache file when they were found
  // on a mesh with this connectivity and these wall faces.
  stage_clock = Stopwatch();
  find_nearest(points, add_geometry_to_file, log);
  std::vector<double> first_distance;
  std::vector<double> second_distance;
  detail::nearest_distances(geometry.dual, geometry.walls, nearest_, geometry.centres, points, first_distance,
                            second_distance);
  report_.distance_seconds = stage_clock.seconds();

  // 2. Rigid-body initialisation (eq. 9–11).
  stage_clock = Stopwatch();
  const std::vector<detail::FaceMotion> faces = detail::wall_motion(geometry.dual, geometry.walls, boundary);
  detail::CellMotion motion =
      detail::predict(geometry, nearest_, faces, first_distance, second_distance, options_);
  report_.predictor_seconds = stage_clock.seconds();

  // 3. Smoothing of w and u on the dual mesh (eq. 12–21), the predictor as first guess.
  stage_clock = Stopwatch();
  const detail::SmoothingOutcome smoothed = detail::smooth(geometry, faces, boundary, options_, motion);
  report_.spin_iterations = smoothed.spin_iterations;
  report_.smoothing_iterations = smoothed.velocity.iterations;
  report_.smoothing_residual = smoothed.velocity.residual;
  report_.smoothing_seconds = stage_clock.seconds();

  // 4. Interpolation to nodes (eq. 22–26).
  stage_clock = Stopwatch();
  std::vector<Vector3> result = detail::interpolate_to_nodes(geometry, points, boundary, motion);
  report_.interpolation_seconds = stage_clock.seconds();

  // 5. Negative-volume repair (eq. 27), up to repair_passes passes.
  stage_clock = Stopwatch();
  const detail::RepairOutcome repaired =
      detail::repair_inverted_cells(geometry, points, boundary, motion, options_.repair_passes, result);
  report_.inverted_after_interpolation = repaired.inverted_after_interpolation;
  report_.repair_passes = repaired.passes;
  report_.inverted_after_repair = repaired.inverted_after_repair;
  report_.repair_seconds = stage_clock.seconds();
  report_.total_seconds = total_clock.seconds();
  log.detail(summary());
  return result;
}

std::string AraMethod::summary() const {
  std::ostringstream summary;
  summary << "ara: " << geometry_->dual.cell_count() << " cells, " << geometry_->walls.boundary_count
          << " boundaries, distances " << (report_.cache_used ? "(cached) " : "") << report_.distance_seconds
          << " s, smoothing "
          << (options_.solver == Solver::gauss_seidel ? "(Gauss-Seidel) " : "(conjugate gradients) ")
          << report_.spin_iterations << " + " << report_.smoothing_iterations << " iterations (r.m.s. "
          << report_.smoothing_residual << ") " << report_.smoothing_seconds
          << " s, inverted after interpolation " << report_.inverted_after_interpolation << ", after "
          << report_.repair_passes << " repair passes " << report_.inverted_after_repair
          << " (kept the fewest); setup "
          << (report_.geometry_cached      ? "(cached) "
              : report_.geometry_from_file ? "(from the cache file) "
                                           : "")
          << report_.setup_seconds << " s, total " << report_.total_seconds << " s";
  return summary.str();
}

}  // namespace mixmesh::deform
