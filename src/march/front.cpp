#include "front.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "mixmesh/core/error.hpp"

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

}  // namespace

Front build_front(const SurfaceMesh& surface) {
  Front front;
  const std::vector<SurfaceFace> faces = surface_faces(surface, front.patch_names);
  const std::size_t point_count = surface.points.size();

  // Sheet normal at every wake node: decides which side a wall face touching it takes.
  std::vector<Vector3> wake_normal(point_count, Vector3::Zero());
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

  // Faces within 45 degrees of the sheet's plane count as across it.
  const double across_sheet = std::sqrt(0.5);
  std::vector<std::array<int, 3>> node_columns(point_count, {-1, -1, -1});
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

  for (const SurfaceFace& face : faces) {
    const int n = face.corner_count;
    if (face.wake) {
      for (int side : {+1, -1}) {
        FrontFace front_face{n, {-1, -1, -1, -1}, face.patch, false};
        for (int k = 0; k < n; ++k) {
          const int source = side > 0 ? k : n - 1 - k;  // the lower side runs the other way round
          front_face.columns[static_cast<std::size_t>(k)] =
              column(face.nodes[static_cast<std::size_t>(source)], side);
        }
        front.faces.push_back(front_face);
      }
      continue;
    }
    FrontFace front_face{n, {-1, -1, -1, -1}, face.patch, true};
    const Vector3 face_normal = area_vector(surface.points, face).normalized();
    for (int k = 0; k < n; ++k) {
      const Index node = face.nodes[static_cast<std::size_t>(k)];
      int side = 0;
      if (on_wake[static_cast<std::size_t>(node)]) {
        // A wall face facing the same way as the sheet (the upper surface at the
        // trailing edge) joins the line above it, one facing the other way the line
        // below; a face across the sheet (a tip cap) gets a line of its own, so no
        // cell has to bridge the two sides.
        const double facing = face_normal.dot(wake_normal[static_cast<std::size_t>(node)].normalized());
        side = facing > across_sheet ? +1 : facing < -across_sheet ? -1 : 0;
      }
      front_face.columns[static_cast<std::size_t>(k)] = column(node, side);
    }
    front.faces.push_back(front_face);
  }

  const std::size_t column_count = front.column_node.size();
  front.column_faces.assign(column_count, {});
  for (std::size_t f = 0; f < front.faces.size(); ++f)
    for (int k = 0; k < front.faces[f].corner_count; ++k)
      front.column_faces[static_cast<std::size_t>(front.faces[f].columns[static_cast<std::size_t>(k)])]
          .push_back(static_cast<int>(f));

  // Edges: free (one face), shared (two faces, opposite directions), else an error.
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

  // Neighbourhoods: rings, closed by mirroring in the symmetry plane where needed.
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

  // Structured stencils for the interior nodes of structured patches.
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
  return front;
}

}  // namespace mixmesh::march_detail
