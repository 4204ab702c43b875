#include "mixmesh/march/march_layers.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include <Eigen/Geometry>

#include "front.hpp"
#include "junction.hpp"
#include "layer_checks.hpp"
#include "layer_mesh.hpp"
#include "layer_solver.hpp"
#include "line_geometry.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"

namespace mixmesh {

namespace {

using march_detail::close_pinched_lines;
using march_detail::column_normals;
using march_detail::fade_towards_symmetry;
using march_detail::Front;
using march_detail::FrontFace;
using march_detail::keep_in_sheet_end;
using march_detail::line_data;
using march_detail::LineData;
using march_detail::off_the_sheet;
using march_detail::raise_to_outer_height;
using march_detail::see_every_wall_face;
using march_detail::unit_or;

// Weight of the smoothed direction against the orthogonal one (control functions
// held near the wall, released over the outer layers).
double release_weight(const MarchOptions& options, int layer) {
  if (layer < options.orthogonal_layers) return 0.0;
  const double t = std::clamp(static_cast<double>(layer - options.orthogonal_layers + 1) /
                                  static_cast<double>(std::max(1, options.release_layers)),
                              0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

void check_options(const MarchOptions& options) {
  if (options.sweeps < 0) throw Error("march: sweeps must be >= 0, got " + std::to_string(options.sweeps));
  if (options.orthogonal_layers < 0 || options.release_layers < 0)
    throw Error("march: orthogonal and release layer counts must be >= 0");
  if (!(options.direction_memory >= 0.0 && options.direction_memory < 1.0))
    throw Error("march: direction memory must lie in [0, 1)");
  if (!(options.layer_tolerance >= 0.0))
    throw Error("march: layer tolerance must be >= 0, got " + std::to_string(options.layer_tolerance));
  if (options.layer_solve != LayerSolve::sweeps && options.layer_solve != LayerSolve::sparse)
    throw Error("march: unknown layer solve " + std::to_string(static_cast<int>(options.layer_solve)));
  if (options.step_reductions < 0) throw Error("march: step reductions must be >= 0");
  if (!(options.wake_spread_degrees >= 0.0 && options.wake_spread_degrees < 45.0))
    throw Error("march: wake spread must lie in [0, 45) degrees, got " +
                std::to_string(options.wake_spread_degrees));
  if (options.direction_smoothing_passes < 0) throw Error("march: direction smoothing passes must be >= 0");
  if (!(options.maximum_turn_degrees >= 0.0 && options.maximum_turn_degrees <= 180.0))
    throw Error("march: maximum turn per layer must lie in [0, 180] degrees, got " +
                std::to_string(options.maximum_turn_degrees));
}

std::string degrees_text(double value) {
  std::ostringstream stream;
  stream.precision(1);
  stream << std::fixed << value;
  return stream.str();
}

std::string scientific(double value) {
  std::ostringstream stream;
  stream.precision(2);
  stream << std::scientific << value;
  return stream.str();
}

// What every phase of the march reads and none changes.
struct MarchContext {
  const SurfaceMesh& surface;
  const MarchOptions& options;
  const Front& front;
  const std::vector<double>& steps;
  const Log* log;
  bool smoothed;
  LineData lines;
};

// What the march carries from one layer to the next.
struct MarchState {
  std::vector<Vector3> current, previous;
  std::vector<Vector3> direction;  // each line's last marching direction
  std::vector<double> marched;     // each line's length so far
  std::vector<char> face_active;
  std::vector<int> stop_at;
  std::vector<Vector3> first_normal;
  std::vector<char> node_stopped;
  std::map<int, StoppedRegion> stopped;
};

// One layer on its way: each line's normal, step and new position.
struct LayerStep {
  int layer = 0;
  double release = 0.0;
  std::vector<char> column_active;
  std::vector<Vector3> normal;
  std::vector<double> step;
  std::vector<Vector3> predicted_direction;
  std::vector<Vector3> next;
};

std::vector<char> active_columns(const Front& front, const std::vector<char>& face_active) {
  std::vector<char> column_active(front.column_node.size(), 0);
  for (std::size_t face = 0; face < front.faces.size(); ++face)
    if (face_active[face])
      for (int k = 0; k < front.faces[face].corner_count; ++k)
        column_active[static_cast<std::size_t>(front.faces[face].columns[static_cast<std::size_t>(k)])] = 1;
  return column_active;
}

// The surface's points and faces in the result, and each line's first point.
void start_result(const SurfaceMesh& surface, const Front& front, BoundaryLayer& result) {
  const std::size_t column_count = front.column_node.size();
  result.mesh.points = surface.points;
  result.region_names = front.patch_names;
  result.column_node = front.column_node;
  result.column_side = front.column_side;
  result.column_points.resize(column_count);
  for (std::size_t c = 0; c < column_count; ++c) result.column_points[c].push_back(front.column_node[c]);
  for (const FrontFace& f : front.faces) {
    result.face_columns.emplace_back(f.columns.begin(), f.columns.begin() + f.corner_count);
    result.face_patch.push_back(f.patch);
    result.face_wall.push_back(f.wall);
  }
  result.face_layers.assign(front.faces.size(), 0);
}

// The layer at which each face stops at the latest for the forced stops.
std::vector<int> forced_stop_layers(const SurfaceMesh& surface, const Front& front,
                                    const std::vector<ForcedStop>& forced_stops) {
  const std::size_t face_count = front.faces.size();
  std::vector<int> stop_at(face_count, std::numeric_limits<int>::max());
  // A face is in a stop's reach when its centroid or one of its nodes is: the faces at a
  // wing's root are long spanwise, and a crossing at the root's trailing edge lay within
  // no face's centroid reach, so the retries there changed nothing.
  for (const ForcedStop& forced : forced_stops)
    for (std::size_t face = 0; face < face_count; ++face) {
      const FrontFace& front_face = front.faces[face];
      Vector3 centre = Vector3::Zero();
      double nearest = std::numeric_limits<double>::infinity();
      for (int k = 0; k < front_face.corner_count; ++k) {
        const Vector3& node = surface.points[static_cast<std::size_t>(
            front.column_node[static_cast<std::size_t>(front_face.columns[static_cast<std::size_t>(k)])])];
        centre += node / front_face.corner_count;
        nearest = std::min(nearest, (node - forced.centre).norm());
      }
      if (std::min(nearest, (centre - forced.centre).norm()) <= forced.radius)
        stop_at[face] = std::min(stop_at[face], std::max(0, forced.layer));
    }
  return stop_at;
}

// Each line's layer normal; the junction lines' first one is kept for the layers above.
std::vector<Vector3> layer_normals(const MarchContext& march, MarchState& state,
                                   const LayerStep& layer_step) {
  const Front& front = march.front;
  const std::size_t column_count = front.column_node.size();
  const int layer = layer_step.layer;
  const std::vector<char>& on_wall = march.lines.on_wall;
  const std::vector<char>& junction_line = march.lines.junction_line;
  const std::vector<Vector3>& sheet_normal = march.lines.sheet_normal;
  std::vector<Vector3> normal = column_normals(front, state.current, state.face_active, march.smoothed,
                                               state.direction, on_wall, layer_step.release);
  // The two lines of a junction keep their first normal: the faces around them shear
  // against each other (the wall triangle's lines turn round the tip with the
  // smoothing, the sheet's lines do not), so their layer normal turns upstream and
  // feeds that shear back into the lines.
  if (march.smoothed) {
    for (std::size_t c = 0; c < column_count; ++c)
      if (junction_line[c] && layer > 0) normal[c] = state.first_normal[c];
    if (layer == 0) {
      // Their first normal also leaves the sheet on its own side (below): at a blunt
      // base's end both lines see the base facing along the sheet, and without the
      // sheet's faces (weighed out at the first layers) they would start as one.
      const std::vector<Vector3> seeing =
          march_detail::junction_directions(front, state.current, state.face_active);
      for (std::size_t c = 0; c < column_count; ++c)
        if (junction_line[c] && on_wall[c])
          normal[c] = off_the_sheet(seeing[c].squaredNorm() > 0.0 ? seeing[c] : normal[c], sheet_normal[c]);
      state.first_normal = normal;
    }
  }
  for (std::size_t c = 0; c < column_count; ++c)
    if (on_wall[c] && !junction_line[c]) normal[c] = off_the_sheet(normal[c], sheet_normal[c]);
  // (Not for the plain-normal baseline, which stays plain extrusion for the comparison.)
  if (march.smoothed)
    see_every_wall_face(front, state.current, state.face_active, on_wall, junction_line, normal);
  return normal;
}

// Each line's step at `layer`: its own wake steps off the wall, the last layer raised
// to the outer layer height.
std::vector<double> line_steps(const MarchContext& march, const MarchState& state, int layer) {
  const std::vector<double>& steps = march.steps;
  const std::vector<std::vector<double>>& own_steps = march.lines.own_steps;
  const MarchOptions& options = march.options;
  std::vector<double> step(own_steps.size());
  for (std::size_t c = 0; c < step.size(); ++c)
    step[c] = (own_steps[c].empty() ? steps : own_steps[c])[static_cast<std::size_t>(layer)];
  if (layer + 1 == static_cast<int>(steps.size()) && options.outer_layer_height > 0.0)
    raise_to_outer_height(march.front, state.current, state.face_active, options.outer_layer_height, step);
  return step;
}

// Predictor: the layer normal, blended with the previous marching direction.
void predict_directions(const MarchContext& march, const MarchState& state, LayerStep& layer_step) {
  const Front& front = march.front;
  const std::size_t column_count = front.column_node.size();
  const std::vector<Vector3>& current = state.current;
  const std::vector<Vector3>& normal = layer_step.normal;
  std::vector<Vector3>& predicted_direction = layer_step.predicted_direction;
  const int layer = layer_step.layer;
  const double memory = march.smoothed && layer > 0 ? march.options.direction_memory : 0.0;
  layer_step.step = line_steps(march, state, layer);
  predicted_direction.resize(column_count);
  for (std::size_t c = 0; c < column_count; ++c) {
    const Vector3 before = unit_or(current[c] - state.previous[c], normal[c]);
    predicted_direction[c] = unit_or((1.0 - memory) * normal[c] + memory * before, normal[c]);
    if (front.on_symmetry[c])
      predicted_direction[c] =
          unit_or(Vector3(predicted_direction[c].x(), 0.0, predicted_direction[c].z()), normal[c]);
  }
  // At a junction the sheet lines next to the split face's lines start parallel to
  // them, so the prism between the two sheet lines there (the first cell of the wrap
  // face of the sheet's edge) has two equal triangles.
  if (layer == 0)
    for (const march_detail::Junction& junction : front.junctions)
      for (int end : {0, 1}) {
        const FrontFace& split = front.faces[static_cast<std::size_t>(junction.face)];
        predicted_direction[static_cast<std::size_t>(junction.sheet[static_cast<std::size_t>(end)])] =
            predicted_direction[static_cast<std::size_t>(split.columns[end == 0 ? 0 : 3])];
      }
  layer_step.next.resize(column_count);
  for (std::size_t c = 0; c < column_count; ++c)
    layer_step.next[c] = current[c] + layer_step.step[c] * predicted_direction[c];
}

// Corrector: face-weighted Laplace, then the control functions (step length held,
// orthogonal direction near the wall, smoothed direction released outwards).
void correct_layer(const MarchContext& march, const MarchState& state, LayerStep& layer_step,
                   MarchReport& report) {
  const Front& front = march.front;
  const MarchOptions& options = march.options;
  const std::vector<char>& face_active = state.face_active;
  const std::vector<Vector3>& current = state.current;
  const std::vector<Vector3>& normal = layer_step.normal;
  const std::vector<double>& step = layer_step.step;
  const std::vector<Vector3>& predicted_direction = layer_step.predicted_direction;
  std::vector<Vector3>& next = layer_step.next;
  const double release = layer_step.release;
  const double symmetry_y = march.surface.symmetry_y;
  const march_detail::LayerSolution solution =
      options.layer_solve == LayerSolve::sparse
          ? march_detail::solve_layer_sparse(front, options.sweeps, options.layer_tolerance, face_active,
                                             current, next, symmetry_y)
          : march_detail::solve_layer_by_sweeps(front, options.sweeps, face_active, current, next,
                                                symmetry_y);
  const std::vector<Vector3>& corrected = solution.positions;
  report.corrector_iterations += solution.iterations;
  report.corrector_change = std::max(report.corrector_change, solution.last_change);
  if (march.log)
    march.log->detail("march: layer " + std::to_string(layer_step.layer + 1) + ": corrector " +
                      std::to_string(solution.iterations) + " iterations, last change " +
                      scientific(solution.last_change) + " of the step");
  for (std::size_t c = 0; c < front.column_node.size(); ++c) {
    // The corrector moves the node sideways; its pull along the line (inwards at
    // convex, outwards at concave corners) is the spacing the control holds.
    const Vector3& along = predicted_direction[c];
    Vector3 sideways = corrected[c] - next[c];
    sideways -= sideways.dot(along) * along;
    Vector3 smooth = unit_or(step[c] * along + sideways, along);
    if (smooth.dot(normal[c]) < 0.2) smooth = along;  // never turn back into the wall
    next[c] = current[c] + step[c] * unit_or((1.0 - release) * predicted_direction[c] + release * smooth,
                                             predicted_direction[c]);
  }
}

// Direction smoothing over the released layers: neighbouring lines turn together,
// so thin cells at convex corners (tip edge, tip leading edge) do not shear over.
void smooth_directions(const MarchContext& march, const MarchState& state, LayerStep& layer_step) {
  const std::size_t column_count = march.front.column_node.size();
  const std::vector<Vector3>& current = state.current;
  const std::vector<char>& column_active = layer_step.column_active;
  const std::vector<double>& step = layer_step.step;
  std::vector<Vector3>& next = layer_step.next;
  const double release = layer_step.release;
  std::vector<Vector3> ahead = next;
  for (int pass = 0; pass < march.options.direction_smoothing_passes; ++pass) {
    const std::vector<Vector3> mean =
        march_detail::neighbour_mean_directions(march.front, column_active, current, ahead);
    for (std::size_t c = 0; c < column_count; ++c)
      if (column_active[c]) ahead[c] = current[c] + step[c] * mean[c];
  }
  for (std::size_t c = 0; c < column_count; ++c)
    if (column_active[c]) {
      const Vector3 own = unit_or(next[c] - current[c], layer_step.normal[c]);
      const Vector3 mean = unit_or(ahead[c] - current[c], own);
      next[c] = current[c] + step[c] * unit_or((1.0 - release) * own + release * mean, own);
    }
}

// Turn limit: a line turns by at most maximum_turn_degrees per layer. The corrector
// and the direction smoothing bend the lines most in the outer layers, where the
// steps become as long as the surface cells are wide (convex tip, leading and
// trailing edges); the limit spreads that bend over more layers.
void limit_turn(const MarchContext& march, const MarchState& state, LayerStep& layer_step) {
  const std::vector<Vector3>& current = state.current;
  std::vector<Vector3>& next = layer_step.next;
  const double turn_limit = march.options.maximum_turn_degrees * M_PI / 180.0;
  if (march.smoothed && turn_limit > 0.0 && layer_step.layer > 0)
    for (std::size_t c = 0; c < march.front.column_node.size(); ++c) {
      const Vector3 before = unit_or(current[c] - state.previous[c], layer_step.normal[c]);
      const Vector3 after = unit_or(next[c] - current[c], before);
      const Vector3 axis = before.cross(after);
      if (std::atan2(axis.norm(), before.dot(after)) <= turn_limit) continue;
      next[c] = current[c] + layer_step.step[c] * (Eigen::AngleAxisd(turn_limit, axis.normalized()) * before);
    }
}

// Lines fade their approach to a symmetry plane, keep out of their sheet end's
// conormals, and those in the plane stay in it.
void hold_symmetry_and_sheet_ends(const MarchContext& march, const MarchState& state, LayerStep& layer_step) {
  const Front& front = march.front;
  const SurfaceMesh& surface = march.surface;
  const std::vector<Vector3>& current = state.current;
  const std::vector<double>& marched = state.marched;
  const std::vector<Vector3>& normal = layer_step.normal;
  const std::vector<double>& step = layer_step.step;
  std::vector<Vector3>& next = layer_step.next;
  for (std::size_t c = 0; c < front.column_node.size(); ++c) {
    if (surface.symmetry_tolerance >= 0.0 && !front.on_symmetry[c])
      next[c] = current[c] + step[c] * fade_towards_symmetry(unit_or(next[c] - current[c], normal[c]),
                                                             current[c].y() - surface.symmetry_y,
                                                             marched[c] + step[c]);
    next[c] = keep_in_sheet_end(current[c], next[c], march.lines.conormals[c]);
    if (front.on_symmetry[c]) next[c].y() = surface.symmetry_y;
  }
}

// The faces of `faces` whose cells are invalid, and with the self-intersection check
// the active faces whose cells cross, sorted and once each.
std::vector<int> failing_faces(const MarchContext& march, const MarchState& state,
                               const LayerStep& layer_step, const std::vector<int>& active_faces,
                               const std::vector<int>& faces) {
  std::vector<int> bad = march_detail::invalid_cells(march.front, faces, state.current, layer_step.next);
  const std::size_t invalid = bad.size();
  if (march.options.check_self_intersection) {
    const std::vector<int> crossing =
        march_detail::intersecting_faces(march.front, active_faces, state.current, layer_step.next);
    bad.insert(bad.end(), crossing.begin(), crossing.end());
  }
  if (march.log && !bad.empty())
    march.log->detail("march: layer " + std::to_string(layer_step.layer + 1) + ": " +
                      std::to_string(invalid) + " invalid cells, " + std::to_string(bad.size() - invalid) +
                      " crossing faces");
  std::sort(bad.begin(), bad.end());
  bad.erase(std::unique(bad.begin(), bad.end()), bad.end());
  return bad;
}

// Safety: shorten and locally smooth the steps of failing columns, then stop them.
// Returns the faces that still fail.
std::vector<int> retry_failing_columns(const MarchContext& march, const MarchState& state,
                                       LayerStep& layer_step, MarchReport& report) {
  const Front& front = march.front;
  const std::size_t column_count = front.column_node.size();
  const std::vector<Vector3>& current = state.current;
  const std::vector<Vector3>& normal = layer_step.normal;
  std::vector<double>& step = layer_step.step;
  std::vector<Vector3>& next = layer_step.next;
  std::vector<int> active_faces;
  for (std::size_t face = 0; face < front.faces.size(); ++face)
    if (state.face_active[face]) active_faces.push_back(static_cast<int>(face));
  std::vector<int> bad = failing_faces(march, state, layer_step, active_faces, active_faces);
  // Retries of the failing columns: first their direction is smoothed with their
  // neighbours', then they march along the layer normal (orthogonal to the faces
  // around them), then their step is halved, step_reductions times.
  for (int attempt = 0; attempt <= march.options.step_reductions + 1 && !bad.empty(); ++attempt) {
    const std::vector<Vector3> mean_direction =
        attempt == 0 ? march_detail::neighbour_mean_directions(front, layer_step.column_active, current, next)
                     : normal;
    std::vector<char> touched(column_count, 0);
    for (int face : bad)
      for (int k = 0; k < front.faces[static_cast<std::size_t>(face)].corner_count; ++k)
        touched[static_cast<std::size_t>(
            front.faces[static_cast<std::size_t>(face)].columns[static_cast<std::size_t>(k)])] = 1;
    std::vector<int> recheck;
    for (std::size_t c = 0; c < column_count; ++c) {
      if (!touched[c]) continue;
      if (attempt > 1) {
        step[c] *= 0.5;
        ++report.reduced_steps;
      }
      next[c] = current[c] + step[c] * unit_or(mean_direction[c] + normal[c], normal[c]);
      next[c] = keep_in_sheet_end(current[c], next[c], march.lines.conormals[c]);
      if (front.on_symmetry[c]) next[c].y() = march.surface.symmetry_y;
      for (int face : front.column_faces[c])
        if (state.face_active[static_cast<std::size_t>(face)]) recheck.push_back(face);
    }
    std::sort(recheck.begin(), recheck.end());
    recheck.erase(std::unique(recheck.begin(), recheck.end()), recheck.end());
    bad = failing_faces(march, state, layer_step, active_faces, recheck);
  }
  return bad;
}

// A junction's cut cell (junction.hpp) is closed by the first cells of the sheet faces
// and the wrap face next to it: where one of those stops at the first layer, the split
// face stops with it. (A split face that stops alone leaves the others to close the
// edge.)
void stop_split_faces_with_their_sheets(const Front& front, std::vector<int>& bad) {
  for (const march_detail::Junction& junction : front.junctions) {
    const std::vector<int> group = march_detail::junction_faces(front, junction);
    const bool sheet_stops = std::any_of(group.begin() + 1, group.end(), [&](int face) {
      return std::find(bad.begin(), bad.end(), face) != bad.end();
    });
    if (sheet_stops && std::find(bad.begin(), bad.end(), junction.face) == bad.end())
      bad.push_back(junction.face);
  }
}

// The active faces whose blending stop has come join this layer's stops.
void stop_blended_faces(const MarchState& state, int layer, std::vector<int>& bad, MarchReport& report) {
  for (std::size_t face = 0; face < state.face_active.size(); ++face)
    if (state.face_active[face] && state.stop_at[face] <= layer &&
        std::find(bad.begin(), bad.end(), static_cast<int>(face)) == bad.end()) {
      bad.push_back(static_cast<int>(face));
      ++report.blended_faces;
    }
}

// The slope round this layer's stops (breadth first, one layer per ring of faces).
void slope_round_stops(const MarchContext& march, int layer, const std::vector<int>& bad,
                       std::vector<int>& stop_at) {
  std::vector<int> ring = bad;
  for (int face : bad)
    stop_at[static_cast<std::size_t>(face)] = std::min(stop_at[static_cast<std::size_t>(face)], layer);
  while (!ring.empty()) {
    std::vector<int> next_ring;
    for (int face : ring)
      for (int neighbour : march.lines.face_neighbours[static_cast<std::size_t>(face)]) {
        const int limit = stop_at[static_cast<std::size_t>(face)] + 1;
        if (limit >= static_cast<int>(march.steps.size()) ||
            stop_at[static_cast<std::size_t>(neighbour)] <= limit)
          continue;
        stop_at[static_cast<std::size_t>(neighbour)] = limit;
        next_ring.push_back(neighbour);
      }
    ring = std::move(next_ring);
  }
}

// The stopped faces leave the front; their nodes and centres go to the report.
void record_stops(const MarchContext& march, MarchState& state, int layer, const std::vector<int>& bad) {
  const Front& front = march.front;
  for (int face : bad) {
    state.face_active[static_cast<std::size_t>(face)] = 0;
    const FrontFace& f = front.faces[static_cast<std::size_t>(face)];
    StoppedRegion& region = state.stopped[layer];
    region.layer = layer;
    ++region.faces;
    Vector3 centre = Vector3::Zero();
    for (int k = 0; k < f.corner_count; ++k) {
      const Index node = front.column_node[static_cast<std::size_t>(f.columns[static_cast<std::size_t>(k)])];
      centre += march.surface.points[static_cast<std::size_t>(node)] / f.corner_count;
      state.node_stopped[static_cast<std::size_t>(node)] = 1;
    }
    region.location += centre;
  }
}

// Commit the layer: new points for columns with an active face, then the cells.
// False when no column is left.
bool commit_layer(const Front& front, MarchState& state, const LayerStep& layer_step, BoundaryLayer& result) {
  const std::vector<char> column_active = active_columns(front, state.face_active);
  const std::vector<Vector3>& next = layer_step.next;
  bool any = false;
  for (std::size_t c = 0; c < front.column_node.size(); ++c) {
    if (!column_active[c]) continue;
    any = true;
    result.column_points[c].push_back(static_cast<Index>(result.mesh.points.size()));
    result.mesh.points.push_back(next[c]);
    state.marched[c] += (next[c] - state.current[c]).norm();
    state.direction[c] = unit_or(next[c] - state.current[c], state.direction[c]);
    state.previous[c] = state.current[c];
    state.current[c] = next[c];
  }
  for (std::size_t face = 0; face < front.faces.size(); ++face)
    if (state.face_active[face]) {
      march_detail::add_swept_cell(front, static_cast<int>(face), layer_step.layer, result);
      ++result.face_layers[face];
    }
  return any;
}

// The layers every face reached, the thickness, the stopped regions and the quality
// of the junctions' cut stacks.
void finish_report(const std::vector<double>& steps, MarchState& state, BoundaryLayer& result) {
  MarchReport& report = result.report;
  report.layers_completed = *std::min_element(result.face_layers.begin(), result.face_layers.end());
  for (int layer = 0; layer < report.layers_completed; ++layer)
    report.total_thickness += steps[static_cast<std::size_t>(layer)];
  for (auto& [layer, region] : state.stopped) {
    region.location /= region.faces;
    for (std::size_t k = static_cast<std::size_t>(layer); k < steps.size(); ++k)
      region.thickness_lost += steps[k];
    report.stopped_faces += region.faces;
    report.stopped.push_back(region);
  }
  report.stopped_nodes =
      static_cast<int>(std::count(state.node_stopped.begin(), state.node_stopped.end(), 1));
  report.junctions = static_cast<int>(result.tetrahedron_face.size() / 2);
  for (std::size_t cell = 0; cell < result.mesh.cell_count(CellType::pyramid); ++cell)
    report.junction_minimum_scaled_jacobian =
        std::min(report.junction_minimum_scaled_jacobian,
                 cell_shape(CellType::pyramid, result.mesh.points, result.mesh.cell(CellType::pyramid, cell))
                     .min_corner_jacobian);
  for (std::size_t cell = 0; cell < result.mesh.cell_count(CellType::tetrahedron); ++cell) {
    const Index* t = result.mesh.cell(CellType::tetrahedron, cell);
    auto point = [&](int k) { return result.mesh.points[static_cast<std::size_t>(t[k])]; };
    report.junction_largest_dihedral_degrees =
        std::max(report.junction_largest_dihedral_degrees,
                 largest_dihedral_degrees(point(0), point(1), point(2), point(3)));
  }
}

void log_summary(const BoundaryLayer& result, const Log& log) {
  const MarchReport& report = result.report;
  log.info("march: " + std::to_string(report.layers_completed) + " of " +
           std::to_string(report.layers_requested) + " layers everywhere, first spacing " +
           std::to_string(report.first_spacing) + " m, thickness " + std::to_string(report.total_thickness) +
           " m, " + std::to_string(result.mesh.cell_count()) + " cells");
  if (report.junctions > 0)
    log.info("march: " + std::to_string(report.junctions) +
             " junction(s) of a sheet's free edge with the wall closed; smallest scaled Jacobian of their "
             "pyramids " +
             scientific(report.junction_minimum_scaled_jacobian) +
             ", largest dihedral angle of their "
             "tetrahedra " +
             degrees_text(report.junction_largest_dihedral_degrees) + " deg");
  if (report.thinned_lines > 0)
    log.info("march: " + std::to_string(report.thinned_lines) +
             " lines near the concave corners of a sheet and a wall (a blunt base with a wake) in stacks "
             "down to " +
             scientific(report.thinnest_stack) + " m thick");
  for (const StoppedRegion& region : report.stopped)
    log.warning("march: " + std::to_string(region.faces) + " faces stopped at layer " +
                std::to_string(region.layer) + " near " + point_text(region.location) + " (" +
                scientific(region.thickness_lost) + " m of the wall stack lost)");
}

}  // namespace

BoundaryLayer march_layers(const SurfaceMesh& surface, const MarchOptions& options, const Log* log) {
  const Stopwatch stopwatch;
  check_options(options);
  const std::vector<double> steps = layer_steps(options.spacing);
  const Front front = march_detail::build_front(surface);
  const std::size_t column_count = front.column_node.size();
  const std::size_t face_count = front.faces.size();

  BoundaryLayer result;
  start_result(surface, front, result);
  MarchState state;
  state.current.resize(column_count);
  for (std::size_t c = 0; c < column_count; ++c)
    state.current[c] = surface.points[static_cast<std::size_t>(front.column_node[c])];
  state.face_active.assign(face_count, 1);
  // Blending: a face next to one that stopped at layer k stops at k + 1 at the latest,
  // the next ring at k + 2 …, so the stack slopes down to a stopped region instead of
  // standing over it as a cliff (whose pit the far field's hull could not close).
  state.stop_at = forced_stop_layers(surface, front, options.forced_stops);

  const bool smoothed = options.method == MarchMethod::smoothed;
  const MarchContext march{
      surface, options, front, steps, log, smoothed, line_data(front, options, steps, state.current)};
  state.direction =
      column_normals(front, state.current, state.face_active, true,
                     std::vector<Vector3>(column_count, Vector3::UnitZ()), march.lines.on_wall, 1.0);
  state.marched.assign(column_count, 0.0);
  state.previous = state.current;

  MarchReport& report = result.report;
  report.layers_requested = static_cast<int>(steps.size());
  report.first_spacing = steps.front();
  state.node_stopped.assign(surface.points.size(), 0);

  for (int layer = 0; layer < static_cast<int>(steps.size()); ++layer) {
    LayerStep layer_step;
    layer_step.layer = layer;
    layer_step.column_active = active_columns(front, state.face_active);
    layer_step.release = march.smoothed ? release_weight(options, layer) : 1.0;
    layer_step.normal = layer_normals(march, state, layer_step);
    predict_directions(march, state, layer_step);
    if (march.smoothed) correct_layer(march, state, layer_step, report);
    if (march.smoothed && layer_step.release > 0.0 && options.direction_smoothing_passes > 0)
      smooth_directions(march, state, layer_step);
    limit_turn(march, state, layer_step);
    hold_symmetry_and_sheet_ends(march, state, layer_step);

    std::vector<int> bad = retry_failing_columns(march, state, layer_step, report);
    if (layer == 0 && !bad.empty()) stop_split_faces_with_their_sheets(front, bad);
    stop_blended_faces(state, layer, bad, report);
    if (!bad.empty()) close_pinched_lines(front, state.face_active, bad);
    slope_round_stops(march, layer, bad, state.stop_at);
    record_stops(march, state, layer, bad);

    const bool any = commit_layer(front, state, layer_step, result);
    if (log)
      log->detail("march: layer " + std::to_string(layer + 1) + " of " + std::to_string(steps.size()) + ", " +
                  std::to_string(bad.size()) + " faces stopped");
    if (!any) break;
  }
  march_detail::add_junction_stacks(front, result);
  march_detail::add_boundary_faces(front, options, result);

  finish_report(steps, state, result);
  report.thinned_lines = march.lines.thinned_lines;
  report.thinnest_stack = march.lines.thinnest_stack;
  report.seconds = stopwatch.seconds();
  if (log) log_summary(result, *log);
  return result;
}

}  // namespace mixmesh
