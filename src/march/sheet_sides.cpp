#include "sheet_sides.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>

#include "mixmesh/core/error.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"

namespace mixmesh::march_detail {

std::vector<SurfaceFace> surface_faces(const SurfaceMesh& surface, std::vector<std::string>& patch_names) {
  const auto point_count = static_cast<Index>(surface.points.size());
  auto check_node = [&](Index node, const std::string& patch) {
    if (node < 0 || node >= point_count)
      throw Error("march: patch '" + patch + "' refers to node " + std::to_string(node) +
                  ", but the surface has " + std::to_string(point_count) + " points");
  };
  std::vector<SurfaceFace> faces;
  for (const StructuredPatch& patch : surface.structured) {
    if (patch.ni < 2 || patch.nj < 2 ||
        patch.nodes.size() != static_cast<std::size_t>(patch.ni) * static_cast<std::size_t>(patch.nj))
      throw Error("march: structured patch '" + patch.name + "' has " + std::to_string(patch.nodes.size()) +
                  " nodes for ni = " + std::to_string(patch.ni) + ", nj = " + std::to_string(patch.nj));
    for (Index node : patch.nodes) check_node(node, patch.name);
    const int region = static_cast<int>(patch_names.size());
    patch_names.push_back(patch.name);
    for (int j = 0; j + 1 < patch.nj; ++j)
      for (int i = 0; i + 1 < patch.ni; ++i)
        faces.push_back(
            {4,
             {patch.node(i, j), patch.node(i + 1, j), patch.node(i + 1, j + 1), patch.node(i, j + 1)},
             region,
             patch.role == PatchRole::wake});
  }
  for (const TrianglePatch& patch : surface.unstructured) {
    if (patch.triangles.size() % 3 != 0)
      throw Error("march: triangle patch '" + patch.name + "' has " + std::to_string(patch.triangles.size()) +
                  " indices, not a multiple of 3");
    for (Index node : patch.triangles) check_node(node, patch.name);
    const int region = static_cast<int>(patch_names.size());
    patch_names.push_back(patch.name);
    for (std::size_t t = 0; t < patch.triangles.size(); t += 3)
      faces.push_back({3,
                       {patch.triangles[t], patch.triangles[t + 1], patch.triangles[t + 2], -1},
                       region,
                       patch.role == PatchRole::wake});
  }
  for (const SurfaceFace& face : faces) {
    for (int a = 0; a < face.corner_count; ++a)
      for (int b = a + 1; b < face.corner_count; ++b)
        if (face.nodes[static_cast<std::size_t>(a)] == face.nodes[static_cast<std::size_t>(b)])
          throw Error("march: patch '" + patch_names[static_cast<std::size_t>(face.patch)] +
                      "' has a degenerate face at node " +
                      std::to_string(face.nodes[static_cast<std::size_t>(a)]));
  }
  return faces;
}

namespace {

struct JunctionPlan {
  int face = -1;  // surface face index of the split triangle
  int corner = 0;
  Index sheet_node = -1;  // the other node of the sheet's free edge at the junction
};

// Orders the fan of wall faces across the sheet at `node` from the wall face on one side
// of the sheet to the one on the other, picks the triangle that straddles the sheet's
// plane as the split face, and gives the fan faces before it the first side and those
// after it the other (in corner_side; the split corner gets the side of the faces after
// it). No plan (face -1) when the fan is not one chain between faces of opposite sides,
// the straddling face is not a triangle, or the sheet has not exactly one free edge at
// the node.
JunctionPlan plan_junction(const SurfaceMesh& surface, const std::vector<SurfaceFace>& faces, Index node,
                           const std::vector<std::pair<std::size_t, int>>& fan,
                           const std::vector<std::size_t>& wall_faces,
                           std::vector<std::array<int, 4>>& corner_side, const Vector3& sheet_normal) {
  auto corner_node = [&](std::size_t f, int k) {
    const int n = faces[f].corner_count;
    return faces[f].nodes[static_cast<std::size_t>((k % n + n) % n)];
  };
  const std::size_t count = fan.size();
  auto previous_of = [&](std::size_t i) { return corner_node(fan[i].first, fan[i].second - 1); };
  auto next_of = [&](std::size_t i) { return corner_node(fan[i].first, fan[i].second + 1); };
  std::size_t start = count;
  for (std::size_t i = 0; i < count; ++i) {
    bool follows = false;
    for (std::size_t j = 0; j < count; ++j) follows |= j != i && next_of(j) == previous_of(i);
    if (follows) continue;
    if (start != count) return {};
    start = i;
  }
  if (start == count) return {};
  std::vector<std::size_t> order{start};
  std::vector<char> used(count, 0);
  used[start] = 1;
  while (order.size() < count) {
    std::size_t following = count;
    for (std::size_t j = 0; j < count; ++j)
      if (!used[j] && previous_of(j) == next_of(order.back())) following = j;
    if (following == count) return {};
    used[following] = 1;
    order.push_back(following);
  }
  // Side of the wall face beyond an end of the fan (the one sharing edge node-other).
  auto side_beyond = [&](Index other) {
    for (std::size_t f : wall_faces)
      for (int k = 0; k < faces[f].corner_count; ++k)
        if (faces[f].nodes[static_cast<std::size_t>(k)] == node &&
            corner_side[f][static_cast<std::size_t>(k)] != 0 &&
            (corner_node(f, k + 1) == other || corner_node(f, k - 1) == other))
          return corner_side[f][static_cast<std::size_t>(k)];
    return 0;
  };
  const int side_start = side_beyond(previous_of(order.front()));
  const int side_end = side_beyond(next_of(order.back()));
  if (side_start == 0 || side_end != -side_start) return {};
  const Vector3& here = surface.points[static_cast<std::size_t>(node)];
  // The split face is the one that straddles the sheet's plane (its edges at the node
  // on either side of it); if none does (the fan lies on one side to rounding), the
  // middle face of the fan.
  std::size_t split = order[count / 2];
  for (std::size_t i : order) {
    const double before = (surface.points[static_cast<std::size_t>(previous_of(i))] - here).dot(sheet_normal);
    const double after = (surface.points[static_cast<std::size_t>(next_of(i))] - here).dot(sheet_normal);
    if (before * after <= 0.0) {
      split = i;
      break;
    }
  }
  if (faces[fan[split].first].corner_count != 3) return {};
  // The sheet's free edge at the node: a sheet edge used by one sheet face and by no wall face.
  std::unordered_map<Index, int> sheet_edges;
  std::vector<Index> wall_neighbours;
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int k = 0; k < faces[f].corner_count; ++k) {
      if (faces[f].nodes[static_cast<std::size_t>(k)] != node) continue;
      for (Index other : {corner_node(f, k - 1), corner_node(f, k + 1)}) {
        if (faces[f].wake)
          ++sheet_edges[other];
        else
          wall_neighbours.push_back(other);
      }
    }
  JunctionPlan plan;
  int free_edges = 0;
  for (const auto& [other, uses] : sheet_edges)
    if (uses == 1 &&
        std::find(wall_neighbours.begin(), wall_neighbours.end(), other) == wall_neighbours.end()) {
      plan.sheet_node = other;
      ++free_edges;
    }
  if (free_edges != 1) return {};
  bool before_split = true;
  for (std::size_t i : order) {
    int& side = corner_side[fan[i].first][static_cast<std::size_t>(fan[i].second)];
    if (i == split) {
      side = side_end;
      before_split = false;
      continue;
    }
    side = before_split ? side_start : side_end;
  }
  plan.face = static_cast<int>(fan[split].first);
  plan.corner = fan[split].second;
  return plan;
}

}  // namespace

SheetSides sheet_sides(const SurfaceMesh& surface, const std::vector<SurfaceFace>& faces) {
  const std::size_t point_count = surface.points.size();
  SheetSides sides;
  std::vector<Vector3>& wake_normal = sides.wake_normal;
  wake_normal.assign(point_count, Vector3::Zero());
  std::vector<char> on_wake(point_count, 0);
  for (const SurfaceFace& face : faces)
    if (face.wake) {
      const Vector3 area = face_area_vector(surface.points, face.nodes.data(), face.corner_count);
      for (int k = 0; k < face.corner_count; ++k) {
        const auto node = static_cast<std::size_t>(face.nodes[static_cast<std::size_t>(k)]);
        wake_normal[node] += area;
        on_wake[node] = 1;
      }
    }

  // Side of every wall face corner at a wake node: a face facing the same way as the
  // sheet (the upper surface at the trailing edge) joins the line above it, one facing
  // the other way the line below; faces within 45 degrees of the sheet's plane are
  // across it (a tip cap).
  const double across_sheet = std::sqrt(0.5);
  sides.corner_side.assign(faces.size(), {0, 0, 0, 0});
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const SurfaceFace& face = faces[f];
    if (face.wake) continue;
    const Vector3 face_normal =
        face_area_vector(surface.points, face.nodes.data(), face.corner_count).normalized();
    for (int k = 0; k < face.corner_count; ++k) {
      const Index node = face.nodes[static_cast<std::size_t>(k)];
      if (!on_wake[static_cast<std::size_t>(node)]) continue;
      const double facing = face_normal.dot(wake_normal[static_cast<std::size_t>(node)].normalized());
      const int side = facing > across_sheet ? +1 : facing < -across_sheet ? -1 : 0;
      sides.corner_side[f][static_cast<std::size_t>(k)] = side;
      sides.wall_at_wake[node].push_back(f);
      if (side == 0) sides.across[node].push_back({f, k});
    }
  }
  return sides;
}

std::vector<char> sheet_free_edge_nodes(const SurfaceMesh& surface, const std::vector<SurfaceFace>& faces) {
  std::vector<char> on_sheet_free_edge(surface.points.size(), 0);
  auto on_plane = [&](Index node) {
    return surface.symmetry_tolerance >= 0.0 && std::abs(surface.points[static_cast<std::size_t>(node)].y() -
                                                         surface.symmetry_y) <= surface.symmetry_tolerance;
  };
  std::unordered_map<std::uint64_t, int> sheet_uses;
  auto edge_key = [](Index a, Index b) {
    return static_cast<std::uint64_t>(std::min(a, b)) << 32 | static_cast<std::uint64_t>(std::max(a, b));
  };
  for (const SurfaceFace& face : faces)
    for (int k = 0; k < face.corner_count; ++k) {
      const std::uint64_t key = edge_key(face.nodes[static_cast<std::size_t>(k)],
                                         face.nodes[static_cast<std::size_t>((k + 1) % face.corner_count)]);
      sheet_uses[key] += face.wake ? 1 : 1000;
    }
  for (const auto& [key, uses] : sheet_uses)
    if (uses == 1 &&
        !(on_plane(static_cast<Index>(key >> 32)) && on_plane(static_cast<Index>(key & 0xffffffffu)))) {
      on_sheet_free_edge[static_cast<std::size_t>(key >> 32)] = 1;
      on_sheet_free_edge[static_cast<std::size_t>(key & 0xffffffffu)] = 1;
    }
  return on_sheet_free_edge;
}

JunctionPlans plan_junctions(const SurfaceMesh& surface, const std::vector<SurfaceFace>& faces,
                             const std::vector<char>& on_sheet_free_edge, SheetSides& sides) {
  const std::vector<Vector3>& wake_normal = sides.wake_normal;
  std::vector<std::array<int, 4>>& corner_side = sides.corner_side;
  JunctionPlans plans;
  plans.split_corner.assign(faces.size(), -1);
  // Edges of the sheet's faces: a wall face across the sheet that shares one at a node
  // stands on the sheet's attachment (a blunt base, the wake leaving from its middle).
  std::set<std::pair<Index, Index>> sheet_edges;
  for (const SurfaceFace& face : faces)
    if (face.wake)
      for (int k = 0; k < face.corner_count; ++k)
        sheet_edges.insert(std::minmax(face.nodes[static_cast<std::size_t>(k)],
                                       face.nodes[static_cast<std::size_t>((k + 1) % face.corner_count)]));
  auto on_attachment = [&](std::size_t f, int k) {
    const int n = faces[f].corner_count;
    const Index node = faces[f].nodes[static_cast<std::size_t>(k)];
    for (int step : {1, n - 1})
      if (sheet_edges.count(std::minmax(node, faces[f].nodes[static_cast<std::size_t>((k + step) % n)])))
        return true;
    return false;
  };
  // Joins a wall face across the sheet to the line on the side of the sheet its centre
  // lies, as the wing's surfaces do at a sharp trailing edge (a wall line of its own
  // would march into the sheet).
  // The offset along the face's edge on the sheet (a base's long quad on the attachment
  // line) does not count: the sheet's normal at the node is a mean over its faces there,
  // not square to that edge, and on a cranked wing's forward-swept trailing edge the two
  // half-base quads at a node both came out on one side (1 mm across against 0.6 m along).
  auto join_by_centre = [&](Index node, std::size_t f, int k) {
    const int n = faces[f].corner_count;
    const Vector3& here = surface.points[static_cast<std::size_t>(node)];
    Vector3 centre = Vector3::Zero();
    for (int c = 0; c < n; ++c)
      centre += surface.points[static_cast<std::size_t>(faces[f].nodes[static_cast<std::size_t>(c)])] / n;
    Vector3 offset = centre - here;
    for (int step : {1, n - 1}) {
      const Index other = faces[f].nodes[static_cast<std::size_t>((k + step) % n)];
      if (!sheet_edges.count(std::minmax(node, other))) continue;
      const Vector3 along = surface.points[static_cast<std::size_t>(other)] - here;
      if (along.norm() > 0.0) offset -= offset.dot(along.normalized()) * along.normalized();
    }
    const double above = offset.dot(wake_normal[static_cast<std::size_t>(node)]);
    corner_side[f][static_cast<std::size_t>(k)] = above >= 0.0 ? +1 : -1;
  };
  for (auto& [node, fan] : sides.across) {
    // Faces on the attachment (a blunt base's) join by their centre at every node, also
    // where the sheet's free edge starts (the base's end at a tip): the rest of the fan
    // there (the tip cap's triangles) then lies between faces of either side and is
    // split as at a sharp trailing edge. As a fan of their own the base's faces at the
    // tip kept a line of their own, stopped at the first layer and left the hull open
    // (every random wing with a base and a wake).
    std::vector<std::pair<std::size_t, int>> rest;
    for (const auto& [f, k] : fan) {
      if (on_attachment(f, k))
        join_by_centre(node, f, k);
      else
        rest.push_back({f, k});
    }
    if (rest.empty()) continue;
    const JunctionPlan plan = plan_junction(surface, faces, node, rest, sides.wall_at_wake[node], corner_side,
                                            wake_normal[static_cast<std::size_t>(node)].normalized());
    if (plan.face >= 0) {
      plans.split_corner[static_cast<std::size_t>(plan.face)] = plan.corner;
      plans.junction_nodes.push_back({static_cast<std::size_t>(plan.face), plan.sheet_node});
    } else if (!on_sheet_free_edge[static_cast<std::size_t>(node)]) {
      for (const auto& [f, k] : rest) join_by_centre(node, f, k);
    }
  }
  std::sort(plans.junction_nodes.begin(), plans.junction_nodes.end());
  return plans;
}

}  // namespace mixmesh::march_detail
