#include "mixmesh/march/march_layers.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>

#include <Eigen/Geometry>

#include "concave_corners.hpp"
#include "front.hpp"
#include "junction.hpp"
#include "layer_checks.hpp"
#include "layer_mesh.hpp"
#include "layer_solver.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/mesh/visible_direction.hpp"

namespace mixmesh {

namespace {

using march_detail::Front;
using march_detail::FrontFace;

Vector3 unit_or(const Vector3& vector, const Vector3& fallback) {
  const double length = vector.norm();
  return length > 0.0 ? Vector3(vector / length) : fallback;
}

// Column normals of the current layer from its active faces: angle-weighted corner
// normals (the direction most nearly orthogonal to all faces around a node) or, for
// the baseline, area-weighted face normals. Symmetry columns keep y = 0.
// Wake faces count with weight `wake_weight` at lines that also start on a wall face
// (the trailing edge), so the first grid line there is orthogonal to the wall.
std::vector<Vector3> column_normals(const Front& front, const std::vector<Vector3>& positions,
                                    const std::vector<char>& face_active, bool angle_weighted,
                                    const std::vector<Vector3>& fallback, const std::vector<char>& on_wall,
                                    double wake_weight) {
  std::vector<Vector3> sum(positions.size(), Vector3::Zero());
  // A corner of nearly 180 degrees has no normal of its own (the cross product of two
  // almost opposite edges points anywhere round them): it takes its face's. The split
  // face at a blunt base's end is one: the base's node lies straight along the opening
  // between the two lines of the sheet, and the corner's normal pointed downstream.
  auto add_corner = [&](std::size_t column, double weight, const Vector3& out, const Vector3& in,
                        const Vector3& face_area) {
    const Vector3 corner = out.cross(in);
    const double angle = std::atan2(corner.norm(), out.dot(in));
    const bool straight = angle > 5.0 * M_PI / 6.0 && face_area.norm() > 0.0;
    sum[column] += weight * angle * unit_or(straight ? face_area : corner, Vector3::Zero());
  };
  // Corners with an edge of no length yet (lines of a split or wrap face that start at
  // one point) wait for the normals the other corners give.
  struct Unopened {
    std::size_t face;
    int corner;
    double weight;
  };
  std::vector<Unopened> unopened;
  for (std::size_t face = 0; face < front.faces.size(); ++face) {
    if (!face_active[face]) continue;
    const FrontFace& f = front.faces[face];
    const int n = f.corner_count;
    auto at = [&](int k) -> const Vector3& {
      return positions[static_cast<std::size_t>(f.columns[static_cast<std::size_t>((k + n) % n)])];
    };
    Vector3 area = Vector3::Zero();
    for (int k = 0; k < n; ++k) area += at(k).cross(at(k + 1));
    for (int k = 0; k < n; ++k) {
      const auto column = static_cast<std::size_t>(f.columns[static_cast<std::size_t>(k)]);
      const double weight = !f.wall && on_wall[column] ? wake_weight : 1.0;
      if (!angle_weighted) {
        sum[column] += 0.5 * weight * area;
        continue;
      }
      if (at(k + 1) == at(k) || at(k - 1) == at(k)) {
        unopened.push_back({face, k, weight});
        continue;
      }
      add_corner(column, weight, at(k + 1) - at(k), at(k - 1) - at(k), area);
    }
  }
  // Such an edge is the edge of the quad it opens into: it opens along the difference of
  // its two lines' normals from the other faces (one line above the sheet, one below).
  const std::vector<Vector3> provisional = unopened.empty() ? std::vector<Vector3>() : sum;
  for (const Unopened& corner : unopened) {
    const FrontFace& f = front.faces[corner.face];
    const int n = f.corner_count;
    const int k = corner.corner;
    auto column = [&](int corner) {
      return static_cast<std::size_t>(f.columns[static_cast<std::size_t>((corner + n) % n)]);
    };
    auto edge = [&](int to) -> Vector3 {
      if (positions[column(to)] != positions[column(k)]) return positions[column(to)] - positions[column(k)];
      return unit_or(provisional[column(to)], Vector3::Zero()) -
             unit_or(provisional[column(k)], Vector3::Zero());
    };
    Vector3 area = Vector3::Zero();
    for (int c = 0; c < n; ++c) area += positions[column(c)].cross(positions[column(c + 1)]);
    add_corner(column(k), corner.weight, edge(k + 1), edge(k - 1), area);
  }
  std::vector<Vector3> normals(positions.size());
  for (std::size_t c = 0; c < positions.size(); ++c) {
    if (front.on_symmetry[c]) sum[c].y() = 0.0;
    normals[c] = unit_or(sum[c], fallback[c]);
  }
  return normals;
}

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

// The points of the lines that start on a wall and also on a sheet (where a sheet
// leaves the wall: a trailing edge), once per sheet face corner.
std::vector<Vector3> trailing_edge_points(const Front& front, const std::vector<Vector3>& points,
                                          const std::vector<char>& on_wall) {
  std::vector<Vector3> attachment;
  for (const FrontFace& f : front.faces)
    if (!f.wall)
      for (int k = 0; k < f.corner_count; ++k)
        if (on_wall[static_cast<std::size_t>(f.columns[static_cast<std::size_t>(k)])])
          attachment.push_back(points[static_cast<std::size_t>(f.columns[static_cast<std::size_t>(k)])]);
  return attachment;
}

// Outward conormals (in the surface, across the edge) of the free edges at a sheet's
// downstream end (a wake's end): the free sheet edges that are left once the side edges
// have their wrap faces (front.cpp, add_wrap_faces), but for those in the symmetry plane,
// at columns that start on the sheet only. Such a line keeps out of these directions, so
// the side faces of the end stay in the surface the edge sweeps along the sheet normal:
// a plane end gives plane side faces, exact to the last bit. Lines drifting 1e-15 off
// that plane made the hull there so nearly flat that the far-field tetrahedralisation
// filled it with slivers of no volume. Per line, an orthonormal basis of its conormals
// (empty for most lines).
std::vector<std::vector<Vector3>> end_conormals(const Front& front, const std::vector<Vector3>& points,
                                                const std::vector<char>& on_wall) {
  std::vector<std::vector<Vector3>> conormals(points.size());
  if (std::none_of(on_wall.begin(), on_wall.end(), [](char wall) { return wall != 0; })) return conormals;
  for (const march_detail::FreeEdge& edge : front.free_edges) {
    const FrontFace& f = front.faces[static_cast<std::size_t>(edge.face)];
    const int n = f.corner_count;
    if (f.wall || f.wrap) continue;
    const auto first = static_cast<std::size_t>(f.columns[static_cast<std::size_t>(edge.corner)]);
    const auto second = static_cast<std::size_t>(f.columns[static_cast<std::size_t>((edge.corner + 1) % n)]);
    if (front.on_symmetry[first] && front.on_symmetry[second]) continue;
    const Vector3 area = face_area_vector(points, f.columns.data(), n);
    const Vector3 conormal = unit_or((points[second] - points[first]).cross(area), Vector3::Zero());
    if (conormal.squaredNorm() == 0.0) continue;
    for (std::size_t column : {first, second})
      if (!on_wall[column]) conormals[column].push_back(conormal);
  }
  // Each line's conormals as an orthonormal basis (Gram-Schmidt), once for all layers.
  for (std::vector<Vector3>& column : conormals) {
    std::vector<Vector3> basis;
    for (const Vector3& conormal : column) {
      Vector3 direction = conormal;
      for (const Vector3& unit : basis) direction -= direction.dot(unit) * unit;
      if (direction.norm() > 1e-6) basis.push_back(direction.normalized());
    }
    column = std::move(basis);
  }
  return conormals;
}

// The step from `from` to `to` without its parts along the orthonormal `basis` of a
// line's end conormals, scaled back to its length.
Vector3 keep_in_sheet_end(const Vector3& from, const Vector3& to, const std::vector<Vector3>& basis) {
  if (basis.empty()) return to;
  Vector3 step = to - from;
  const double length = step.norm();
  for (const Vector3& unit : basis) step -= step.dot(unit) * unit;
  const double kept = step.norm();
  if (!(kept > 1e-3 * length)) return to;  // nothing left to march along: leave the line as it was
  return from + (length / kept) * step;
}

// Per line, the distance of its surface point from the nearest line that starts on a
// wall and also on a sheet (a trailing-edge line); 0 on wall lines and everywhere when
// there is no sheet.
std::vector<double> distance_from_wall_lines(const Front& front, const std::vector<Vector3>& points,
                                             const std::vector<char>& on_wall) {
  const std::vector<Vector3> attachment = trailing_edge_points(front, points, on_wall);
  std::vector<double> distance(points.size(), 0.0);
  if (attachment.empty()) return distance;
  for (std::size_t c = 0; c < points.size(); ++c) {
    if (on_wall[c]) continue;
    double nearest = (points[c] - attachment.front()).squaredNorm();
    for (const Vector3& point : attachment) nearest = std::min(nearest, (points[c] - point).squaredNorm());
    distance[c] = std::sqrt(nearest);
  }
  return distance;
}

// Per line on a sheet, the unit normal of the sheet faces on its side (pointing away
// from the sheet); zero for the other lines.
std::vector<Vector3> sheet_side_normals(const Front& front, const std::vector<Vector3>& points) {
  std::vector<Vector3> normal(points.size(), Vector3::Zero());
  for (const FrontFace& f : front.faces) {
    if (f.wall || f.wrap) continue;
    const Vector3 area = face_area_vector(points, f.columns.data(), f.corner_count);
    for (int k = 0; k < f.corner_count; ++k)
      normal[static_cast<std::size_t>(f.columns[static_cast<std::size_t>(k)])] += area;
  }
  for (Vector3& v : normal) v = unit_or(v, Vector3::Zero());
  return normal;
}

// A line that starts on a wall and on a sheet leaves the sheet's plane by at least 45
// degrees on its own side. Where the wall there faces along the sheet (a blunt base
// with the wake leaving from its middle) the wall's normal lies in the sheet's plane,
// and the lines above and below would march along the same direction.
Vector3 off_the_sheet(const Vector3& normal, const Vector3& sheet_normal) {
  const double least = std::sqrt(0.5);  // sin 45 degrees
  const double along = normal.dot(sheet_normal);
  if (sheet_normal.squaredNorm() == 0.0 || along >= least) return normal;
  const Vector3 in_plane = normal - along * sheet_normal;
  if (in_plane.norm() < 1e-12) return sheet_normal;
  return std::sqrt(1.0 - least * least) * in_plane.normalized() + least * sheet_normal;
}

// A first line below the plane of one of its wall faces inverts that face's first cell.
// The angle-weighted normal can do that where faces of very different size and direction
// meet: at a swept wing's sharp trailing edge on the symmetry plane, the line (held in
// the plane) leaned under the upper surface's last face (random wing 12 of seed 12).
// Such a line takes the direction that sees its wall faces best (in the plane for a
// symmetry line).
void see_every_wall_face(const Front& front, const std::vector<Vector3>& points,
                         const std::vector<char>& face_active, const std::vector<char>& on_wall,
                         const std::vector<char>& junction_line, std::vector<Vector3>& normal) {
  // The wall faces' unit normals once per layer; the fan of a line only where it leans
  // under one of them (a few lines, every layer).
  std::vector<Vector3> unit(front.faces.size(), Vector3::Zero());
  for (std::size_t face = 0; face < front.faces.size(); ++face) {
    const FrontFace& f = front.faces[face];
    if (!f.wall || !face_active[face]) continue;
    const Vector3 area = face_area_vector(points, f.columns.data(), f.corner_count);
    if (area.norm() > 0.0) unit[face] = area.normalized();
  }
  for (std::size_t c = 0; c < points.size(); ++c) {
    if (!on_wall[c] || junction_line[c]) continue;
    const auto& faces = front.column_faces[c];
    const bool below = std::any_of(faces.begin(), faces.end(), [&](int face) {
      const Vector3& face_normal = unit[static_cast<std::size_t>(face)];
      return !face_normal.isZero() && face_normal.dot(normal[c]) <= 0.0;
    });
    if (!below) continue;
    std::vector<Vector3> fan = wall_face_normals(front, points, face_active, static_cast<int>(c));
    if (front.on_symmetry[c])
      for (Vector3& face_normal : fan)
        face_normal = unit_or(Vector3(face_normal.x(), 0.0, face_normal.z()), face_normal);
    const Vector3 seeing = visible_direction(fan);
    if (seeing.squaredNorm() > 0.0) normal[c] = seeing;
  }
}

// The last layer's step of each line: at least `fraction` of the shortest edge of the
// active front faces at the line (MarchOptions::outer_layer_height). Lines on no active
// face keep their step.
void raise_to_outer_height(const Front& front, const std::vector<Vector3>& current,
                           const std::vector<char>& face_active, double fraction, std::vector<double>& step) {
  std::vector<double> shortest(step.size(), std::numeric_limits<double>::infinity());
  for (std::size_t face = 0; face < front.faces.size(); ++face) {
    if (!face_active[face]) continue;
    const FrontFace& front_face = front.faces[face];
    for (int k = 0; k < front_face.corner_count; ++k) {
      const auto a = static_cast<std::size_t>(front_face.columns[static_cast<std::size_t>(k)]);
      const auto b = static_cast<std::size_t>(
          front_face.columns[static_cast<std::size_t>((k + 1) % front_face.corner_count)]);
      const double length = (current[a] - current[b]).norm();
      shortest[a] = std::min(shortest[a], length);
      shortest[b] = std::min(shortest[b], length);
    }
  }
  for (std::size_t c = 0; c < step.size(); ++c)
    if (std::isfinite(shortest[c])) step[c] = std::max(step[c], fraction * shortest[c]);
}

// The step of a line towards a symmetry plane fades where the layers grow as thick as
// the line is far from the plane: the lines in the plane march in it, so a neighbour
// that keeps moving towards it (the upper side of a wing or wake with dihedral) closes
// the row of cells between them. On a wake, whose layers thicken to a metre, this
// stopped the row next to the plane on ordinary wings with 2-8 degrees of dihedral.
Vector3 fade_towards_symmetry(const Vector3& direction, double distance, double height) {
  if (distance == 0.0 || direction.y() * distance >= 0.0) return direction;
  Vector3 faded = direction;
  faded.y() *= 1.0 - std::exp(-std::abs(distance) / height);
  return unit_or(faded, direction);
}

// Adds to `stopping` (faces that stop at this layer) the faces that would otherwise
// meet a line in two separate fans: where the faces still growing round a line are
// split by stopped ones into groups that share no edge at the line, the layer's cells
// of different groups touch along that line alone and the hull pinches there (an edge
// on four hull faces). All but the largest group stop too, until no line is pinched.
void close_pinched_lines(const Front& front, const std::vector<char>& face_active,
                         std::vector<int>& stopping) {
  std::vector<char> growing = face_active;
  for (int face : stopping) growing[static_cast<std::size_t>(face)] = 0;
  std::vector<int> lines;
  auto collect = [&](int face) {
    const FrontFace& f = front.faces[static_cast<std::size_t>(face)];
    for (int k = 0; k < f.corner_count; ++k) lines.push_back(f.columns[static_cast<std::size_t>(k)]);
  };
  for (int face : stopping) collect(face);
  while (!lines.empty()) {
    const int line = lines.back();
    lines.pop_back();
    std::vector<int> faces;
    for (int face : front.column_faces[static_cast<std::size_t>(line)])
      if (growing[static_cast<std::size_t>(face)]) faces.push_back(face);
    if (faces.size() < 2) continue;
    // Groups of faces joined by an edge at the line (union-find over the few faces).
    std::vector<std::size_t> group(faces.size());
    for (std::size_t i = 0; i < faces.size(); ++i) group[i] = i;
    auto root = [&](std::size_t i) {
      while (group[i] != i) i = group[i] = group[group[i]];
      return i;
    };
    auto neighbours = [&](int face) {
      const FrontFace& f = front.faces[static_cast<std::size_t>(face)];
      std::array<int, 2> pair{-1, -1};
      for (int k = 0; k < f.corner_count; ++k)
        if (f.columns[static_cast<std::size_t>(k)] == line)
          pair = {f.columns[static_cast<std::size_t>((k + 1) % f.corner_count)],
                  f.columns[static_cast<std::size_t>((k + f.corner_count - 1) % f.corner_count)]};
      return pair;
    };
    for (std::size_t i = 0; i < faces.size(); ++i)
      for (std::size_t j = i + 1; j < faces.size(); ++j) {
        const std::array<int, 2> a = neighbours(faces[i]), b = neighbours(faces[j]);
        if (a[0] == b[0] || a[0] == b[1] || a[1] == b[0] || a[1] == b[1]) group[root(i)] = root(j);
      }
    std::vector<std::size_t> size(faces.size(), 0);
    for (std::size_t i = 0; i < faces.size(); ++i) ++size[root(i)];
    const std::size_t largest =
        static_cast<std::size_t>(std::max_element(size.begin(), size.end()) - size.begin());
    for (std::size_t i = 0; i < faces.size(); ++i)
      if (root(i) != largest) {
        growing[static_cast<std::size_t>(faces[i])] = 0;
        stopping.push_back(faces[i]);
        collect(faces[i]);
      }
  }
}

// Per line (and per face) what the surface fixes for all layers.
struct LineData {
  std::vector<std::vector<int>> face_neighbours;
  std::vector<char> on_wall;
  std::vector<std::vector<Vector3>> conormals;
  // Wake lines thicken and relax their growth downstream (spacing.hpp, wake_layer_steps),
  // and lines near a concave corner of a sheet and a wall keep a thinner stack
  // (concave_corners.hpp); only those lines keep their own steps (empty: the wall's).
  std::vector<std::vector<double>> own_steps;
  int thinned_lines = 0;        // lines near a concave corner whose stack was thinned
  double thinnest_stack = 0.0;  // the thinnest of those stacks (m)
  std::vector<char> junction_line;
  std::vector<Vector3> sheet_normal;
};

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

std::vector<std::vector<int>> face_neighbours(const Front& front) {
  std::vector<std::vector<int>> neighbours(front.faces.size());
  for (const march_detail::SharedEdge& edge : front.shared_edges) {
    neighbours[static_cast<std::size_t>(edge.faces[0])].push_back(edge.faces[1]);
    neighbours[static_cast<std::size_t>(edge.faces[1])].push_back(edge.faces[0]);
  }
  return neighbours;
}

std::vector<char> wall_lines(const Front& front) {
  std::vector<char> on_wall(front.column_node.size(), 0);
  for (const FrontFace& f : front.faces)
    if (f.wall)
      for (int k = 0; k < f.corner_count; ++k)
        on_wall[static_cast<std::size_t>(f.columns[static_cast<std::size_t>(k)])] = 1;
  return on_wall;
}

std::vector<std::vector<double>> line_wake_steps(const Front& front, const MarchOptions& options,
                                                 const std::vector<double>& steps,
                                                 const std::vector<Vector3>& points,
                                                 const std::vector<char>& on_wall) {
  std::vector<std::vector<double>> wake_steps(points.size());
  if (options.wake_spread_degrees > 0.0) {
    const std::vector<double> distance = distance_from_wall_lines(front, points, on_wall);
    for (std::size_t c = 0; c < points.size(); ++c)
      if (!on_wall[c]) wake_steps[c] = wake_layer_steps(steps, distance[c], options.wake_spread_degrees);
  }
  return wake_steps;
}

std::vector<char> junction_lines(const Front& front) {
  std::vector<char> junction_line(front.column_node.size(), 0);
  for (const march_detail::Junction& junction : front.junctions)
    for (int k : {0, 3})
      junction_line[static_cast<std::size_t>(
          front.faces[static_cast<std::size_t>(junction.face)].columns[static_cast<std::size_t>(k)])] = 1;
  return junction_line;
}

// The lines near a concave corner of a sheet and a wall (a blunt base with the wake
// leaving its middle) keep every layer in a stack no thicker than the corner allows.
void thin_near_concave_corners(const Front& front, const std::vector<double>& steps,
                               const std::vector<Vector3>& points, LineData& lines) {
  const std::vector<march_detail::ConcaveCorner> corners = march_detail::concave_corners(front, points);
  if (corners.empty()) return;
  const std::vector<double> limit = march_detail::corner_thickness_limits(corners, points);
  for (std::size_t c = 0; c < points.size(); ++c) {
    if (!std::isfinite(limit[c])) continue;
    const std::vector<double>& own = lines.own_steps[c].empty() ? steps : lines.own_steps[c];
    if (std::accumulate(own.begin(), own.end(), 0.0) <= limit[c]) continue;
    lines.own_steps[c] = steps_within_thickness(own, limit[c]);
    lines.thinnest_stack = lines.thinned_lines == 0 ? limit[c] : std::min(lines.thinnest_stack, limit[c]);
    ++lines.thinned_lines;
  }
}

// `points`: the lines' surface points.
LineData line_data(const Front& front, const MarchOptions& options, const std::vector<double>& steps,
                   const std::vector<Vector3>& points) {
  LineData lines;
  lines.face_neighbours = face_neighbours(front);
  lines.on_wall = wall_lines(front);
  lines.conormals = end_conormals(front, points, lines.on_wall);
  lines.own_steps = line_wake_steps(front, options, steps, points, lines.on_wall);
  thin_near_concave_corners(front, steps, points, lines);
  lines.junction_line = junction_lines(front);
  lines.sheet_normal = sheet_side_normals(front, points);
  return lines;
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
