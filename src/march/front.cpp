#include "front.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "mixmesh/core/error.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "sheet_sides.hpp"

namespace mixmesh::march_detail {

namespace {

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
