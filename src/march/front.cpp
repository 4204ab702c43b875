#include "front.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <unordered_map>

#include "mixmesh/core/error.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"

namespace mixmesh::march_detail {

namespace {

struct SurfaceFace {
  int corner_count;
  std::array<Index, 4> nodes;
  int patch;
  bool wake;
};

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

Vector3 area_vector(const std::vector<Vector3>& points, const SurfaceFace& face) {
  Vector3 sum = Vector3::Zero();
  for (int k = 0; k < face.corner_count; ++k)
    sum += points[static_cast<std::size_t>(face.nodes[static_cast<std::size_t>(k)])].cross(
        points[static_cast<std::size_t>(face.nodes[static_cast<std::size_t>((k + 1) % face.corner_count)])]);
  return 0.5 * sum;
}

// Counter-clockwise ring of edge neighbours of a column; empty when the faces around
// it do not form one fan. `closed` tells whether the fan closes.
std::vector<int> fan_ring(const Front& front, int column, bool& closed) {
  std::vector<int> outs, ins;
  for (int f : front.column_faces[static_cast<std::size_t>(column)]) {
    const FrontFace& face = front.faces[static_cast<std::size_t>(f)];
    const int n = face.corner_count;
    for (int k = 0; k < n; ++k)
      if (face.columns[static_cast<std::size_t>(k)] == column) {
        outs.push_back(face.columns[static_cast<std::size_t>((k + 1) % n)]);
        ins.push_back(face.columns[static_cast<std::size_t>((k + n - 1) % n)]);
      }
  }
  const std::size_t count = outs.size();
  std::size_t start = 0;
  closed = true;
  for (std::size_t f = 0; f < count; ++f)
    if (std::find(ins.begin(), ins.end(), outs[f]) == ins.end()) {
      start = f;
      closed = false;
      break;
    }
  std::vector<int> ring;
  std::vector<char> used(count, 0);
  std::size_t current = start;
  for (std::size_t visited = 0; visited < count; ++visited) {
    used[current] = 1;
    ring.push_back(outs[current]);
    std::size_t next = count;
    for (std::size_t g = 0; g < count; ++g)
      if (!used[g] && outs[g] == ins[current]) next = g;
    if (next == count) {
      if (!closed)
        ring.push_back(ins[current]);
      else if (ins[current] != outs[start])
        return {};
      if (visited + 1 != count) return {};
      return ring;
    }
    current = next;
  }
  return {};
}

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

// Closes a sheet's side edges by a wrap face each: the free edges of the sheet that lie
// neither in the symmetry plane nor at the sheet's downstream end (a wake's tip edge).
// Without it each layer leaves a side face along the edge as thin as the layer, whose
// hull the far field could only fill with slivers; with it the layers above and below
// the sheet meet round the edge (FrontFace::wrap). Downstream is the mean direction from
// the nodes where the sheet leaves a wall (`attached`) into the sheet faces there; an
// end edge faces downstream (within 45 degrees), a side edge across it. (Measured from
// the nearest trailing-edge node instead, the end of a wake behind a swept, tapered
// wing looked like a side edge where it passes behind the tip.)
void add_wrap_faces(const SurfaceMesh& surface, const std::vector<char>& attached,
                    const std::vector<std::array<int, 3>>& node_columns, Front& front) {
  std::unordered_map<std::uint64_t, int> uses;
  auto key = [](int a, int b) {
    return static_cast<std::uint64_t>(std::min(a, b)) << 32 | static_cast<std::uint64_t>(std::max(a, b));
  };
  for (const FrontFace& face : front.faces)
    for (int k = 0; k < face.corner_count; ++k)
      ++uses[key(face.columns[static_cast<std::size_t>(k)],
                 face.columns[static_cast<std::size_t>((k + 1) % face.corner_count)])];
  auto node_of = [&](int column) { return front.column_node[static_cast<std::size_t>(column)]; };
  auto point_of = [&](int column) -> const Vector3& {
    return surface.points[static_cast<std::size_t>(node_of(column))];
  };
  auto upper_sheet_face = [&](const FrontFace& face) {
    return !face.wall && front.column_side[static_cast<std::size_t>(face.columns[0])] == +1;
  };
  Vector3 downstream = Vector3::Zero();
  for (const FrontFace& face : front.faces) {
    if (!upper_sheet_face(face)) continue;
    Vector3 centre = Vector3::Zero(), attachment = Vector3::Zero();
    int count = 0;
    for (int k = 0; k < face.corner_count; ++k) {
      const int column = face.columns[static_cast<std::size_t>(k)];
      centre += point_of(column) / face.corner_count;
      if (attached[static_cast<std::size_t>(node_of(column))]) {
        attachment += point_of(column);
        ++count;
      }
    }
    if (count > 0 && count < face.corner_count) downstream += (centre - attachment / count).normalized();
  }
  if (downstream.norm() == 0.0) return;  // no sheet leaves a wall
  downstream.normalize();
  const double facing = std::cos(M_PI / 4.0);
  const std::size_t face_count = front.faces.size();
  for (std::size_t f = 0; f < face_count; ++f) {
    const FrontFace face = front.faces[f];
    if (!upper_sheet_face(face)) continue;
    const int n = face.corner_count;
    Vector3 area = Vector3::Zero();
    for (int k = 0; k < n; ++k)
      area += point_of(face.columns[static_cast<std::size_t>(k)])
                  .cross(point_of(face.columns[static_cast<std::size_t>((k + 1) % n)]));
    for (int k = 0; k < n; ++k) {
      const int above_a = face.columns[static_cast<std::size_t>(k)];
      const int above_b = face.columns[static_cast<std::size_t>((k + 1) % n)];
      if (uses[key(above_a, above_b)] != 1) continue;
      if (front.on_symmetry[static_cast<std::size_t>(above_a)] &&
          front.on_symmetry[static_cast<std::size_t>(above_b)])
        continue;
      const Vector3 conormal = (point_of(above_b) - point_of(above_a)).cross(area).normalized();
      if (conormal.dot(downstream) >= facing) continue;  // the sheet's end
      const int below_a = node_columns[static_cast<std::size_t>(node_of(above_a))][0];
      const int below_b = node_columns[static_cast<std::size_t>(node_of(above_b))][0];
      if (below_a < 0 || below_b < 0) continue;
      FrontFace wrap{4, {above_b, above_a, below_a, below_b}, face.patch, false, false};
      wrap.wrap = true;
      front.faces.push_back(wrap);
    }
  }
}

// Which side of a sheet the wall faces at its nodes join.
struct SheetSides {
  // Sheet normal at every wake node: decides which side a wall face touching it takes.
  std::vector<Vector3> wake_normal;
  std::vector<std::array<int, 4>> corner_side;
  std::unordered_map<Index, std::vector<std::pair<std::size_t, int>>> across;  // node -> (face, corner)
  std::unordered_map<Index, std::vector<std::size_t>> wall_at_wake;
};

// The junctions planned at the nodes where wall faces lie across a sheet.
struct JunctionPlans {
  std::vector<int> split_corner;
  std::vector<std::pair<std::size_t, Index>> junction_nodes;  // (split face, sheet free-edge node)
};

SheetSides sheet_sides(const SurfaceMesh& surface, const std::vector<SurfaceFace>& faces) {
  const std::size_t point_count = surface.points.size();
  SheetSides sides;
  std::vector<Vector3>& wake_normal = sides.wake_normal;
  wake_normal.assign(point_count, Vector3::Zero());
  std::vector<char> on_wake(point_count, 0);
  for (const SurfaceFace& face : faces)
    if (face.wake) {
      const Vector3 area = area_vector(surface.points, face);
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
    const Vector3 face_normal = area_vector(surface.points, face).normalized();
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

// Nodes on a free edge of a sheet: a sheet edge of one sheet face that no wall face
// uses and that does not lie in the symmetry plane (the plane closes a sheet's root
// edge: the wall faces across the sheet there, a blunt base's, join the lines on
// either side like the others; as a free edge they got a line of their own, and the
// layers did not close round it on the plane).
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

// Gives the wall faces across a sheet their sides (in sides.corner_side) and plans the
// junctions where such a fan meets the sheet's free edge.
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

// The front faces: each wall face once (a split face as a quad on both sheet lines),
// each wake face twice, once per side. Returns each node's columns by side + 1.
std::vector<std::array<int, 3>> add_front_faces(const SurfaceMesh& surface,
                                                const std::vector<SurfaceFace>& faces,
                                                const std::vector<std::array<int, 4>>& corner_side,
                                                const std::vector<int>& split_corner, Front& front) {
  std::vector<std::array<int, 3>> node_columns(surface.points.size(), {-1, -1, -1});
  auto column = [&](Index node, int side) {
    int& slot = node_columns[static_cast<std::size_t>(node)][static_cast<std::size_t>(side + 1)];
    if (slot < 0) {
      slot = static_cast<int>(front.column_node.size());
      front.column_node.push_back(node);
      front.column_side.push_back(side);
      const double y = surface.points[static_cast<std::size_t>(node)].y();
      front.on_symmetry.push_back(surface.symmetry_tolerance >= 0.0 &&
                                  std::abs(y - surface.symmetry_y) <= surface.symmetry_tolerance);
    }
    return slot;
  };

  for (std::size_t f = 0; f < faces.size(); ++f) {
    const SurfaceFace& face = faces[f];
    const int n = face.corner_count;
    if (face.wake) {
      for (int side : {+1, -1}) {
        FrontFace front_face{n, {-1, -1, -1, -1}, face.patch, false, false};
        for (int k = 0; k < n; ++k) {
          const int source = side > 0 ? k : n - 1 - k;  // the lower side runs the other way round
          front_face.columns[static_cast<std::size_t>(k)] =
              column(face.nodes[static_cast<std::size_t>(source)], side);
        }
        front.faces.push_back(front_face);
      }
      continue;
    }
    FrontFace front_face{n, {-1, -1, -1, -1}, face.patch, true, false};
    if (split_corner[f] >= 0) {
      // Triangle (t, a, b) split at t: quad (t_a, a, b, t_b), t_a the line on the side of
      // edge t-a, t_b the one on the side of edge b-t.
      const int k = split_corner[f];
      const Index t = face.nodes[static_cast<std::size_t>(k)];
      const int side_after = corner_side[f][static_cast<std::size_t>(k)];
      front_face.corner_count = 4;
      front_face.split = true;
      front_face.columns = {
          column(t, side_after), column(face.nodes[static_cast<std::size_t>((k + 1) % 3)], 0),
          column(face.nodes[static_cast<std::size_t>((k + 2) % 3)], 0), column(t, -side_after)};
      front.faces.push_back(front_face);
      continue;
    }
    for (int k = 0; k < n; ++k) {
      const Index node = face.nodes[static_cast<std::size_t>(k)];
      front_face.columns[static_cast<std::size_t>(k)] =
          column(node, corner_side[f][static_cast<std::size_t>(k)]);
    }
    front.faces.push_back(front_face);
  }
  return node_columns;
}

void add_junctions(const std::vector<SurfaceFace>& faces,
                   const std::vector<std::pair<std::size_t, Index>>& junction_nodes,
                   const std::vector<std::array<int, 3>>& node_columns, Front& front) {
  // The front faces are the surface's wall faces in order, each wake face twice.
  std::vector<int> front_face_of(faces.size(), -1);
  for (std::size_t f = 0, next = 0; f < faces.size(); ++f) {
    front_face_of[f] = static_cast<int>(next);
    next += faces[f].wake ? 2 : 1;
  }
  for (const auto& [f, sheet_node] : junction_nodes) {
    Junction junction;
    junction.face = front_face_of[f];
    const FrontFace& split = front.faces[static_cast<std::size_t>(junction.face)];
    for (int end : {0, 1}) {
      const int line = split.columns[end == 0 ? 0 : 3];
      junction.sheet[static_cast<std::size_t>(end)] =
          node_columns[static_cast<std::size_t>(sheet_node)]
                      [static_cast<std::size_t>(front.column_side[static_cast<std::size_t>(line)] + 1)];
    }
    front.junctions.push_back(junction);
  }
}

void add_column_faces(Front& front) {
  const std::size_t column_count = front.column_node.size();
  front.column_faces.assign(column_count, {});
  for (std::size_t f = 0; f < front.faces.size(); ++f)
    for (int k = 0; k < front.faces[f].corner_count; ++k)
      front.column_faces[static_cast<std::size_t>(front.faces[f].columns[static_cast<std::size_t>(k)])]
          .push_back(static_cast<int>(f));
}

// Edges: free (one face), shared (two faces, opposite directions), else an error.
void add_edges(Front& front) {
  std::unordered_map<std::uint64_t, std::vector<std::pair<int, int>>> edges;
  for (std::size_t f = 0; f < front.faces.size(); ++f) {
    const FrontFace& face = front.faces[f];
    for (int k = 0; k < face.corner_count; ++k) {
      const auto a = static_cast<std::uint64_t>(face.columns[static_cast<std::size_t>(k)]);
      const auto b =
          static_cast<std::uint64_t>(face.columns[static_cast<std::size_t>((k + 1) % face.corner_count)]);
      edges[std::min(a, b) << 32 | std::max(a, b)].push_back({static_cast<int>(f), k});
    }
  }
  for (const auto& [key, list] : edges) {
    const auto node_a = front.column_node[static_cast<std::size_t>(key >> 32)];
    const auto node_b = front.column_node[static_cast<std::size_t>(key & 0xffffffffu)];
    const std::string where =
        "the edge between surface nodes " + std::to_string(node_a) + " and " + std::to_string(node_b);
    if (list.size() > 2)
      throw Error("march: " + where + " is shared by " + std::to_string(list.size()) + " faces on one side");
    if (list.size() == 1) {
      front.free_edges.push_back({list[0].first, list[0].second});
      continue;
    }
    const FrontFace& first = front.faces[static_cast<std::size_t>(list[0].first)];
    const FrontFace& second = front.faces[static_cast<std::size_t>(list[1].first)];
    if (first.columns[static_cast<std::size_t>(list[0].second)] ==
        second.columns[static_cast<std::size_t>(list[1].second)])
      throw Error("march: faces of patches '" + front.patch_names[static_cast<std::size_t>(first.patch)] +
                  "' and '" + front.patch_names[static_cast<std::size_t>(second.patch)] +
                  "' are oriented inconsistently at " + where);
    front.shared_edges.push_back({{list[0].first, list[1].first}, {list[0].second, list[1].second}});
  }
  // Deterministic order (the hash map's is not).
  std::sort(front.free_edges.begin(), front.free_edges.end(), [](const FreeEdge& a, const FreeEdge& b) {
    return a.face != b.face ? a.face < b.face : a.corner < b.corner;
  });
  std::sort(front.shared_edges.begin(), front.shared_edges.end(),
            [](const SharedEdge& a, const SharedEdge& b) {
              return a.faces != b.faces ? a.faces < b.faces : a.corners < b.corners;
            });
}

// Neighbourhoods: rings, closed by mirroring in the symmetry plane where needed.
void add_rings(Front& front) {
  const std::size_t column_count = front.column_node.size();
  front.neighbourhood.assign(column_count, Neighbourhood::free);
  front.ring.assign(column_count, {});
  front.stencil.assign(column_count, {-1, -1, -1, -1, -1, -1, -1, -1});
  for (std::size_t c = 0; c < column_count; ++c) {
    bool closed = false;
    std::vector<int> ring = fan_ring(front, static_cast<int>(c), closed);
    if (ring.empty()) continue;
    if (!closed) {
      const bool ends_in_plane = front.on_symmetry[static_cast<std::size_t>(ring.front())] &&
                                 front.on_symmetry[static_cast<std::size_t>(ring.back())];
      if (!front.on_symmetry[c] || !ends_in_plane) {
        front.ring[c] = ring;  // open fan on a free edge: directions are averaged over it
        continue;
      }
      for (std::size_t k = ring.size() - 1; k-- > 1;) ring.push_back(-(ring[k] + 1));
    }
    if (ring.size() < 3) continue;
    front.ring[c] = ring;
    front.neighbourhood[c] = Neighbourhood::ring;
  }
}

// The two lines of a split corner or a wrap face's node are free columns (their
// directions are averaged with their fans') and do not average with each other: one
// serves the faces above the sheet, the other those below.
void free_split_and_wrap_lines(Front& front) {
  for (const FrontFace& face : front.faces) {
    if (!face.split && !face.wrap) continue;
    for (const auto& [one, other] : face.wrap ? std::vector<std::pair<int, int>>{{0, 3}, {1, 2}}
                                              : std::vector<std::pair<int, int>>{{0, 3}})
      for (const auto& [line, partner] : {std::pair{one, other}, std::pair{other, one}}) {
        const auto column = static_cast<std::size_t>(face.columns[static_cast<std::size_t>(line)]);
        std::vector<int>& ring = front.ring[column];
        ring.erase(std::remove(ring.begin(), ring.end(), face.columns[static_cast<std::size_t>(partner)]),
                   ring.end());
        front.neighbourhood[column] = Neighbourhood::free;
      }
  }
}

// Structured stencils for the interior nodes of structured patches.
void add_structured_stencils(const SurfaceMesh& surface, Front& front) {
  std::size_t face_base = 0;
  for (const StructuredPatch& patch : surface.structured) {
    const int sides = patch.role == PatchRole::wake ? 2 : 1;
    const auto quads = static_cast<std::size_t>(patch.ni - 1) * static_cast<std::size_t>(patch.nj - 1);
    for (int side = 0; side < sides; ++side) {
      // Column at corner k of quad (i, j) in the patch's own winding.
      auto corner = [&](int i, int j, int k) {
        const std::size_t quad = static_cast<std::size_t>(j) * static_cast<std::size_t>(patch.ni - 1) +
                                 static_cast<std::size_t>(i);
        const std::size_t f =
            sides == 2 ? face_base + 2 * quad + static_cast<std::size_t>(side) : face_base + quad;
        return front.faces[f].columns[static_cast<std::size_t>(side == 0 ? k : 3 - k)];
      };
      for (int j = 1; j + 1 < patch.nj; ++j)
        for (int i = 1; i + 1 < patch.ni; ++i) {
          const int c = corner(i, j, 0);
          if (front.column_faces[static_cast<std::size_t>(c)].size() != 4 ||
              front.neighbourhood[static_cast<std::size_t>(c)] != Neighbourhood::ring ||
              front.ring[static_cast<std::size_t>(c)].size() != 4)
            continue;
          front.stencil[static_cast<std::size_t>(c)] = {
              corner(i, j, 1), corner(i - 1, j, 0), corner(i, j, 3),     corner(i, j - 1, 0),
              corner(i, j, 2), corner(i - 1, j, 3), corner(i, j - 1, 1), corner(i - 1, j - 1, 0)};
          front.neighbourhood[static_cast<std::size_t>(c)] = Neighbourhood::structured;
        }
    }
    face_base += quads * static_cast<std::size_t>(sides);
  }
}

}  // namespace

Front build_front(const SurfaceMesh& surface) {
  Front front;
  const std::vector<SurfaceFace> faces = surface_faces(surface, front.patch_names);
  const std::size_t point_count = surface.points.size();
  SheetSides sides = sheet_sides(surface, faces);
  const std::vector<char> on_sheet_free_edge = sheet_free_edge_nodes(surface, faces);
  const JunctionPlans plans = plan_junctions(surface, faces, on_sheet_free_edge, sides);
  const std::vector<std::array<int, 3>> node_columns =
      add_front_faces(surface, faces, sides.corner_side, plans.split_corner, front);
  add_junctions(faces, plans.junction_nodes, node_columns, front);
  // Where a sheet leaves the wall (trailing-edge nodes): wake nodes of a wall face.
  std::vector<char> attached(point_count, 0);
  for (const auto& [node, wall_faces] : sides.wall_at_wake) attached[static_cast<std::size_t>(node)] = 1;
  add_wrap_faces(surface, attached, node_columns, front);
  add_column_faces(front);
  add_edges(front);
  add_rings(front);
  free_split_and_wrap_lines(front);
  add_structured_stencils(surface, front);
  return front;
}

std::vector<Vector3> wall_face_normals(const Front& front, const std::vector<Vector3>& points,
                                       const std::vector<char>& face_active, int line) {
  std::vector<Vector3> normals;
  for (int face : front.column_faces[static_cast<std::size_t>(line)]) {
    const FrontFace& wall = front.faces[static_cast<std::size_t>(face)];
    if (!wall.wall || !face_active[static_cast<std::size_t>(face)]) continue;
    const Vector3 area = face_area_vector(points, wall.columns.data(), wall.corner_count);
    if (area.norm() > 0.0) normals.push_back(area.normalized());
  }
  return normals;
}

}  // namespace mixmesh::march_detail
