// The far field's tetrahedron faces against the input triangles: the boundary faces
// tagged with their markers, and the metric lengths of the edges on the hull.
#include <algorithm>
#include <map>
#include <string>

#include "farfield/farfield_parts.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/mesh/face_connectivity.hpp"

namespace mixmesh {

namespace {

using FaceKey = std::array<Index, 4>;  // sorted_face_key of a triangle

FaceKey triangle_key(const std::array<Index, 3>& triangle) {
  return sorted_face_key(triangle.data(), 3);
}

}  // namespace

namespace farfield_detail {

void add_boundary_faces(const std::vector<Index>& global, const std::vector<Triangle>& hull,
                        const std::vector<Triangle>& plane, const std::vector<Triangle>& outer,
                        const FarFieldOptions& options, MixedMesh& mesh) {
  const int symmetry_marker = mesh.marker(options.symmetry_marker);
  const int farfield_marker = mesh.marker(options.farfield_marker);
  std::map<FaceKey, int> boundary_marker;  // -1: hull
  auto to_global = [&](const Triangle& triangle) {
    return triangle_key({global[static_cast<std::size_t>(triangle[0])],
                         global[static_cast<std::size_t>(triangle[1])],
                         global[static_cast<std::size_t>(triangle[2])]});
  };
  for (const Triangle& triangle : hull) boundary_marker[to_global(triangle)] = -1;
  for (const Triangle& triangle : plane) boundary_marker[to_global(triangle)] = symmetry_marker;
  for (const Triangle& triangle : outer) boundary_marker[to_global(triangle)] = farfield_marker;
  std::map<FaceKey, std::pair<int, std::array<Index, 3>>> faces;
  for (std::size_t cell = 0; cell < mesh.cell_count(CellType::tetrahedron); ++cell) {
    const Index* nodes = mesh.cell(CellType::tetrahedron, cell);
    for (int number = 0; number < tetrahedron_descriptor.face_count; ++number) {
      const LocalFace& local = tetrahedron_descriptor.faces[static_cast<std::size_t>(number)];
      const std::array<Index, 3> face = {nodes[local.nodes[0]], nodes[local.nodes[1]], nodes[local.nodes[2]]};
      auto& entry = faces[triangle_key(face)];
      if (entry.first++ == 0) entry.second = face;
    }
  }
  std::size_t matched = 0;
  for (const auto& [key, entry] : faces) {
    if (entry.first != 1) continue;
    const auto found = boundary_marker.find(key);
    if (found == boundary_marker.end())
      throw Error("farfield: TetGen left a boundary face that is not an input triangle, near " +
                  point_text(mesh.points[static_cast<std::size_t>(key[0])]));
    ++matched;
    if (found->second >= 0) mesh.add_face(FaceType::triangle, entry.second.data(), found->second);
  }
  if (matched != boundary_marker.size())
    throw Error("farfield: " + std::to_string(boundary_marker.size() - matched) +
                " boundary triangles are not faces of the tetrahedra (TetGen changed the boundary)");
}

}  // namespace farfield_detail

MetricLengthReport hull_metric_lengths(const MixedMesh& mesh, const std::vector<std::array<Index, 3>>& hull,
                                       const std::vector<Index>& metric_nodes,
                                       const std::vector<Matrix3>& metrics) {
  // Lookups by point number: the mesh has ten times as many tetrahedron faces as the
  // hull has triangles, and most are rejected by their first node.
  std::vector<const Matrix3*> metric_of(mesh.points.size(), nullptr);
  for (std::size_t entry = 0; entry < metric_nodes.size(); ++entry)
    if (metric_nodes[entry] >= 0 && static_cast<std::size_t>(metric_nodes[entry]) < metric_of.size())
      metric_of[static_cast<std::size_t>(metric_nodes[entry])] = &metrics[entry];
  std::vector<char> on_hull(mesh.points.size(), 0);
  std::vector<FaceKey> hull_keys;
  for (const auto& triangle : hull) {
    hull_keys.push_back(triangle_key(triangle));
    for (Index node : triangle) on_hull[static_cast<std::size_t>(node)] = 1;
  }
  std::sort(hull_keys.begin(), hull_keys.end());

  std::vector<double> lengths;
  const std::size_t count = mesh.cell_count(CellType::tetrahedron);
  for (std::size_t cell = 0; cell < count; ++cell) {
    const Index* nodes = mesh.cell(CellType::tetrahedron, cell);
    for (int face = 0; face < tetrahedron_descriptor.face_count; ++face) {
      const LocalFace& local = tetrahedron_descriptor.faces[static_cast<std::size_t>(face)];
      const std::array<Index, 3> corners = {nodes[local.nodes[0]], nodes[local.nodes[1]],
                                            nodes[local.nodes[2]]};
      if (!std::all_of(corners.begin(), corners.end(),
                       [&](Index node) { return on_hull[static_cast<std::size_t>(node)] != 0; }))
        continue;
      const FaceKey key = triangle_key(corners);
      if (!std::binary_search(hull_keys.begin(), hull_keys.end(), key)) continue;
      std::vector<Matrix3> face_metrics;
      for (Index node : {key[0], key[1], key[2]})
        if (const Matrix3* metric = metric_of[static_cast<std::size_t>(node)])
          face_metrics.push_back(*metric);
      if (face_metrics.empty()) continue;
      const Matrix3 metric = log_euclidean_mean(face_metrics);
      for (int edge_number = 0; edge_number < tetrahedron_descriptor.edge_count; ++edge_number) {
        const auto& edge = tetrahedron_descriptor.edges[static_cast<std::size_t>(edge_number)];
        lengths.push_back(metric_length(metric, mesh.points[static_cast<std::size_t>(nodes[edge[1]])] -
                                                    mesh.points[static_cast<std::size_t>(nodes[edge[0]])]));
      }
    }
  }
  MetricLengthReport report;
  report.edges = lengths.size();
  if (lengths.empty()) return report;
  std::sort(lengths.begin(), lengths.end());
  auto quantile = [&](double fraction) {
    return lengths[std::min(lengths.size() - 1,
                            static_cast<std::size_t>(fraction * static_cast<double>(lengths.size())))];
  };
  report.median = quantile(0.5);
  report.lower_decile = quantile(0.1);
  report.upper_decile = quantile(0.9);
  const auto within = std::count_if(lengths.begin(), lengths.end(),
                                    [](double length) { return length >= 0.6 && length <= 1.6; });
  report.within_range = static_cast<double>(within) / static_cast<double>(lengths.size());
  return report;
}

}  // namespace mixmesh
