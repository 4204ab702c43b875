#include "mixmesh/mesh/face_connectivity.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <unordered_map>
#include <utility>

namespace mixmesh {

namespace {

// A face as stored for matching: its sorted nodes (the fourth is -1 for triangles)
// and the cell face it came from (whose winding decides the orientation check).
struct FaceRecord {
  std::array<Index, 4> key;
  CellFace owner;
};

// +1 or -1: the winding of `nodes` relative to its sorted order, defined as the
// direction in which the smallest node is followed by the second smallest.
int winding(const Index* nodes, int count) {
  int first = 0;
  for (int corner = 1; corner < count; ++corner)
    if (nodes[corner] < nodes[first]) first = corner;
  const Index next = nodes[(first + 1) % count];
  const Index previous = nodes[(first + count - 1) % count];
  return next < previous ? 1 : -1;
}

}  // namespace

std::array<Index, 4> sorted_face_key(const Index* nodes, int count) {
  // Insertion sort of two to four entries (std::sort on a tiny array trips GCC 12's
  // array-bounds analysis).
  std::array<Index, 4> key{-1, -1, -1, -1};
  for (int corner = 0; corner < count; ++corner) key[static_cast<std::size_t>(corner)] = nodes[corner];
  for (int next = 1; next < count; ++next)
    for (int slot = next;
         slot > 0 && key[static_cast<std::size_t>(slot - 1)] > key[static_cast<std::size_t>(slot)]; --slot)
      std::swap(key[static_cast<std::size_t>(slot - 1)], key[static_cast<std::size_t>(slot)]);
  return key;
}

int face_nodes(const MixedMesh& mesh, const CellFace& face, Index* nodes) {
  const LocalFace& local = descriptor(face.type).faces[face.local_face];
  const Index* cell = mesh.cell(face.type, static_cast<std::size_t>(face.cell));
  for (int corner = 0; corner < local.node_count; ++corner) nodes[corner] = cell[local.nodes[corner]];
  return local.node_count;
}

FaceConnectivity match_faces(const MixedMesh& mesh) {
  // Bucket every face by its smallest node (counting sort), then match inside the
  // small buckets: linear in the number of faces, no hashing of whole faces.
  // visit(key, owner) for every face of every cell.
  auto for_each_cell_face = [&mesh](auto&& visit) {
    for (CellType type : all_cell_types) {
      const CellDescriptor& cell = descriptor(type);
      const std::size_t count = mesh.cell_count(type);
      for (std::size_t index_in_block = 0; index_in_block < count; ++index_in_block) {
        const Index* nodes = mesh.cell(type, index_in_block);
        for (int face = 0; face < cell.face_count; ++face) {
          const LocalFace& local = cell.faces[face];
          Index corners[4] = {-1, -1, -1, -1};
          for (int corner = 0; corner < local.node_count; ++corner)
            corners[corner] = nodes[local.nodes[corner]];
          visit(sorted_face_key(corners, local.node_count),
                CellFace{type, static_cast<Index>(index_in_block), face});
        }
      }
    }
  };
  const std::size_t point_count = mesh.points.size();
  std::vector<std::size_t> start(point_count + 1, 0);
  std::size_t face_total = 0;
  for_each_cell_face([&](const std::array<Index, 4>& key, const CellFace&) {
    ++start[static_cast<std::size_t>(key[0]) + 1];
    ++face_total;
  });
  for (std::size_t point = 0; point < point_count; ++point) start[point + 1] += start[point];

  std::vector<FaceRecord> records(face_total);
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for_each_cell_face([&](const std::array<Index, 4>& key, const CellFace& owner) {
    records[fill[static_cast<std::size_t>(key[0])]++] = FaceRecord{key, owner};
  });

  FaceConnectivity result;
  // Boundary cell faces, keyed for the comparison with the tagged faces below.
  std::vector<std::array<Index, 4>> boundary_keys;
  for (std::size_t point = 0; point < point_count; ++point) {
    const std::size_t begin = start[point];
    const std::size_t end = start[point + 1];
    std::sort(records.begin() + static_cast<std::ptrdiff_t>(begin),
              records.begin() + static_cast<std::ptrdiff_t>(end),
              [](const FaceRecord& a, const FaceRecord& b) { return a.key < b.key; });
    for (std::size_t first = begin; first < end;) {
      std::size_t last = first + 1;
      while (last < end && records[last].key == records[first].key) ++last;
      const std::size_t multiplicity = last - first;
      if (multiplicity == 1) {
        result.boundary.push_back(records[first].owner);
        boundary_keys.push_back(records[first].key);
      } else if (multiplicity == 2) {
        Index a[4] = {-1, -1, -1, -1};
        Index b[4] = {-1, -1, -1, -1};
        const int count = face_nodes(mesh, records[first].owner, a);
        face_nodes(mesh, records[first + 1].owner, b);
        const std::array<CellFace, 2> pair{records[first].owner, records[first + 1].owner};
        if (winding(a, count) == winding(b, count))
          result.same_orientation.push_back(pair);
        else
          result.interior.push_back(pair);
      } else {
        for (std::size_t member = first; member < last; ++member)
          result.shared_by_many.push_back(records[member].owner);
      }
      first = last;
    }
  }

  // Tagged boundary faces against boundary cell faces.
  std::unordered_map<std::size_t, std::vector<std::size_t>> tagged_by_node;
  std::vector<std::array<Index, 4>> tagged_keys;
  std::vector<std::pair<FaceType, std::size_t>> tagged_ids;
  for (FaceType type : all_face_types) {
    const int count = node_count(type);
    for (std::size_t face = 0; face < mesh.face_count(type); ++face) {
      const auto key = sorted_face_key(mesh.face(type, face), count);
      tagged_by_node[static_cast<std::size_t>(key[0])].push_back(tagged_keys.size());
      tagged_keys.push_back(key);
      tagged_ids.emplace_back(type, face);
    }
  }
  std::vector<char> tagged_used(tagged_keys.size(), 0);
  for (std::size_t face = 0; face < boundary_keys.size(); ++face) {
    const auto& key = boundary_keys[face];
    bool found = false;
    const auto candidates = tagged_by_node.find(static_cast<std::size_t>(key[0]));
    if (candidates != tagged_by_node.end()) {
      for (std::size_t candidate : candidates->second) {
        if (tagged_keys[candidate] == key) {
          tagged_used[candidate] = 1;
          found = true;
        }
      }
    }
    if (!found) result.untagged_boundary.push_back(result.boundary[face]);
  }
  for (std::size_t tagged = 0; tagged < tagged_keys.size(); ++tagged)
    if (!tagged_used[tagged]) result.stray_boundary_faces.push_back(tagged_ids[tagged]);

  // Triangles whose nodes all belong to one quad of the boundary.
  std::unordered_map<Index, std::vector<std::size_t>> quads_by_node;
  std::vector<std::array<Index, 4>> quad_keys;
  for (std::size_t face = 0; face < boundary_keys.size(); ++face) {
    if (boundary_keys[face][3] < 0) continue;
    for (Index node : boundary_keys[face]) quads_by_node[node].push_back(quad_keys.size());
    quad_keys.push_back(boundary_keys[face]);
  }
  if (!quad_keys.empty()) {
    for (const auto& key : boundary_keys) {
      if (key[3] >= 0) continue;
      const auto candidates = quads_by_node.find(key[0]);
      if (candidates == quads_by_node.end()) continue;
      for (std::size_t quad : candidates->second) {
        const auto& corners = quad_keys[quad];
        auto holds = [&](Index node) {
          return std::find(corners.begin(), corners.end(), node) != corners.end();
        };
        if (holds(key[1]) && holds(key[2])) {
          ++result.triangles_in_quads;
          break;
        }
      }
    }
  }
  return result;
}

std::vector<std::array<Index, 2>> triangle_free_edges(const std::vector<std::array<Index, 3>>& triangles) {
  // Undirected edge → (use count, the directed edge as first met).
  std::map<std::pair<Index, Index>, std::pair<int, std::array<Index, 2>>> edges;
  for (const auto& triangle : triangles) {
    for (int corner = 0; corner < 3; ++corner) {
      const Index from = triangle[static_cast<std::size_t>(corner)];
      const Index to = triangle[static_cast<std::size_t>((corner + 1) % 3)];
      auto& entry = edges[{std::min(from, to), std::max(from, to)}];
      if (entry.first++ == 0) entry.second = {from, to};
    }
  }
  std::vector<std::array<Index, 2>> free_edges;
  for (const auto& [key, entry] : edges)
    if (entry.first == 1) free_edges.push_back(entry.second);
  return free_edges;
}

}  // namespace mixmesh
