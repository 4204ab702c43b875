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
#include "deform/dual_mesh.hpp"
#include "deform/rotation.hpp"
#include "deform/wall_faces.hpp"
#include "mixmesh/core/error.hpp"

namespace mixmesh::deform {

namespace {

using detail::DualMesh;
using detail::WallFaces;

// Motion of a wall face: its centre's displacement and its rotation (the centre itself is
// AraGeometry::wall_centres).
struct FaceMotion {
  Vector3 displacement;
  Vector3 rotation;
};

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

std::vector<Vector3> AraMethod::move(const MixedMesh& mesh, const BoundaryMotion& boundary, const Log& log) {
  report_ = {};
  Stopwatch total_clock;
  Stopwatch stage_clock;
  if (boundary.roles.size() != mesh.points.size() || boundary.displacement.size() != mesh.points.size() ||
      boundary.rotation.size() != mesh.points.size())
    throw Error("ara: boundary motion does not match the mesh (" + std::to_string(boundary.roles.size()) +
                " entries for " + std::to_string(mesh.points.size()) + " points)");
  const std::uint64_t connectivity = detail::connectivity_hash(mesh);
  const std::uint64_t point_bits = detail::points_hash(mesh.points);
  report_.geometry_cached = geometry_ && geometry_->connectivity == connectivity &&
                            geometry_->points == point_bits &&
                            geometry_->marker_roles == boundary.marker_roles;
  // A cache file of nearest faces only (written with cache_geometry off, or by an older
  // mixmesh) gets the geometry added once it is built, so the next run reads it.
  bool add_geometry_to_file = false;
  if (!report_.geometry_cached) {
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
  }
  const detail::AraGeometry& geometry = *geometry_;
  const DualMesh& dual = geometry.dual;
  const WallFaces& walls = geometry.walls;
  const std::vector<Vector3>& centres = geometry.centres;
  const std::size_t cells = dual.cell_count();
  const std::vector<Vector3>& points = mesh.points;
  report_.setup_seconds = stage_clock.seconds();

  // 1. Distance metrics: nearest faces from memory or the cache file when they were found
  // on a mesh with this connectivity and these wall faces.
  stage_clock = Stopwatch();
  auto fits = [&](const NearestFaces& nearest) {
    return nearest.mesh_hash == geometry.nearest_key && nearest.point_count == points.size() &&
           nearest.cell_count == cells && nearest.wall_face_count == walls.faces.size() &&
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
              << "; this mesh has " << points.size() << ", " << cells << ", " << walls.faces.size()
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
  if (!report_.cache_used) {
    nearest_ = detail::find_nearest_faces(dual, walls, centres, points, options_.candidates);
    nearest_.point_count = points.size();
    nearest_.mesh_hash = geometry.nearest_key;
    if (!options_.cache_file.empty()) {
      if (options_.cache_geometry)
        detail::write_ara_cache(nearest_, geometry, options_.cache_file);
      else
        write_nearest_faces(nearest_, options_.cache_file);
    }
  }
  std::vector<double> first_distance;
  std::vector<double> second_distance;
  detail::nearest_distances(dual, walls, nearest_, centres, points, first_distance, second_distance);
  report_.distance_seconds = stage_clock.seconds();

  // 2. Rigid-body initialisation (eq. 9–11).
  stage_clock = Stopwatch();
  const std::vector<FaceMotion> faces = wall_motion(dual, walls, boundary);
  const bool rotate = options_.predictor == Predictor::rotation;
  std::vector<Vector3> velocity(cells);  // u = x′ − x
  std::vector<Vector3> spin(cells);      // w, rotation vector of the cell
  detail::parallel_items(cells, [&](std::size_t cell) {
    const Vector3& x = centres[cell];
    Vector3 moved[2] = {x, x};
    Vector3 rotation[2] = {Vector3::Zero(), Vector3::Zero()};
    for (int side = 0; side < 2; ++side) {
      const Index wall = nearest_.faces[cell][static_cast<std::size_t>(side)];
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
    if (nearest_.faces[cell][1] >= 0) {
      const double d1 = first_distance[cell];
      const double d2 = second_distance[cell];
      const double alpha = d1 + d2 > 0.0 ? std::clamp(d2 / (d1 + d2), 0.5, 1.0) : 1.0;  // eq. 2
      beta = blend(alpha, options_.gamma, options_.blend_form);                         // eq. 11
    }
    velocity[cell] = beta * moved[0] + (1.0 - beta) * moved[1] - x;  // eq. 10
    spin[cell] = beta * rotation[0] + (1.0 - beta) * rotation[1];
  });
  report_.predictor_seconds = stage_clock.seconds();

  // 3. Smoothing of w and u on the dual mesh (eq. 12–21), the predictor as first guess.
  stage_clock = Stopwatch();
  std::vector<Vector3> wall_velocity(faces.size());
  std::vector<Vector3> wall_spin(faces.size(), Vector3::Zero());
  double largest_spin = 0.0;
  for (std::size_t wall = 0; wall < faces.size(); ++wall) {
    wall_velocity[wall] = faces[wall].displacement;
    if (rotate) wall_spin[wall] = faces[wall].rotation;
    largest_spin = std::max(largest_spin, wall_spin[wall].norm());
  }
  const bool gauss_seidel = options_.solver == Solver::gauss_seidel;
  if (gauss_seidel && geometry.colours.empty()) geometry_->colours = detail::colour_cells(dual);
  auto solve = [&](std::vector<Vector3>& values, const std::vector<Vector3>& source, double scale) {
    detail::SolveSettings settings;
    settings.relaxation = options_.relaxation;
    settings.tolerance = options_.tolerance;
    settings.scale = scale;
    settings.max_iterations = options_.max_iterations;
    return gauss_seidel ? detail::gauss_seidel(values, source, geometry.stencil, geometry.colours, settings)
                        : detail::conjugate_gradient(values, source, geometry.stencil, settings);
  };
  // The angular velocity first (eq. 21), so that the velocity smoothing can transport
  // neighbour velocities rigidly with it.
  if (rotate) {
    const detail::SolveResult spun =
        solve(spin, detail::smoothing_source(geometry.stencil, wall_spin, {}), largest_spin);
    report_.spin_iterations = spun.iterations;
  }
  // R − I of every cell, for the transport and the interpolation to nodes.
  std::vector<Eigen::Matrix3d> cell_turn;
  detail::Transport transport;
  std::vector<Eigen::Matrix3d> wall_turn;
  if (rotate) {
    cell_turn.resize(cells);
    detail::parallel_items(cells, [&](std::size_t cell) {
      cell_turn[cell] = detail::rotation_matrix(spin[cell]) - Eigen::Matrix3d::Identity();
    });
    if (options_.smoothing == Smoothing::rigid_transport) {
      wall_turn.resize(faces.size());
      for (std::size_t wall = 0; wall < faces.size(); ++wall)
        wall_turn[wall] = detail::rotation_matrix(wall_spin[wall]) - Eigen::Matrix3d::Identity();
      transport = {&cell_turn, &wall_turn, &centres, &geometry.wall_centres};
    }
  }
  const detail::SolveResult smoothed =
      solve(velocity, detail::smoothing_source(geometry.stencil, wall_velocity, transport),
            boundary.largest_displacement());
  report_.smoothing_iterations = smoothed.iterations;
  report_.smoothing_residual = smoothed.residual;
  report_.smoothing_seconds = stage_clock.seconds();

  // 4. Interpolation to nodes (eq. 22–26).
  stage_clock = Stopwatch();
  std::vector<Vector3> result(points.size());
  auto candidate = [&](std::size_t node, std::size_t cell) -> Vector3 {
    // x′_j = R_j(x_i − c_j) + c_j + u_j: the node moved rigidly with cell j (eq. 23).
    if (!rotate) return points[node] + velocity[cell];
    return points[node] + velocity[cell] + cell_turn[cell] * (points[node] - centres[cell]);
  };
  auto interpolate = [&](std::size_t node, int repair_pass,
                         const std::vector<double>* deformed_volume) -> Vector3 {
    const std::size_t begin = dual.point_cell_offsets[node];
    const std::size_t end = dual.point_cell_offsets[node + 1];
    double volume_average = 0.0;
    if (repair_pass > 0) {
      for (std::size_t slot = begin; slot < end; ++slot)
        volume_average += std::abs((*deformed_volume)[static_cast<std::size_t>(dual.point_cells[slot])]);
      volume_average /= static_cast<double>(end - begin);
    }
    Vector3 sum = Vector3::Zero();
    double total = 0.0;
    for (std::size_t slot = begin; slot < end; ++slot) {
      const std::size_t cell = static_cast<std::size_t>(dual.point_cells[slot]);
      double weight = geometry.node_weights[slot];
      if (repair_pass > 0) {
        // Eq. 27 (reconstructed): ω′ = ω (1 + m V_ave / V_j); inverted and tiny cells are
        // clamped to a thousandth of V_ave, so they weigh most.
        const double own = std::max((*deformed_volume)[cell], 1e-3 * volume_average);
        weight *= 1.0 + repair_pass * volume_average / own;
      }
      sum += weight * candidate(node, cell);
      total += weight;
    }
    if (total <= 0.0) {  // every weight clipped: plain average
      sum = Vector3::Zero();
      for (std::size_t slot = begin; slot < end; ++slot)
        sum += candidate(node, static_cast<std::size_t>(dual.point_cells[slot]));
      total = static_cast<double>(end - begin);
    }
    return Vector3(sum / total);
  };
  detail::parallel_items(points.size(), [&](std::size_t node) {
    const std::size_t begin = dual.point_cell_offsets[node];
    const std::size_t end = dual.point_cell_offsets[node + 1];
    if (boundary.roles[node] == NodeRole::prescribed || begin == end) {
      result[node] = points[node] + boundary.displacement[node];
      return;
    }
    result[node] = interpolate(node, 0, nullptr);
  });
  detail::project_sliding(boundary, points, result);
  report_.interpolation_seconds = stage_clock.seconds();

  // 5. Negative-volume repair (eq. 27), up to repair_passes passes.
  stage_clock = Stopwatch();
  std::vector<double> deformed_volume(cells);
  std::vector<char> invalid(cells, 0);
  auto check = [&]() {
    detail::parallel_items(cells, [&](std::size_t cell) {
      deformed_volume[cell] = detail::cell_measure(dual, cell, result);
      invalid[cell] = !detail::cell_valid(dual, cell, result);
    });
    return static_cast<std::size_t>(std::count(invalid.begin(), invalid.end(), 1));
  };
  std::size_t inverted = check();
  report_.inverted_after_interpolation = inverted;
  // A pass can make things worse where the cells' rigid motions disagree; the result
  // with the fewest inverted cells is the one returned.
  std::vector<Vector3> best;
  if (inverted > 0) best = result;
  std::size_t best_inverted = inverted;
  std::vector<char> touched(points.size(), 0);
  for (int pass = 1; pass <= options_.repair_passes && inverted > 0; ++pass) {
    std::vector<Index> nodes;
    for (std::size_t cell = 0; cell < cells; ++cell) {
      if (!invalid[cell]) continue;
      for (int local = 0; local < dual.cell_size(cell); ++local) {
        const Index node = dual.nodes(cell)[local];
        if (boundary.roles[static_cast<std::size_t>(node)] == NodeRole::prescribed) continue;
        if (touched[static_cast<std::size_t>(node)] == pass) continue;
        touched[static_cast<std::size_t>(node)] = static_cast<char>(pass);
        nodes.push_back(node);
      }
    }
    std::vector<Vector3> updated(nodes.size());
    detail::parallel_items(nodes.size(), [&](std::size_t slot) {
      updated[slot] = interpolate(static_cast<std::size_t>(nodes[slot]), pass, &deformed_volume);
    });
    for (std::size_t slot = 0; slot < nodes.size(); ++slot)
      result[static_cast<std::size_t>(nodes[slot])] = updated[slot];
    detail::project_sliding(boundary, points, result);
    // Only the cells of the moved nodes change: checking those alone instead of every
    // cell gives the same count (a full check of the M6's 701 k cells took 0.1–0.2 s a pass).
    const std::vector<Index> changed = detail::cells_of_nodes(dual, nodes);
    detail::parallel_items(changed.size(), [&](std::size_t slot) {
      const std::size_t cell = static_cast<std::size_t>(changed[slot]);
      deformed_volume[cell] = detail::cell_measure(dual, cell, result);
      invalid[cell] = !detail::cell_valid(dual, cell, result);
    });
    inverted = static_cast<std::size_t>(std::count(invalid.begin(), invalid.end(), 1));
    report_.repair_passes = pass;
    if (inverted < best_inverted) {
      best = result;
      best_inverted = inverted;
    }
  }
  if (inverted > best_inverted) result = std::move(best);
  report_.inverted_after_repair = std::min(inverted, best_inverted);

  report_.repair_seconds = stage_clock.seconds();
  report_.total_seconds = total_clock.seconds();
  std::ostringstream summary;
  summary << "ara: " << cells << " cells, " << walls.boundary_count << " boundaries, distances "
          << (report_.cache_used ? "(cached) " : "") << report_.distance_seconds << " s, smoothing "
          << (gauss_seidel ? "(Gauss-Seidel) " : "(conjugate gradients) ") << report_.spin_iterations << " + "
          << smoothed.iterations << " iterations (r.m.s. " << smoothed.residual << ") "
          << report_.smoothing_seconds << " s, inverted after interpolation "
          << report_.inverted_after_interpolation << ", after " << report_.repair_passes << " repair passes "
          << report_.inverted_after_repair << " (kept the fewest); setup "
          << (report_.geometry_cached      ? "(cached) "
              : report_.geometry_from_file ? "(from the cache file) "
                                           : "")
          << report_.setup_seconds << " s, total " << report_.total_seconds << " s";
  log.detail(summary.str());
  return result;
}

}  // namespace mixmesh::deform
