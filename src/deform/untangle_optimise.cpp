// The optimisation stage of the untangling (untangle.hpp says why it is needed).
#include <algorithm>
#include <cmath>
#include <limits>

#include "deform/ara_smoothing.hpp"
#include "deform/untangle.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/mesh/topology.hpp"

namespace mixmesh::deform::detail {

namespace {

// Knupp's untangling function, smoothed: φ(r) = sqrt((r − β)² + δ²) − (r − β), about
// 2(β − r) for an inverted measure and near zero once r is well above β. r is a measure
// of the deformed cell over the same measure of the undeformed one, so a flat cell 1 µm
// thick counts as much as a cube: each only has to keep a fraction β of its own shape.
constexpr double target_ratio = 0.1;      // β
constexpr double smoothing_width = 0.01;  // δ
constexpr int largest_ring = 2;
constexpr int sweeps = 8;
constexpr int descent_steps = 40;
constexpr int halvings = 40;

// d V6 / d vertex of tetrahedron_volume6(a, b, c, d), vertex 0..3.
Vector3 volume_gradient(const Vector3& a, const Vector3& b, const Vector3& c, const Vector3& d, int vertex) {
  switch (vertex) {
    case 1:
      return (c - a).cross(d - a);
    case 2:
      return (d - a).cross(b - a);
    case 3:
      return (b - a).cross(c - a);
    default:
      return -((c - a).cross(d - a) + (d - a).cross(b - a) + (b - a).cross(c - a));
  }
}

// The measures cell_valid() checks, in a fixed order (the face sub-tetrahedra about the
// cell centre, then the corner determinants), and their gradients with respect to the
// position of `node` (a node of the cell) when `gradients` is not null. Volume cells only.
void cell_measures(const DualMesh& dual, std::size_t cell, Index node, const std::vector<Vector3>& points,
                   std::vector<double>& values, std::vector<Vector3>* gradients) {
  const CellType type = static_cast<CellType>(dual.cell_kind[cell]);
  const CellDescriptor& shape = descriptor(type);
  const Index* nodes = dual.nodes(cell);
  auto at = [&](int local) -> const Vector3& { return points[static_cast<std::size_t>(nodes[local])]; };
  auto is_node = [&](int local) { return nodes[local] == node ? 1.0 : 0.0; };
  const Vector3 centre = cell_centre(type, points, nodes);
  const double centre_weight = 1.0 / shape.node_count;
  values.clear();
  if (gradients) gradients->clear();
  // One sub-tetrahedron (a, b, c, centre) turned so that it is positive in a valid cell,
  // with the weights of `node` in a, b and c.
  auto sub_tetrahedron = [&](const Vector3& a, const Vector3& b, const Vector3& c, double weight_a,
                             double weight_b, double weight_c) {
    values.push_back(-tetrahedron_volume6(a, b, c, centre));
    if (!gradients) return;
    const std::array<double, 4> weights = {weight_a, weight_b, weight_c, centre_weight};
    Vector3 gradient = Vector3::Zero();
    for (int vertex = 0; vertex < 4; ++vertex)
      if (weights[static_cast<std::size_t>(vertex)] != 0.0)
        gradient -= weights[static_cast<std::size_t>(vertex)] * volume_gradient(a, b, c, centre, vertex);
    gradients->push_back(gradient);
  };
  for (int face = 0; face < shape.face_count; ++face) {
    const LocalFace& local = shape.faces[static_cast<std::size_t>(face)];
    if (local.node_count == 3) {
      sub_tetrahedron(at(local.nodes[0]), at(local.nodes[1]), at(local.nodes[2]), is_node(local.nodes[0]),
                      is_node(local.nodes[1]), is_node(local.nodes[2]));
      continue;
    }
    Vector3 face_centre = Vector3::Zero();
    double face_weight = 0.0;
    for (int corner = 0; corner < 4; ++corner) {
      face_centre += 0.25 * at(local.nodes[static_cast<std::size_t>(corner)]);
      face_weight += 0.25 * is_node(local.nodes[static_cast<std::size_t>(corner)]);
    }
    for (int corner = 0; corner < 4; ++corner) {
      const int first = local.nodes[static_cast<std::size_t>(corner)];
      const int second = local.nodes[static_cast<std::size_t>((corner + 1) % 4)];
      sub_tetrahedron(at(first), at(second), face_centre, is_node(first), is_node(second), face_weight);
    }
  }
  for (int corner = 0; corner < shape.corner_count; ++corner) {
    const Corner& local = shape.corners[static_cast<std::size_t>(corner)];
    const Vector3& origin = at(local.node);
    const Vector3 first = at(local.neighbours[0]) - origin;
    const Vector3 second = at(local.neighbours[1]) - origin;
    const Vector3 third = at(local.neighbours[2]) - origin;
    values.push_back(first.cross(second).dot(third));
    if (!gradients) continue;
    const std::array<Vector3, 3> partial = {second.cross(third), third.cross(first), first.cross(second)};
    Vector3 gradient = -is_node(local.node) * (partial[0] + partial[1] + partial[2]);
    for (int side = 0; side < 3; ++side)
      gradient +=
          is_node(local.neighbours[static_cast<std::size_t>(side)]) * partial[static_cast<std::size_t>(side)];
    gradients->push_back(gradient);
  }
}

// The untangling function of `node`'s cells at the current positions, and its gradient.
struct NodeObjective {
  const DualMesh& dual;
  const std::vector<Vector3>& original;
  std::vector<double> values, reference;
  std::vector<Vector3> gradients;
  double lowest = 0.0;  // the smallest ratio r at the last evaluation

  double operator()(std::size_t node, const std::vector<Vector3>& points, Vector3* gradient) {
    double total = 0.0;
    lowest = std::numeric_limits<double>::infinity();
    if (gradient) gradient->setZero();
    for (std::size_t slot = dual.point_cell_offsets[node]; slot < dual.point_cell_offsets[node + 1]; ++slot) {
      const std::size_t cell = static_cast<std::size_t>(dual.point_cells[slot]);
      cell_measures(dual, cell, static_cast<Index>(node), points, values, gradient ? &gradients : nullptr);
      cell_measures(dual, cell, static_cast<Index>(node), original, reference, nullptr);
      const double largest = *std::max_element(reference.begin(), reference.end());
      for (std::size_t entry = 0; entry < values.size(); ++entry) {
        // The undeformed mesh is valid, so every reference is positive; the floor only
        // keeps a degenerate one from dividing by zero.
        const double scale = std::max(reference[entry], 1e-12 * std::max(largest, 1e-300));
        lowest = std::min(lowest, values[entry] / scale);
        const double excess = values[entry] / scale - target_ratio;
        const double root = std::sqrt(excess * excess + smoothing_width * smoothing_width);
        total += root - excess;
        if (gradient) *gradient += (excess / root - 1.0) / scale * gradients[entry];
      }
    }
    return total;
  }
};

std::size_t inverted_round(const DualMesh& dual, std::size_t node, const std::vector<Vector3>& points) {
  std::size_t count = 0;
  for (std::size_t slot = dual.point_cell_offsets[node]; slot < dual.point_cell_offsets[node + 1]; ++slot)
    count += !cell_valid(dual, static_cast<std::size_t>(dual.point_cells[slot]), points);
  return count;
}

// Steepest descent of the node's untangling function. The step starts at the node's
// shortest edge, doubles after a step that lowers the function and halves until one
// does, so a node beside a cell a micrometre thick creeps and a node in open space can
// travel; it stops once every measure of its cells has reached β, so nodes do not drift
// further than untangling needs. Returns whether the node moved.
bool descend(NodeObjective& objective, const BoundaryMotion& boundary, std::size_t node,
             const std::vector<Index>& neighbours, std::vector<Vector3>& moved) {
  double distance = std::numeric_limits<double>::infinity();
  for (Index other : neighbours)
    distance = std::min(distance, (moved[static_cast<std::size_t>(other)] - moved[node]).norm());
  if (!(distance > 0.0) || !std::isfinite(distance)) return false;
  const Vector3 start = moved[node];
  Vector3 gradient;
  double value = objective(node, moved, &gradient);
  for (int step = 0; step < descent_steps && objective.lowest < target_ratio; ++step) {
    if (boundary.roles[node] == NodeRole::sliding)
      gradient -= gradient.dot(boundary.slide_normal[node]) * boundary.slide_normal[node];
    const double norm = gradient.norm();
    if (!(norm > 0.0)) break;
    const Vector3 here = moved[node];
    bool lower = false;
    for (int halving = 0; halving < halvings && !lower; ++halving) {
      moved[node] = here - (distance / norm) * gradient;
      lower = objective(node, moved, nullptr) < value;
      if (!lower) distance *= 0.5;
    }
    if (!lower) {
      moved[node] = here;
      break;
    }
    distance *= 2.0;
    value = objective(node, moved, &gradient);
  }
  return moved[node] != start;
}

}  // namespace

std::size_t optimise_inverted(const DualMesh& dual, const BoundaryMotion& boundary,
                              const std::vector<Vector3>& original, std::vector<Vector3>& moved,
                              std::vector<char>& invalid, std::vector<char>& ever_moved) {
  std::size_t inverted = static_cast<std::size_t>(std::count(invalid.begin(), invalid.end(), 1));
  if (dual.planar) return inverted;  // the measures above are those of volume cells
  NodeObjective objective{dual, original, {}, {}, {}, 0.0};
  std::vector<Index> neighbours;
  for (int ring = 0; ring <= largest_ring && inverted > 0; ++ring) {
    const std::vector<Index> region = inverted_region(dual, invalid, ring);
    // Gauss–Seidel over the region's free nodes: each node moves against the gradient of
    // its cells' untangling function, and keeps the move only when no more of its cells
    // are inverted than before, so the count never grows.
    for (int sweep = 0; sweep < sweeps && inverted > 0; ++sweep) {
      for (Index entry : region) {
        const std::size_t node = static_cast<std::size_t>(entry);
        if (boundary.roles[node] == NodeRole::prescribed) continue;
        const Vector3 kept = moved[node];
        const std::size_t before = inverted_round(dual, node, moved);
        edge_neighbours(dual, node, neighbours);
        if (!descend(objective, boundary, node, neighbours, moved)) continue;
        if (inverted_round(dual, node, moved) > before) {
          moved[node] = kept;
          continue;
        }
        ever_moved[node] = 1;
        for (std::size_t slot = dual.point_cell_offsets[node]; slot < dual.point_cell_offsets[node + 1];
             ++slot) {
          const std::size_t cell = static_cast<std::size_t>(dual.point_cells[slot]);
          const char now = !cell_valid(dual, cell, moved);
          inverted = inverted - static_cast<std::size_t>(invalid[cell]) + static_cast<std::size_t>(now);
          invalid[cell] = now;
        }
      }
    }
  }
  return inverted;
}

}  // namespace mixmesh::deform::detail
