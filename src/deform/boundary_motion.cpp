// From a Motion to the prescribed displacement and rotation of every boundary node.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <unordered_map>

#include "deform/rotation.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/deform/deform.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"

namespace mixmesh::deform {

namespace {

// Boundary faces (volume meshes) or edges (planar meshes) as node lists with markers.
struct BoundaryElements {
  std::vector<std::vector<Index>> nodes;
  std::vector<int> markers;
};

BoundaryElements boundary_elements(const MixedMesh& mesh) {
  BoundaryElements elements;
  if (mesh.planar()) {
    for (std::size_t edge = 0; edge < mesh.boundary_edges.markers.size(); ++edge) {
      elements.nodes.push_back(
          {mesh.boundary_edges.nodes[2 * edge], mesh.boundary_edges.nodes[2 * edge + 1]});
      elements.markers.push_back(mesh.boundary_edges.markers[edge]);
    }
    return elements;
  }
  for (FaceType type : all_face_types) {
    const int count = node_count(type);
    for (std::size_t face = 0; face < mesh.face_count(type); ++face) {
      elements.nodes.emplace_back(mesh.face(type, face), mesh.face(type, face) + count);
      elements.markers.push_back(mesh.faces(type).markers[face]);
    }
  }
  return elements;
}

std::string marker_list(const MixedMesh& mesh) {
  std::string list;
  for (const std::string& name : mesh.marker_names) list += (list.empty() ? "" : ", ") + name;
  return list.empty() ? "none" : list;
}

int require_marker(const MixedMesh& mesh, const std::string& name, const std::string& user) {
  const int id = mesh.find_marker(name);
  if (id < 0)
    throw Error("motion: " + user + " names marker '" + name +
                "', which the mesh does not have (markers: " + marker_list(mesh) + ")");
  return id;
}

// Unit normal of a symmetry marker's plane (line in a planar mesh), checked flat.
Vector3 symmetry_normal(const MixedMesh& mesh, const BoundaryElements& elements, int marker,
                        const std::string& name) {
  Vector3 normal = Vector3::Zero();
  Vector3 centre = Vector3::Zero();
  std::size_t count = 0;
  double extent = 0.0;
  for (std::size_t element = 0; element < elements.nodes.size(); ++element) {
    if (elements.markers[element] != marker) continue;
    const auto& nodes = elements.nodes[element];
    if (nodes.size() == 2) {
      const Vector3 along =
          mesh.points[static_cast<std::size_t>(nodes[1])] - mesh.points[static_cast<std::size_t>(nodes[0])];
      // Orient every edge the same way before summing.
      const Vector3 in_plane(-along.y(), along.x(), 0.0);
      normal += normal.dot(in_plane) < 0.0 ? -in_plane : in_plane;
    } else {
      normal += face_area_vector(mesh.points, nodes.data(), static_cast<int>(nodes.size()));
    }
    for (Index node : nodes) centre += mesh.points[static_cast<std::size_t>(node)];
    count += nodes.size();
  }
  if (count == 0 || normal.norm() == 0.0) throw Error("motion: symmetry marker '" + name + "' has no faces");
  normal.normalize();
  centre /= static_cast<double>(count);
  double off_plane = 0.0;
  for (std::size_t element = 0; element < elements.nodes.size(); ++element) {
    if (elements.markers[element] != marker) continue;
    for (Index node : elements.nodes[element]) {
      const Vector3 offset = mesh.points[static_cast<std::size_t>(node)] - centre;
      off_plane = std::max(off_plane, std::abs(offset.dot(normal)));
      extent = std::max(extent, offset.norm());
    }
  }
  if (off_plane > 1e-6 * std::max(extent, 1e-300)) {
    std::ostringstream message;
    message << "motion: symmetry marker '" << name << "' is not flat (a node lies " << off_plane
            << " off its mean plane); only planes can be symmetry markers";
    throw Error(message.str());
  }
  return normal;
}

// The mesh node of every row of a mode or surface field: by index, or the body node
// nearest to the row's position.
std::vector<Index> field_node_indices(const Body& body, const std::vector<char>& on_body,
                                      const std::vector<Vector3>& points) {
  const NodeField& field = body.field;
  std::vector<Index> nodes;
  if (field.positions.empty()) {
    for (std::size_t entry = 0; entry < field.nodes.size(); ++entry) {
      const Index node = field.nodes[entry];
      if (node < 0 || static_cast<std::size_t>(node) >= points.size() ||
          !on_body[static_cast<std::size_t>(node)])
        throw Error("motion: body '" + body.name + "': field row " + std::to_string(entry + 1) +
                    " names node " + std::to_string(node) + ", which is not on the body's markers");
      nodes.push_back(node);
    }
    return nodes;
  }
  // Bucket the body's nodes on a grid of about one node per cell.
  std::vector<Index> candidates;
  Eigen::AlignedBox3d box;
  for (std::size_t node = 0; node < points.size(); ++node)
    if (on_body[node]) {
      candidates.push_back(static_cast<Index>(node));
      box.extend(points[node]);
    }
  if (candidates.empty()) throw Error("motion: body '" + body.name + "' has no boundary nodes");
  const double size = std::max(box.diagonal().norm(), 1e-300);
  const double tolerance = 1e-6 * size;
  const double cell = size / std::max(1.0, std::cbrt(static_cast<double>(candidates.size())));
  std::unordered_map<std::uint64_t, std::vector<Index>> grid;
  auto key = [&](long x, long y, long z) {
    return (static_cast<std::uint64_t>(x & 0x1FFFFF) << 42) |
           (static_cast<std::uint64_t>(y & 0x1FFFFF) << 21) | static_cast<std::uint64_t>(z & 0x1FFFFF);
  };
  auto coordinate = [&](double value, double low) {
    return static_cast<long>(std::floor((value - low) / cell));
  };
  const Vector3 low = box.min();
  for (Index node : candidates) {
    const Vector3& p = points[static_cast<std::size_t>(node)];
    grid[key(coordinate(p.x(), low.x()), coordinate(p.y(), low.y()), coordinate(p.z(), low.z()))].push_back(
        node);
  }
  for (std::size_t entry = 0; entry < field.positions.size(); ++entry) {
    const Vector3& position = field.positions[entry];
    const long x = coordinate(position.x(), low.x());
    const long y = coordinate(position.y(), low.y());
    const long z = coordinate(position.z(), low.z());
    Index best = -1;
    double best_distance = std::numeric_limits<double>::infinity();
    for (long dx = -1; dx <= 1; ++dx)
      for (long dy = -1; dy <= 1; ++dy)
        for (long dz = -1; dz <= 1; ++dz) {
          const auto found = grid.find(key(x + dx, y + dy, z + dz));
          if (found == grid.end()) continue;
          for (Index node : found->second) {
            const double distance = (points[static_cast<std::size_t>(node)] - position).norm();
            if (distance < best_distance) {
              best_distance = distance;
              best = node;
            }
          }
        }
    if (best < 0 || best_distance > tolerance) {
      std::ostringstream message;
      message << "motion: body '" << body.name << "': field row " << entry + 1 << " at (" << position.x()
              << ", " << position.y() << ", " << position.z() << ") matches no node of the body";
      throw Error(message.str());
    }
    nodes.push_back(best);
  }
  return nodes;
}

}  // namespace

std::size_t BoundaryMotion::count(NodeRole role) const {
  return static_cast<std::size_t>(std::count(roles.begin(), roles.end(), role));
}

double BoundaryMotion::largest_displacement() const {
  double largest = 0.0;
  for (const Vector3& entry : displacement) largest = std::max(largest, entry.norm());
  return largest;
}

BoundaryMotion boundary_motion(const MixedMesh& mesh, const MixedMesh& reference, const Motion& motion,
                               int step) {
  const std::size_t points = mesh.points.size();
  if (reference.points.size() != points)
    throw Error("motion: the reference mesh has " + std::to_string(reference.points.size()) +
                " points, the mesh " + std::to_string(points));
  BoundaryMotion boundary;
  boundary.roles.assign(points, NodeRole::interior);
  boundary.displacement.assign(points, Vector3::Zero());
  boundary.rotation.assign(points, Vector3::Zero());
  boundary.slide_normal.assign(points, Vector3::Zero());
  boundary.body.assign(points, -1);
  boundary.marker_roles.assign(mesh.marker_names.size(), MarkerRole::fixed);
  const BoundaryElements elements = boundary_elements(mesh);
  const bool planar = mesh.planar();

  // Symmetry markers: nodes slide in the plane; a node on two planes is held fixed.
  for (const std::string& name : motion.symmetry) {
    const int marker = require_marker(mesh, name, "symmetry");
    boundary.marker_roles[static_cast<std::size_t>(marker)] = MarkerRole::sliding;
    const Vector3 normal = symmetry_normal(mesh, elements, marker, name);
    for (std::size_t element = 0; element < elements.nodes.size(); ++element) {
      if (elements.markers[element] != marker) continue;
      for (Index node : elements.nodes[element]) {
        const std::size_t at = static_cast<std::size_t>(node);
        if (boundary.roles[at] == NodeRole::sliding &&
            boundary.slide_normal[at].cross(normal).norm() > 1e-9) {
          boundary.roles[at] = NodeRole::prescribed;
          boundary.slide_normal[at] = Vector3::Zero();
        } else if (boundary.roles[at] == NodeRole::interior) {
          boundary.roles[at] = NodeRole::sliding;
          boundary.slide_normal[at] = normal;
        }
      }
    }
  }
  for (const Body& body : motion.bodies)
    for (const std::string& name : body.markers) {
      const int marker = require_marker(mesh, name, "body '" + body.name + "'");
      if (boundary.marker_roles[static_cast<std::size_t>(marker)] == MarkerRole::sliding)
        throw Error("motion: marker '" + name + "' is both a symmetry plane and part of body '" + body.name +
                    "'");
      boundary.marker_roles[static_cast<std::size_t>(marker)] = MarkerRole::moving;
    }
  // Fixed markers hold their nodes (over sliding ones).
  for (std::size_t element = 0; element < elements.nodes.size(); ++element) {
    const int marker = elements.markers[element];
    if (marker >= 0 && static_cast<std::size_t>(marker) < boundary.marker_roles.size() &&
        boundary.marker_roles[static_cast<std::size_t>(marker)] != MarkerRole::fixed)
      continue;
    for (Index node : elements.nodes[element]) {
      boundary.roles[static_cast<std::size_t>(node)] = NodeRole::prescribed;
      boundary.slide_normal[static_cast<std::size_t>(node)] = Vector3::Zero();
    }
  }

  // Moving bodies.
  std::vector<int> owner(points, -1);
  for (std::size_t body_index = 0; body_index < motion.bodies.size(); ++body_index) {
    const Body& body = motion.bodies[body_index];
    std::vector<int> body_markers;
    for (const std::string& name : body.markers) body_markers.push_back(mesh.find_marker(name));
    std::vector<char> on_body(points, 0);
    for (std::size_t element = 0; element < elements.nodes.size(); ++element)
      if (std::find(body_markers.begin(), body_markers.end(), elements.markers[element]) !=
          body_markers.end())
        for (Index node : elements.nodes[element]) on_body[static_cast<std::size_t>(node)] = 1;

    // Target positions of this body's nodes, from the reference mesh.
    std::vector<Vector3> target(points);
    const double fraction = static_cast<double>(step) / std::max(motion.steps, 1);
    const bool rigid = body.law == MotionLaw::rigid || body.law == MotionLaw::pitch_plunge ||
                       body.law == MotionLaw::trajectory;
    RigidPose pose;
    Eigen::Matrix3d step_rotation = Eigen::Matrix3d::Identity();
    if (rigid) {
      pose = body_pose(body, step, motion.steps);
      // From the mesh the step deforms: the previous pose when incremental.
      step_rotation =
          motion.incremental
              ? Eigen::Matrix3d(pose.rotation * body_pose(body, step - 1, motion.steps).rotation.transpose())
              : pose.rotation;
    }
    for (std::size_t node = 0; node < points; ++node)
      if (on_body[node]) target[node] = rigid ? pose.apply(reference.points[node]) : reference.points[node];
    if (!rigid) {
      const std::vector<Index> field_nodes = field_node_indices(body, on_body, reference.points);
      for (std::size_t entry = 0; entry < field_nodes.size(); ++entry) {
        const std::size_t at = static_cast<std::size_t>(field_nodes[entry]);
        const Vector3 change = body.law == MotionLaw::mode
                                   ? Vector3(body.scale * body.field.values[entry])
                                   : Vector3(body.field.values[entry] - reference.points[at]);
        target[at] = reference.points[at] + fraction * change;
      }
    }
    const Vector3 rotation_vector = detail::rotation_vector(step_rotation);
    for (std::size_t node = 0; node < points; ++node) {
      if (!on_body[node]) continue;
      const Vector3 displacement = target[node] - mesh.points[node];
      if (owner[node] >= 0 &&
          (boundary.displacement[node] - displacement).norm() > 1e-9 * (1.0 + displacement.norm())) {
        const Vector3& at = mesh.points[node];
        std::ostringstream message;
        message << "motion: node " << node << " at (" << at.x() << ", " << at.y() << ", " << at.z()
                << ") belongs to body '" << motion.bodies[static_cast<std::size_t>(owner[node])].name
                << "' and body '" << body.name << "', which move it differently";
        throw Error(message.str());
      }
      owner[node] = static_cast<int>(body_index);
      boundary.body[node] = static_cast<int>(body_index);
      boundary.roles[node] = NodeRole::prescribed;
      boundary.slide_normal[node] = Vector3::Zero();
      boundary.displacement[node] = displacement;
      boundary.rotation[node] = rigid ? rotation_vector : Vector3::Zero();
    }
    if (rigid) continue;
    // Mode and surface motions: the rotation of each node's boundary star, fitted by
    // direction (rotation.cpp says why).
    std::vector<std::vector<Index>> neighbours(points);
    for (std::size_t element = 0; element < elements.nodes.size(); ++element) {
      const auto& nodes = elements.nodes[element];
      if (std::find(body_markers.begin(), body_markers.end(), elements.markers[element]) ==
          body_markers.end())
        continue;
      for (Index node : nodes)
        for (Index other : nodes)
          if (other != node) neighbours[static_cast<std::size_t>(node)].push_back(other);
    }
    std::vector<Vector3> before;
    std::vector<Vector3> after;
    for (std::size_t node = 0; node < points; ++node) {
      if (!on_body[node]) continue;
      before.clear();
      after.clear();
      for (Index other : neighbours[node]) {
        const std::size_t at = static_cast<std::size_t>(other);
        before.push_back(mesh.points[at] - mesh.points[node]);
        after.push_back(target[at] - target[node]);
      }
      boundary.rotation[node] = detail::fit_rotation(before, after, planar);
    }
  }
  return boundary;
}

}  // namespace mixmesh::deform
