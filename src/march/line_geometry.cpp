#include "line_geometry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>

#include <Eigen/Geometry>

#include "concave_corners.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/mesh/visible_direction.hpp"

namespace mixmesh::march_detail {

namespace {

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

}  // namespace

Vector3 unit_or(const Vector3& vector, const Vector3& fallback) {
  const double length = vector.norm();
  return length > 0.0 ? Vector3(vector / length) : fallback;
}

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
    const Vector3 area = face_area_vector(positions, f.columns.data(), n);
    for (int k = 0; k < n; ++k) {
      const auto column = static_cast<std::size_t>(f.columns[static_cast<std::size_t>(k)]);
      const double weight = !f.wall && on_wall[column] ? wake_weight : 1.0;
      if (!angle_weighted) {
        sum[column] += weight * area;
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
    add_corner(column(k), corner.weight, edge(k + 1), edge(k - 1),
               face_area_vector(positions, f.columns.data(), n));
  }
  std::vector<Vector3> normals(positions.size());
  for (std::size_t c = 0; c < positions.size(); ++c) {
    if (front.on_symmetry[c]) sum[c].y() = 0.0;
    normals[c] = unit_or(sum[c], fallback[c]);
  }
  return normals;
}

Vector3 keep_in_sheet_end(const Vector3& from, const Vector3& to, const std::vector<Vector3>& basis) {
  if (basis.empty()) return to;
  Vector3 step = to - from;
  const double length = step.norm();
  for (const Vector3& unit : basis) step -= step.dot(unit) * unit;
  const double kept = step.norm();
  if (!(kept > 1e-3 * length)) return to;  // nothing left to march along: leave the line as it was
  return from + (length / kept) * step;
}

Vector3 off_the_sheet(const Vector3& normal, const Vector3& sheet_normal) {
  const double least = std::sqrt(0.5);  // sin 45 degrees
  const double along = normal.dot(sheet_normal);
  if (sheet_normal.squaredNorm() == 0.0 || along >= least) return normal;
  const Vector3 in_plane = normal - along * sheet_normal;
  if (in_plane.norm() < 1e-12) return sheet_normal;
  return std::sqrt(1.0 - least * least) * in_plane.normalized() + least * sheet_normal;
}

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

Vector3 fade_towards_symmetry(const Vector3& direction, double distance, double height) {
  if (distance == 0.0 || direction.y() * distance >= 0.0) return direction;
  Vector3 faded = direction;
  faded.y() *= 1.0 - std::exp(-std::abs(distance) / height);
  return unit_or(faded, direction);
}

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

}  // namespace mixmesh::march_detail
