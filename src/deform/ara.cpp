// The ARA predictor–corrector (Martineau & Georgala §4.3): distances, rigid-body
// initialisation, dual-mesh smoothing, interpolation to nodes, negative-volume repair.
#include "mixmesh/deform/ara.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>

#include "deform/dual_mesh.hpp"
#include "deform/rotation.hpp"
#include "deform/wall_faces.hpp"
#include "mixmesh/core/error.hpp"

namespace mixmesh::deform {

namespace {

using detail::DualMesh;
using detail::WallFaces;

template <class Body>
void parallel_cells(std::size_t count, const Body& body) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t item = range.begin(); item != range.end(); ++item) body(item);
                    });
}

// Motion of a wall face: its centre, the centre's displacement and the rotation.
struct FaceMotion {
  Vector3 centre;
  Vector3 displacement;
  Vector3 rotation;
};

std::vector<FaceMotion> wall_motion(const DualMesh& dual, const WallFaces& walls, const MixedMesh& mesh,
                                    const BoundaryMotion& boundary) {
  std::vector<FaceMotion> motion(walls.faces.size());
  for (std::size_t wall = 0; wall < walls.faces.size(); ++wall) {
    const std::size_t face = static_cast<std::size_t>(walls.faces[wall]);
    const Index* nodes = dual.boundary_nodes(face);
    const int count = dual.face_size(face);
    FaceMotion& entry = motion[wall];
    entry = {Vector3::Zero(), Vector3::Zero(), Vector3::Zero()};
    for (int local = 0; local < count; ++local) {
      const std::size_t node = static_cast<std::size_t>(nodes[local]);
      entry.centre += mesh.points[node];
      entry.displacement += boundary.displacement[node];
      entry.rotation += boundary.rotation[node];
    }
    entry.centre /= count;
    entry.displacement /= count;  // exact for rigid motion: the centre is affine in the nodes
    entry.rotation /= count;
  }
  return motion;
}

// Dual-mesh neighbours of every cell (CSR) with the smoothing weights σ of eq. 20, and
// the wall faces of every cell as Dirichlet neighbours.
struct Stencil {
  std::vector<std::size_t> offsets;
  std::vector<Index> neighbour;  // cell index, or −(wall + 1) for a wall face
  std::vector<double> weight;
};

Stencil build_stencil(const DualMesh& dual, const WallFaces& walls, const std::vector<Vector3>& centres,
                      const std::vector<Vector3>& wall_centres, const std::vector<double>& diffusivity,
                      const std::vector<Vector3>& points) {
  const std::size_t cells = dual.cell_count();
  std::vector<Index> wall_of_face(dual.face_count(), -1);
  for (std::size_t wall = 0; wall < walls.faces.size(); ++wall)
    wall_of_face[static_cast<std::size_t>(walls.faces[wall])] = static_cast<Index>(wall);
  Stencil stencil;
  stencil.offsets.assign(cells + 1, 0);
  for (const auto& pair : dual.interior_cells) {
    ++stencil.offsets[static_cast<std::size_t>(pair[0]) + 1];
    ++stencil.offsets[static_cast<std::size_t>(pair[1]) + 1];
  }
  for (std::size_t face = 0; face < dual.face_count(); ++face)
    if (wall_of_face[face] >= 0) ++stencil.offsets[static_cast<std::size_t>(dual.face_cell[face]) + 1];
  for (std::size_t cell = 0; cell < cells; ++cell) stencil.offsets[cell + 1] += stencil.offsets[cell];
  stencil.neighbour.resize(stencil.offsets.back());
  stencil.weight.resize(stencil.offsets.back());
  std::vector<std::size_t> fill(stencil.offsets.begin(), stencil.offsets.end() - 1);
  constexpr double tiny = 1e-300;
  for (std::size_t pair_index = 0; pair_index < dual.interior_cells.size(); ++pair_index) {
    const auto& pair = dual.interior_cells[pair_index];
    const std::size_t a = static_cast<std::size_t>(pair[0]);
    const std::size_t b = static_cast<std::size_t>(pair[1]);
    // Baker's diffusivity at the face, eq. 17; σ = τ A / |x_i − x_j|, eq. 20.
    const double tau = 0.5 * (diffusivity[a] + diffusivity[b]);
    const double sigma =
        tau * dual.interior_area[pair_index] / std::max((centres[a] - centres[b]).norm(), tiny);
    stencil.neighbour[fill[a]] = pair[1];
    stencil.weight[fill[a]++] = sigma;
    stencil.neighbour[fill[b]] = pair[0];
    stencil.weight[fill[b]++] = sigma;
  }
  for (std::size_t face = 0; face < dual.face_count(); ++face) {
    const Index wall = wall_of_face[face];
    if (wall < 0) continue;
    const std::size_t cell = static_cast<std::size_t>(dual.face_cell[face]);
    const double distance = (centres[cell] - wall_centres[static_cast<std::size_t>(wall)]).norm();
    const double sigma = diffusivity[cell] * detail::face_area(dual, face, points) / std::max(distance, tiny);
    stencil.neighbour[fill[cell]] = -(wall + 1);
    stencil.weight[fill[cell]++] = sigma;
  }
  return stencil;
}

// Rigid transport for the velocity smoothing: the velocity a neighbour (cell centre or
// wall face centre) implies at x_i when x_i moves rigidly with it,
// u_j + (R_j − I)(x_i − x_j) — the locus of eq. 23 applied on the dual mesh.
struct Transport {
  const std::vector<Eigen::Matrix3d>* cell_rotation = nullptr;  // R_j − I per cell
  const std::vector<Eigen::Matrix3d>* wall_rotation = nullptr;  // R_f − I per wall face
  const std::vector<Vector3>* centres = nullptr;
  const std::vector<Vector3>* wall_centres = nullptr;
};

// Point Gauss–Seidel on ∇·(τ∇v) = 0 (eq. 19), one colour at a time so that cells of a
// colour update in parallel and every update sees its neighbours' newest values.
// Returns the iterations done and the final r.m.s. residual (relative to `scale`).
std::pair<int, double> smooth(std::vector<Vector3>& values, const std::vector<Vector3>& wall_values,
                              const Stencil& stencil, const std::vector<std::vector<Index>>& colours,
                              const AraOptions& options, double scale, const Transport& transport = {}) {
  const std::size_t cells = values.size();
  if (cells == 0 || scale <= 0.0) return {0, 0.0};
  std::vector<double> residual(cells, 0.0);
  double rms = std::numeric_limits<double>::infinity();
  int iteration = 0;
  const double epsilon = options.relaxation;
  const bool transported = transport.cell_rotation != nullptr;
  while (iteration < options.max_iterations) {
    ++iteration;
    for (const auto& colour : colours) {
      parallel_cells(colour.size(), [&](std::size_t slot) {
        const std::size_t cell = static_cast<std::size_t>(colour[slot]);
        Vector3 sum = Vector3::Zero();
        double weight = 0.0;
        for (std::size_t entry = stencil.offsets[cell]; entry < stencil.offsets[cell + 1]; ++entry) {
          const Index other = stencil.neighbour[entry];
          const std::size_t at = static_cast<std::size_t>(other >= 0 ? other : -other - 1);
          Vector3 value = other >= 0 ? values[at] : wall_values[at];
          if (transported) {
            const Vector3& from = other >= 0 ? (*transport.centres)[at] : (*transport.wall_centres)[at];
            const Eigen::Matrix3d& turn =
                other >= 0 ? (*transport.cell_rotation)[at] : (*transport.wall_rotation)[at];
            value += turn * ((*transport.centres)[cell] - from);
          }
          sum += stencil.weight[entry] * value;
          weight += stencil.weight[entry];
        }
        if (weight <= 0.0) return;
        const Vector3 target = sum / weight;
        residual[cell] = (target - values[cell]).squaredNorm();
        values[cell] = (1.0 - epsilon) * values[cell] + epsilon * target;  // eq. 19
      });
    }
    double total = 0.0;
    for (double entry : residual) total += entry;
    rms = std::sqrt(total / static_cast<double>(cells)) / scale;
    if (rms <= options.tolerance) break;
  }
  return {iteration, rms};
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
  if (planar) {  // no z extent: solve the 2×2 system
    second(2, 2) = 1.0;
    second(0, 2) = second(2, 0) = second(1, 2) = second(2, 1) = 0.0;
    first.z() = 0.0;
  }
  Vector3 lambda = Vector3::Zero();
  const Eigen::FullPivLU<Eigen::Matrix3d> solver(second);
  if (solver.isInvertible()) lambda = -solver.solve(first);
  for (std::size_t slot = 0; slot < count; ++slot) {
    const Vector3 offset = centres[static_cast<std::size_t>(cells[slot])] - node;
    weights[slot] = std::clamp(1.0 + lambda.dot(offset), 0.0, 2.0);
  }
}

}  // namespace

std::vector<Vector3> AraMethod::move(const MixedMesh& mesh, const BoundaryMotion& boundary, const Log& log) {
  report_ = {};
  if (boundary.roles.size() != mesh.points.size() || boundary.displacement.size() != mesh.points.size() ||
      boundary.rotation.size() != mesh.points.size())
    throw Error("ara: boundary motion does not match the mesh (" + std::to_string(boundary.roles.size()) +
                " entries for " + std::to_string(mesh.points.size()) + " points)");
  const DualMesh dual = detail::build_dual_mesh(mesh);
  const WallFaces walls = detail::wall_faces(dual, boundary.marker_roles);
  if (walls.faces.empty()) throw Error("ara: the mesh has no wall boundary (every marker slides)");
  const std::size_t cells = dual.cell_count();
  const std::vector<Vector3>& points = mesh.points;

  std::vector<Vector3> centres(cells);
  std::vector<double> volume(cells);
  parallel_cells(cells, [&](std::size_t cell) {
    centres[cell] = detail::cell_centre(dual, cell, points);
    volume[cell] = detail::cell_measure(dual, cell, points);
  });

  // 1. Distance metrics: cached nearest faces when they fit this mesh.
  Stopwatch distance_clock;
  const bool cache_fits = nearest_.cell_count == cells && nearest_.wall_face_count == walls.faces.size() &&
                          nearest_.faces.size() == cells;
  if (!cache_fits && !options_.cache_file.empty() && std::filesystem::exists(options_.cache_file)) {
    NearestFaces stored = read_nearest_faces(options_.cache_file);
    if (stored.cell_count == cells && stored.wall_face_count == walls.faces.size()) {
      nearest_ = std::move(stored);
      log.detail("ara: nearest faces read from " + options_.cache_file.string());
    }
  }
  report_.cache_used = nearest_.cell_count == cells && nearest_.wall_face_count == walls.faces.size() &&
                       nearest_.faces.size() == cells;
  if (!report_.cache_used) {
    nearest_ = detail::find_nearest_faces(dual, walls, centres, points, options_.candidates);
    if (!options_.cache_file.empty()) write_nearest_faces(nearest_, options_.cache_file);
  }
  std::vector<double> first_distance;
  std::vector<double> second_distance;
  detail::nearest_distances(dual, walls, nearest_, centres, points, first_distance, second_distance);
  report_.distance_seconds = distance_clock.seconds();

  // 2. Rigid-body initialisation (eq. 9–11).
  const std::vector<FaceMotion> faces = wall_motion(dual, walls, mesh, boundary);
  const bool rotate = options_.predictor == Predictor::rotation;
  std::vector<Vector3> velocity(cells);  // u = x′ − x
  std::vector<Vector3> spin(cells);      // w, rotation vector of the cell
  parallel_cells(cells, [&](std::size_t cell) {
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
        moved[side] = detail::rotate(face.rotation, x - face.centre) + face.centre + face.displacement;
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

  // 3. Smoothing of u and w on the dual mesh (eq. 12–21), Baker's τ from the input mesh.
  double smallest = std::numeric_limits<double>::infinity();
  double largest = 0.0;
  for (double entry : volume) {
    smallest = std::min(smallest, std::abs(entry));
    largest = std::max(largest, std::abs(entry));
  }
  std::vector<double> diffusivity(cells);
  for (std::size_t cell = 0; cell < cells; ++cell)
    diffusivity[cell] = 1.0 + (largest - smallest) / std::max(std::abs(volume[cell]), 1e-300);  // eq. 13
  std::vector<Vector3> wall_centres(faces.size());
  std::vector<Vector3> wall_velocity(faces.size());
  std::vector<Vector3> wall_spin(faces.size());
  double largest_spin = 0.0;
  for (std::size_t wall = 0; wall < faces.size(); ++wall) {
    wall_centres[wall] = faces[wall].centre;
    wall_velocity[wall] = faces[wall].displacement;
    wall_spin[wall] = rotate ? faces[wall].rotation : Vector3::Zero();
    largest_spin = std::max(largest_spin, wall_spin[wall].norm());
  }
  const Stencil stencil = build_stencil(dual, walls, centres, wall_centres, diffusivity, points);
  const auto colours = detail::colour_cells(dual);
  // The angular velocity first (eq. 21), so that the velocity smoothing can transport
  // neighbour velocities rigidly with it.
  if (rotate) smooth(spin, wall_spin, stencil, colours, options_, largest_spin);
  Transport transport;
  std::vector<Eigen::Matrix3d> cell_turn;
  std::vector<Eigen::Matrix3d> wall_turn;
  if (rotate && options_.smoothing == Smoothing::rigid_transport) {
    cell_turn.resize(cells);
    wall_turn.resize(faces.size());
    parallel_cells(cells, [&](std::size_t cell) {
      cell_turn[cell] = detail::rotation_matrix(spin[cell]) - Eigen::Matrix3d::Identity();
    });
    for (std::size_t wall = 0; wall < faces.size(); ++wall)
      wall_turn[wall] = detail::rotation_matrix(wall_spin[wall]) - Eigen::Matrix3d::Identity();
    transport = {&cell_turn, &wall_turn, &centres, &wall_centres};
  }
  const auto [iterations, residual] =
      smooth(velocity, wall_velocity, stencil, colours, options_, boundary.largest_displacement(), transport);
  report_.smoothing_iterations = iterations;
  report_.smoothing_residual = residual;

  // 4. Interpolation to nodes (eq. 22–26).
  std::vector<Vector3> result(points.size());
  std::vector<double> weight_start(dual.point_cells.size());
  auto candidate = [&](std::size_t node, std::size_t cell) -> Vector3 {
    // x′_j = R_j(x_i) + Δx_j: the node moved rigidly with cell j (eq. 23).
    return detail::rotate(spin[cell], points[node] - centres[cell]) + centres[cell] + velocity[cell];
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
      double weight = weight_start[slot];
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
  parallel_cells(points.size(), [&](std::size_t node) {
    const std::size_t begin = dual.point_cell_offsets[node];
    const std::size_t end = dual.point_cell_offsets[node + 1];
    if (boundary.roles[node] == NodeRole::prescribed || begin == end) {
      result[node] = points[node] + boundary.displacement[node];
      return;
    }
    pseudo_laplacian_weights(points[node], dual.point_cells.data() + begin, end - begin, centres, dual.planar,
                             weight_start.data() + begin);
    result[node] = interpolate(node, 0, nullptr);
  });
  detail::project_sliding(boundary, points, result);

  // 5. Negative-volume repair (eq. 27), up to repair_passes passes.
  std::vector<double> deformed_volume(cells);
  std::vector<char> invalid(cells, 0);
  auto check = [&]() {
    parallel_cells(cells, [&](std::size_t cell) {
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
    parallel_cells(nodes.size(), [&](std::size_t slot) {
      updated[slot] = interpolate(static_cast<std::size_t>(nodes[slot]), pass, &deformed_volume);
    });
    for (std::size_t slot = 0; slot < nodes.size(); ++slot)
      result[static_cast<std::size_t>(nodes[slot])] = updated[slot];
    detail::project_sliding(boundary, points, result);
    inverted = check();
    report_.repair_passes = pass;
    if (inverted < best_inverted) {
      best = result;
      best_inverted = inverted;
    }
  }
  if (inverted > best_inverted) result = std::move(best);
  report_.inverted_after_repair = std::min(inverted, best_inverted);

  std::ostringstream summary;
  summary << "ara: " << cells << " cells, " << walls.boundary_count << " boundaries, distances "
          << (report_.cache_used ? "(cached) " : "") << report_.distance_seconds << " s, smoothing "
          << iterations << " iterations (r.m.s. " << residual << "), inverted after interpolation "
          << report_.inverted_after_interpolation << ", after " << report_.repair_passes << " repair passes "
          << inverted;
  log.detail(summary.str());
  return result;
}

}  // namespace mixmesh::deform
