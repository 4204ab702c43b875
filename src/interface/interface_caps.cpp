#include "interface_caps.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mixmesh/core/error.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/mesh/face_connectivity.hpp"

namespace mixmesh::interface_detail {

CapRules cap_rules(const MixedMesh& mesh, const OuterLayer& layer, const InterfaceOptions& options) {
  CapRules rules;
  const int capped_marker = options.capped_marker.empty() ? -1 : mesh.find_marker(options.capped_marker);
  if (capped_marker >= 0)
    for (std::size_t face = 0; face < mesh.face_count(FaceType::quad); ++face)
      if (mesh.faces(FaceType::quad).markers[face] == capped_marker)
        rules.capped_quads.insert(sorted_face_key(mesh.face(FaceType::quad, face), 4));
  rules.plain_hull_node.assign(mesh.points.size(), 0);
  std::set<FaceKey> outer_faces;
  for (const auto& [type, cells] :
       {std::pair{CellType::hexahedron, &layer.hexahedra}, std::pair{CellType::prism, &layer.prisms}})
    for (const OuterCell& outer : *cells) {
      Index corners[4] = {-1, -1, -1, -1};
      const int count = face_nodes(mesh, {type, static_cast<Index>(outer.cell), outer.outer_face}, corners);
      outer_faces.insert(sorted_face_key(corners, count));
      for (int k = 0; k < count; ++k)
        ++rules.outer_edge_uses[std::minmax(corners[k], corners[(k + 1) % count])];
      if (count == 4 && rules.capped_quads.count(sorted_face_key(corners, 4))) continue;
      for (int corner = 0; corner < count; ++corner)
        rules.plain_hull_node[static_cast<std::size_t>(corners[corner])] = 1;
    }
  // The plane quads: the symmetry plane's quads with a footprint edge.
  const int symmetry_marker = options.symmetry_marker.empty() ? -1 : mesh.find_marker(options.symmetry_marker);
  if (symmetry_marker < 0) return rules;
  for (std::size_t face = 0; face < mesh.face_count(FaceType::quad); ++face) {
    const Index* nodes = mesh.face(FaceType::quad, face);
    const int marker = mesh.faces(FaceType::quad).markers[face];
    if (marker != symmetry_marker || outer_faces.count(sorted_face_key(nodes, 4))) continue;
    for (int k = 0; k < 4; ++k) {
      const auto edge = std::minmax(nodes[k], nodes[(k + 1) % 4]);
      const auto uses = rules.outer_edge_uses.find(edge);
      if (uses != rules.outer_edge_uses.end() && uses->second == 1)
        rules.plane_quads.emplace(edge, std::pair{marker, face_area_vector(mesh.points, nodes, 4)});
    }
  }
  return rules;
}

namespace {

constexpr double minimum_cap_reach = 0.4;

// Stands the apex of cap `pyramid` (its last node, the last of `points`) `height` from
// `base` along `direction` and raises it, doubling, while the cap is inverted and the
// next height stays within `limit` (a twisted quad's corner normals lean away from its
// mean normal). Says whether the cap is valid. (A quad with an edge of zero length gets
// no cap: its height would stay zero.)
bool raise_cap_apex(std::vector<Vector3>& points, const Index* pyramid, const Vector3& base,
                    const Vector3& direction, double height, double limit) {
  points.back() = base + height * direction;
  for (; height > 0.0 && !cell_shape(CellType::pyramid, points, pyramid).valid() && 2.0 * height <= limit;) {
    height *= 2.0;
    points.back() = base + height * direction;
  }
  return cell_shape(CellType::pyramid, points, pyramid).valid();
}

// What a cap on a quad (corners outward from its cell) stands on: the quad's middle,
// its unit normal, its shortest and longest edge, its width (its area over its longest
// edge, where that is less than the shortest edge: a sheared quad is narrower than its
// short edges) and its longer diagonal.
struct CapBase {
  Vector3 middle = Vector3::Zero();
  Vector3 normal = Vector3::Zero();
  double shortest = std::numeric_limits<double>::infinity();
  double longest = 0.0;
  double width = 0.0;
  double diagonal = 0.0;
};

CapBase cap_base(const std::vector<Vector3>& points, const Index* corners) {
  CapBase base;
  auto at = [&](int corner) -> const Vector3& { return points[static_cast<std::size_t>(corners[corner])]; };
  for (int corner = 0; corner < 4; ++corner) {
    base.middle += 0.25 * at(corner);
    const double edge = (at((corner + 1) % 4) - at(corner)).norm();
    base.shortest = std::min(base.shortest, edge);
    base.longest = std::max(base.longest, edge);
  }
  const Vector3 area = face_area_vector(points, corners, 4);
  base.normal = area.normalized();
  base.width = std::min(base.shortest, area.norm() / base.longest);
  base.diagonal = std::max((at(2) - at(0)).norm(), (at(3) - at(1)).norm());
  return base;
}

}  // namespace

double unsplittable_cap_quality(CellType type, const std::vector<Vector3>& mesh_points, const Index* nodes,
                                unsigned outer_faces, const InterfaceOptions& options) {
  const CellDescriptor& shape = descriptor(type);
  double worst = 1.0;
  for (int face = 0; face < shape.face_count; ++face) {
    const LocalFace& local = shape.faces[static_cast<std::size_t>(face)];
    if (!((outer_faces >> face) & 1u) || local.node_count != 4) continue;
    std::vector<Vector3> points(5, Vector3::Zero());  // the quad's corners and the apex
    for (int corner = 0; corner < 4; ++corner)
      points[static_cast<std::size_t>(corner)] =
          mesh_points[static_cast<std::size_t>(nodes[local.nodes[static_cast<std::size_t>(corner)]])];
    const Index pyramid[5] = {0, 1, 2, 3, 4};
    const CapBase base = cap_base(points, pyramid);
    if (!raise_cap_apex(points, pyramid, base.middle, base.normal, options.cap_height * base.shortest,
                        options.cap_height_limit * base.diagonal))
      return -1.0;
    worst = std::min(worst, cell_shape(CellType::pyramid, points, pyramid).min_corner_jacobian);
  }
  return worst;
}

void cap_cell(CellType type, std::size_t cell, const Index* nodes, unsigned outer_faces, int region,
              const InterfaceOptions& options, double cap_height, bool split_tried, InterfaceResult& result,
              std::vector<TallCap>* tall_caps, const CapRules* rules) {
  MixedMesh& out = result.mesh;
  const CellDescriptor& shape = descriptor(type);
  for (int face = 0; face < shape.face_count; ++face) {
    if (!((outer_faces >> face) & 1u)) continue;
    const LocalFace& local = shape.faces[static_cast<std::size_t>(face)];
    Index corners[4] = {-1, -1, -1, -1};  // outward from the cell
    for (int corner = 0; corner < local.node_count; ++corner)
      corners[corner] = nodes[local.nodes[static_cast<std::size_t>(corner)]];
    if (local.node_count == 3) {
      result.hull.push_back({corners[0], corners[1], corners[2]});
      continue;
    }
    const CapBase base = cap_base(out.points, corners);
    const double shortest = base.shortest, longest = base.longest;
    Vector3 middle = base.middle;
    // The far field fills the valley between the caps of two neighbouring quads with a
    // tetrahedron of their shared edge and the two apexes; its dihedral angle at the
    // apexes' edge is 180 degrees less twice atan(2 h / L) for apex height h over an edge
    // of length L, and every tetrahedron on a cap face over that edge has an angle near
    // the face's apex angle, 180 degrees less twice atan(2 d / L) for an apex d from the
    // edge. On long, narrow quads (a wake's, 30:1 behind a trailing edge) a height from
    // the shortest edge alone made both slivers, so a marked cell's cap stands at least
    // a part of the longest edge high (minimum_cap_reach 0.4: 0.2 L for a cap height
    // 0.5, 136 deg). Where that crosses the hull (the concave corner behind a tip's
    // trailing edge) lower_crossing_caps brings it down, not below twice the shortest
    // edge. The caps of cells that could not be split (twisted cells at a tip's trailing
    // edge, in a concave corner of the hull) keep their low height.
    const double reach = split_tried ? shortest : std::max(shortest, minimum_cap_reach * longest);
    // The lowest a tall cap may come down to is set by its quad's width: the wake's
    // quads are sheared where its lines' nodes are staggered (behind a cranked trailing
    // edge, 3.5 mm wide with 14 mm short edges), and from the short edges such a cap
    // could not come down at all, so it was never tested against the hull; over a fold
    // it leant across its neighbour's cap.
    // A cap that its shortest edge would keep where it stands is tall only by its
    // sheared quad's width: a standard cap, which keeps its own normal (cap_clearance).
    const auto lowest_from = [&](double edge) {
      return split_tried ? shortest : std::max(edge, std::min(minimum_cap_reach * longest, 2.0 * edge));
    };
    const double lowest_reach = lowest_from(base.width), edge_lowest_reach = lowest_from(shortest);
    const Vector3& quad_normal = base.normal;
    Vector3 normal = quad_normal;
    const int plane_edge = rules ? rules->plane_edge(corners) : -1;
    const std::pair<int, Vector3>* plane_quad =
        plane_edge >= 0 ? &rules->plane_quads.at(std::minmax(corners[plane_edge], corners[(plane_edge + 1) % 4]))
                        : nullptr;
    // A cap over the middle of a quad next to the plane leaves a valley or a slot
    // against the plane that only low caps keep from folding, and low caps over a
    // wake's long end quads are flat (175-176 deg on random wings with the wake's
    // end rows metres long and centimetres wide). Leaning on the plane, the cap fills
    // that space and stands as tall as its neighbours: its apex goes over the middle of
    // the edge on the plane, along the quad's normal turned into the plane.
    const Index apex = static_cast<Index>(out.points.size());
    out.points.push_back(middle);
    // Seen from the apex (outside) the outward winding is counter-clockwise already.
    const Index pyramid[5] = {corners[0], corners[1], corners[2], corners[3], apex};
    // A twisted quad needs a higher apex (its corner normals lean away from the mean
    // normal): raise it, doubling, up to cap_height_limit times the quad's longest
    // diagonal, and stop at the first valid cap. Says whether the cap is valid.
    const auto stand = [&](const Vector3& foot, const Vector3& direction) {
      return raise_cap_apex(out.points, pyramid, foot, direction, cap_height * reach,
                            options.cap_height_limit * base.diagonal);
    };
    bool leans = false;
    if (plane_edge >= 0 && !split_tried) {
      const Vector3& first = out.points[static_cast<std::size_t>(corners[plane_edge])];
      const Vector3& second = out.points[static_cast<std::size_t>(corners[(plane_edge + 1) % 4])];
      const Vector3 plane_normal = plane_quad->second.normalized();
      const Vector3 along = (second - first).normalized();
      Vector3 up = quad_normal - quad_normal.dot(plane_normal) * plane_normal;
      up -= up.dot(along) * along;
      // Not where the quad leans over the plane itself, nor where no leaning cap is
      // valid (a strongly twisted quad): there the cap stands over the quad's middle.
      if (up.norm() > 0.5 && stand(0.5 * (first + second), up.normalized())) {
        leans = true;
        middle = 0.5 * (first + second);
        normal = up.normalized();
      }
    }
    if (!leans) stand(middle, normal);
    if (!cell_shape(CellType::pyramid, out.points, pyramid).valid())
      throw UnsplittableCellError(
          "interface: " + std::string(name(type)) + " " + std::to_string(cell) +
              (split_tried ? " can neither be split about its centre nor capped" : " cannot be capped") +
              " on face " + std::to_string(face) + " near " + point_text(middle),
          middle);
    out.add_cell(CellType::pyramid, pyramid, region);
    ++result.pyramids;
    const double height = (out.points.back() - middle).norm();
    if (tall_caps && cap_height * lowest_reach < height)
      tall_caps->push_back({apex,
                            middle,
                            normal,
                            normal,
                            height,
                            cap_height * lowest_reach,
                            {corners[0], corners[1], corners[2], corners[3], apex},
                            result.hull.size(),
                            leans ? 3u : 4u,
                            leans,
                            !(cap_height * edge_lowest_reach < height)});
    for (int corner = 0; corner < 4; ++corner) {
      const Index triangle[3] = {corners[corner], corners[(corner + 1) % 4], apex};
      if (leans && corner == plane_edge)
        out.add_face(FaceType::triangle, triangle, plane_quad->first);
      else
        result.hull.push_back({triangle[0], triangle[1], triangle[2]});
    }
  }
  ++result.capped_cells;
}

}  // namespace mixmesh::interface_detail
