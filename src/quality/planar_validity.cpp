// validate() for planar meshes: triangles and quads in the z = 0 plane, with boundary
// edges carrying the markers.
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "validity_parts.hpp"

namespace mixmesh::quality_detail {

namespace {

struct EdgeRecord {
  std::array<Index, 2> key;  // sorted nodes
  bool forward;              // the cell runs from key[0] to key[1]
  FaceType type;
  std::size_t cell;
  bool operator<(const EdgeRecord& other) const { return key < other.key; }
};

Vector3 planar_centre(const MixedMesh& mesh, FaceType type, std::size_t cell) {
  const Index* nodes = mesh.planar_cells[static_cast<std::size_t>(index(type))].nodes.data() +
                       cell * static_cast<std::size_t>(node_count(type));
  Vector3 sum = Vector3::Zero();
  for (int corner = 0; corner < node_count(type); ++corner)
    sum += mesh.points[static_cast<std::size_t>(nodes[corner])];
  return sum / node_count(type);
}

}  // namespace

ValidityReport validate_planar(const MixedMesh& mesh, const ValidityOptions& options) {
  ValidityReport report;
  report.planar = true;
  report.points = mesh.points.size();
  const std::vector<Vector3>& points = mesh.points;
  auto at = [&](Index node) -> const Vector3& { return points[static_cast<std::size_t>(node)]; };

  Finding non_positive = make_finding("non_positive_area", "planar cells with non-positive signed area");
  Finding tangled =
      make_finding("tangled_cells", "planar cells with positive area but a reflex or folded corner");
  std::vector<char> used(points.size(), 0);
  std::vector<EdgeRecord> edges;
  for (FaceType type : all_face_types) {
    const FaceBlock& block = mesh.planar_cells[static_cast<std::size_t>(index(type))];
    const int count = node_count(type);
    const std::size_t cells = block.nodes.size() / static_cast<std::size_t>(count);
    for (std::size_t cell = 0; cell < cells; ++cell) {
      const Index* nodes = block.nodes.data() + cell * static_cast<std::size_t>(count);
      double twice_area = 0.0;
      int negative_corners = 0;
      for (int corner = 0; corner < count; ++corner) {
        const Vector3& previous = at(nodes[(corner + count - 1) % count]);
        const Vector3& here = at(nodes[corner]);
        const Vector3& next = at(nodes[(corner + 1) % count]);
        twice_area += here.x() * next.y() - next.x() * here.y();  // shoelace
        const double cross =
            (next - here).x() * (previous - here).y() - (next - here).y() * (previous - here).x();
        negative_corners += cross <= 0.0;
        used[static_cast<std::size_t>(nodes[corner])] = 1;
        const Index from = nodes[corner];
        const Index to = nodes[(corner + 1) % count];
        edges.push_back({{std::min(from, to), std::max(from, to)}, from < to, type, cell});
      }
      if (std::isfinite(twice_area)) report.total_volume += 0.5 * twice_area;
      if (!std::isfinite(twice_area)) continue;  // reported with the points
      const std::string entity = "planar " + std::string(name(type));
      if (twice_area <= 0.0)
        add_offender(non_positive, options.examples, entity, cell, planar_centre(mesh, type, cell));
      else if (negative_corners > 0)
        add_offender(tangled, options.examples, entity, cell, planar_centre(mesh, type, cell));
    }
  }
  report.findings.push_back(std::move(non_positive));
  report.findings.push_back(std::move(tangled));

  tbb::parallel_sort(edges.begin(), edges.end());
  std::vector<std::array<Index, 2>> tagged;
  for (std::size_t edge = 0; edge < mesh.boundary_edges.nodes.size() / 2; ++edge) {
    const Index a = mesh.boundary_edges.nodes[2 * edge];
    const Index b = mesh.boundary_edges.nodes[2 * edge + 1];
    tagged.push_back({std::min(a, b), std::max(a, b)});
  }
  std::vector<std::size_t> tagged_order(tagged.size());
  for (std::size_t edge = 0; edge < tagged.size(); ++edge) tagged_order[edge] = edge;
  std::sort(tagged_order.begin(), tagged_order.end(),
            [&](std::size_t a, std::size_t b) { return tagged[a] < tagged[b]; });
  std::vector<char> tagged_used(tagged.size(), 0);
  auto tag_of = [&](const std::array<Index, 2>& key) {
    auto found = std::lower_bound(
        tagged_order.begin(), tagged_order.end(), key,
        [&](std::size_t edge, const std::array<Index, 2>& value) { return tagged[edge] < value; });
    bool any = false;
    for (; found != tagged_order.end() && tagged[*found] == key; ++found) tagged_used[*found] = any = true;
    return any;
  };

  Finding many = make_finding("edges_on_many_cells", "edges shared by more than two planar cells");
  Finding same = make_finding("same_orientation", "interior edges run the same way by both cells");
  Finding untagged =
      make_finding("untagged_boundary_edges", "boundary edges without a marker",
                   options.require_markers ? Finding::Severity::error : Finding::Severity::warning);
  for (std::size_t first = 0; first < edges.size();) {
    std::size_t last = first + 1;
    while (last < edges.size() && edges[last].key == edges[first].key) ++last;
    const EdgeRecord& edge = edges[first];
    const Vector3 middle = 0.5 * (at(edge.key[0]) + at(edge.key[1]));
    const std::string entity = "planar " + std::string(name(edge.type));
    const std::string nodes = "edge " + std::to_string(edge.key[0]) + "-" + std::to_string(edge.key[1]);
    if (last - first == 1) {
      ++report.boundary_faces;
      if (!tag_of(edge.key)) add_offender(untagged, options.examples, entity, edge.cell, middle, nodes);
    } else if (last - first == 2) {
      ++report.interior_faces;
      if (edges[first].forward == edges[first + 1].forward)
        add_offender(same, options.examples, entity, edge.cell, middle, nodes);
    } else {
      add_offender(many, options.examples, entity, edge.cell, middle, nodes);
    }
    first = last;
  }
  report.findings.push_back(std::move(many));
  report.findings.push_back(std::move(same));
  report.findings.push_back(std::move(untagged));

  Finding stray =
      make_finding("markers_off_boundary", "tagged edges that are not boundary edges of the cells");
  for (std::size_t edge = 0; edge < tagged.size(); ++edge)
    if (!tagged_used[edge])
      add_offender(stray, options.examples, "boundary edge", edge,
                   0.5 * (at(tagged[edge][0]) + at(tagged[edge][1])));
  report.findings.push_back(std::move(stray));

  // Points off the plane, by the same yardstick as duplicates: the bounding box.
  Vector3 lower = Vector3::Constant(INFINITY);
  Vector3 upper = -lower;
  for (const Vector3& point : points)
    if (point.allFinite()) lower = lower.cwiseMin(point), upper = upper.cwiseMax(point);
  const double limit = options.planar_tolerance * (upper - lower).norm();
  Finding off_plane = make_finding("points_off_plane", "points of a planar mesh away from z = 0");
  for (std::size_t point = 0; point < points.size(); ++point)
    if (points[point].allFinite() && std::abs(points[point].z()) > limit)
      add_offender(off_plane, options.examples, "point", point, points[point]);
  report.findings.push_back(std::move(off_plane));

  check_points(mesh, used, options, report.findings);
  return report;
}

}  // namespace mixmesh::quality_detail
