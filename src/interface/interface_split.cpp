#include "mixmesh/interface/interface_split.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "cap_clearance.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/mesh/face_connectivity.hpp"

namespace mixmesh {

namespace {

using FaceKey = std::array<Index, 4>;

// Checks the outer-layer listing against the mesh before anything is built, so a bad
// listing fails with the offending cell named rather than with a broken mesh.
void validate(const MixedMesh& mesh, const OuterLayer& layer) {
  const FaceConnectivity connectivity = match_faces(mesh);
  std::set<std::array<std::size_t, 3>> boundary;
  for (const CellFace& face : connectivity.boundary)
    boundary.insert({static_cast<std::size_t>(index(face.type)), static_cast<std::size_t>(face.cell),
                     static_cast<std::size_t>(face.local_face)});

  auto check = [&](CellType type, const std::vector<OuterCell>& cells) {
    const std::size_t count = mesh.cell_count(type);
    std::set<std::pair<std::size_t, int>> seen;
    for (const OuterCell& outer : cells) {
      const std::string cell_name = std::string(name(type)) + " " + std::to_string(outer.cell);
      if (outer.cell >= count)
        throw Error("interface: outer " + cell_name + " does not exist (the mesh has " +
                    std::to_string(count) + " " + std::string(name(type)) + "s)");
      const CellDescriptor& cell = descriptor(type);
      if (outer.outer_face < 0 || outer.outer_face >= cell.face_count)
        throw Error("interface: outer face " + std::to_string(outer.outer_face) + " of " + cell_name +
                    " is not a face number (0.." + std::to_string(cell.face_count - 1) + ")");
      if (!seen.emplace(outer.cell, outer.outer_face).second)
        throw Error("interface: face " + std::to_string(outer.outer_face) + " of " + cell_name +
                    " is listed twice in the outer layer");
      if (!boundary.count({static_cast<std::size_t>(index(type)), outer.cell,
                           static_cast<std::size_t>(outer.outer_face)}))
        throw Error("interface: outer face " + std::to_string(outer.outer_face) + " of " + cell_name +
                    " is shared with another cell, so it cannot face the far field");
    }
  };
  check(CellType::hexahedron, layer.hexahedra);
  check(CellType::prism, layer.prisms);
}

// Position (0 or 1) of the first node of the chosen diagonal q[s]–q[s+2].
int diagonal_start(const std::vector<Vector3>& points, const Index* quad, HullDiagonal rule) {
  const int smallest_position = static_cast<int>(std::min_element(quad, quad + 4) - quad) % 2;
  if (rule == HullDiagonal::smallest_node) return smallest_position;
  auto at = [&](int corner) -> const Vector3& { return points[static_cast<std::size_t>(quad[corner])]; };
  const double first = (at(2) - at(0)).squaredNorm();
  const double second = (at(3) - at(1)).squaredNorm();
  // Equal lengths up to rounding (a rectangle) fall back to the node rule so the
  // choice never depends on the last bit of a coordinate.
  if (std::abs(first - second) <= 1e-12 * std::max(first, second)) return smallest_position;
  return first < second ? 0 : 1;
}

}  // namespace

namespace {

// The pieces a split about `apex` makes: pyramids on the quads that stay, two
// tetrahedra on every outer quad (along its chosen diagonal), one on every triangle.
// visit(CellType, nodes, is_hull_triangle) with the apex as node index `apex_index`.
// Bit f of `flipped` cuts outer quad f along the other diagonal than the rule's.
template <typename Visit>
void for_each_piece(CellType type, const std::vector<Vector3>& points, const Index* nodes,
                    unsigned outer_faces, unsigned flipped, const InterfaceOptions& options, Index apex_index,
                    Visit visit) {
  const CellDescriptor& shape = descriptor(type);
  for (int face = 0; face < shape.face_count; ++face) {
    const LocalFace& local = shape.faces[static_cast<std::size_t>(face)];
    Index corners[4] = {-1, -1, -1, -1};  // outward from the cell
    for (int corner = 0; corner < local.node_count; ++corner)
      corners[corner] = nodes[local.nodes[static_cast<std::size_t>(corner)]];
    const bool outer = (outer_faces >> face) & 1u;
    // Tetrahedron face 0-2-1 is outward, so (a, c, b, apex) keeps a-b-c outward.
    auto tetrahedron = [&](Index a, Index b, Index c) {
      const Index piece[4] = {a, c, b, apex_index};
      visit(CellType::tetrahedron, piece, outer);
    };
    if (local.node_count == 3) {
      tetrahedron(corners[0], corners[1], corners[2]);
    } else if (!outer) {
      // The pyramid base 0-1-2-3 turns counter-clockwise seen from the apex, i.e.
      // opposite to the cell's outward winding.
      const Index piece[5] = {corners[0], corners[3], corners[2], corners[1], apex_index};
      visit(CellType::pyramid, piece, false);
    } else {
      const int start =
          diagonal_start(points, corners, options.diagonal) ^ static_cast<int>((flipped >> face) & 1u);
      tetrahedron(corners[start], corners[start + 1], corners[start + 2]);
      tetrahedron(corners[start], corners[start + 2], corners[(start + 3) % 4]);
    }
  }
}

// The worst piece of a split about the last point of `points`: the smallest corner
// Jacobian (scaled), negative when a piece is inverted or tangled.
double worst_piece(CellType type, const std::vector<Vector3>& points, const Index* nodes,
                   unsigned outer_faces, unsigned flipped, const InterfaceOptions& options) {
  double worst = 1.0;
  const Index apex = static_cast<Index>(points.size() - 1);
  for_each_piece(type, points, nodes, outer_faces, flipped, options, apex,
                 [&](CellType piece, const Index* corners, bool) {
                   const CellShape shape = cell_shape(piece, points, corners);
                   worst = std::min(
                       worst, shape.valid() ? shape.min_corner_jacobian : -1.0 - shape.negative_corners);
                 });
  return worst;
}

// The split point: the cell centre (Wild Fig. 2) unless a piece about it is inverted
// or nearly so (a thin cell with a warped face), then the best point a compass search
// around the centre finds. The last point of `points` is the scratch slot for the
// candidate. Returns the worst piece about that point in `best_worst`.
Vector3 split_point(CellType type, std::vector<Vector3>& points, const Index* nodes, unsigned outer_faces,
                    unsigned flipped, const InterfaceOptions& options, double& best_worst) {
  Vector3 best = cell_centre(type, points, nodes);
  points.back() = best;
  best_worst = worst_piece(type, points, nodes, outer_faces, flipped, options);
  double step = 0.0;
  for (int corner = 0; corner < node_count(type); ++corner)
    step = std::max(step, (points[static_cast<std::size_t>(nodes[corner])] - best).norm());
  step *= 0.25;
  const Vector3 directions[6] = {Vector3::UnitX(),  -Vector3::UnitX(), Vector3::UnitY(),
                                 -Vector3::UnitY(), Vector3::UnitZ(),  -Vector3::UnitZ()};
  for (int iteration = 0; iteration < 60 && best_worst < options.centre_quality; ++iteration) {
    bool improved = false;
    for (const Vector3& direction : directions) {
      points.back() = best + step * direction;
      const double worst = worst_piece(type, points, nodes, outer_faces, flipped, options);
      if (worst > best_worst) {
        best_worst = worst;
        best = points.back();
        improved = true;
      }
    }
    if (!improved) step *= 0.5;
  }
  return best;
}

// Where and how a cell is split: the split point, the outer quads cut along the other
// diagonal than the rule's (bits as in for_each_piece), and the worst piece (not
// positive: no split makes every piece valid).
struct SplitChoice {
  Vector3 point = Vector3::Zero();
  unsigned flipped = 0u;
  double worst = 0.0;
};

// The split of one cell. The search works on a copy of the cell's nodes alone, numbered
// in the order of their numbers in the mesh (the diagonal rule compares node numbers),
// with the candidate point after them, so that cells can be searched side by side.
SplitChoice choose_split(CellType type, const std::vector<Vector3>& mesh_points, const Index* mesh_nodes,
                         unsigned outer_faces, const InterfaceOptions& options) {
  const int count = node_count(type);
  std::array<Index, 8> nodes{};
  std::vector<Vector3> points(static_cast<std::size_t>(count) + 1);
  for (int corner = 0; corner < count; ++corner) {
    Index rank = 0;
    for (int other = 0; other < count; ++other) rank += mesh_nodes[other] < mesh_nodes[corner];
    nodes[static_cast<std::size_t>(corner)] = rank;
    points[static_cast<std::size_t>(rank)] = mesh_points[static_cast<std::size_t>(mesh_nodes[corner])];
  }
  // The rule's diagonals first; where no split point makes every piece valid (an outer
  // quad twisted by more than the cell is thick, as at a wing tip's trailing edge), the
  // other diagonal of some outer quads: one of the two folds of a twisted quad leans
  // towards the cell's inside. Both triangles stay in this cell, so the hull conforms.
  std::vector<unsigned> outer_quads;
  for (int face = 0; face < descriptor(type).face_count; ++face)
    if (((outer_faces >> face) & 1u) &&
        descriptor(type).faces[static_cast<std::size_t>(face)].node_count == 4)
      outer_quads.push_back(1u << face);
  SplitChoice choice;
  choice.point = split_point(type, points, nodes.data(), outer_faces, choice.flipped, options, choice.worst);
  const unsigned combinations = 1u << std::min<std::size_t>(outer_quads.size(), 4);
  for (unsigned combination = 1; combination < combinations && choice.worst <= 0.0; ++combination) {
    unsigned candidate = 0u;
    for (std::size_t quad = 0; quad < outer_quads.size() && quad < 4; ++quad)
      if ((combination >> quad) & 1u) candidate |= outer_quads[quad];
    double candidate_worst = 0.0;
    const Vector3 candidate_point =
        split_point(type, points, nodes.data(), outer_faces, candidate, options, candidate_worst);
    if (candidate_worst > choice.worst) choice = {candidate_point, candidate, candidate_worst};
  }
  return choice;
}

// Splits one cell about its chosen point: a pyramid on every quad face that stays, two
// tetrahedra on every outer quad, one tetrahedron on every triangle face. Outer faces
// join the hull.
void split_cell(CellType type, std::size_t cell, const Index* nodes, unsigned outer_faces, int region,
                const InterfaceOptions& options, const SplitChoice& choice, InterfaceResult& result) {
  MixedMesh& out = result.mesh;
  const Vector3& point = choice.point;
  const Index centre = static_cast<Index>(out.points.size());
  out.points.push_back(point);
  result.centres.push_back(centre);
  for_each_piece(type, out.points, nodes, outer_faces, choice.flipped, options, centre,
                 [&](CellType piece, const Index* corners, bool outer) {
                   if (!cell_shape(piece, out.points, corners).valid())
                     throw Error("interface: splitting " + std::string(name(type)) + " " +
                                 std::to_string(cell) + " near " + point_text(point) + " gives an inverted " +
                                 std::string(name(piece)));
                   out.add_cell(piece, corners, region);
                   if (piece == CellType::pyramid) {
                     ++result.pyramids;
                     return;
                   }
                   ++result.tetrahedra;
                   // The tetrahedron (a, c, b, apex) of an outer triangle a-b-c.
                   if (outer) result.hull.push_back({corners[0], corners[2], corners[1]});
                 });
}

constexpr double minimum_cap_reach = 0.4;

// Keeps the cell and caps every outer quad with a pyramid outside it, apex above the
// quad's centre at cap_height × its shortest edge (for a marked cell at least
// minimum_cap_reach × its longest); the caps' sides join the hull.
void cap_cell(CellType type, std::size_t cell, const Index* nodes, unsigned outer_faces, int region,
              const InterfaceOptions& options, double cap_height, bool split_tried, InterfaceResult& result,
              std::vector<interface_detail::TallCap>* tall_caps = nullptr) {
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
    Vector3 middle = Vector3::Zero();
    double shortest = std::numeric_limits<double>::infinity(), longest = 0.0;
    for (int corner = 0; corner < 4; ++corner) {
      const Vector3& here = out.points[static_cast<std::size_t>(corners[corner])];
      middle += 0.25 * here;
      const double edge = (out.points[static_cast<std::size_t>(corners[(corner + 1) % 4])] - here).norm();
      shortest = std::min(shortest, edge);
      longest = std::max(longest, edge);
    }
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
    const double lowest_reach =
        split_tried ? shortest : std::max(shortest, std::min(minimum_cap_reach * longest, 2.0 * shortest));
    const Vector3 normal = face_area_vector(out.points, corners, 4).normalized();
    const Index apex = static_cast<Index>(out.points.size());
    out.points.push_back(middle + cap_height * reach * normal);
    // Seen from the apex (outside) the outward winding is counter-clockwise already.
    const Index pyramid[5] = {corners[0], corners[1], corners[2], corners[3], apex};
    // A twisted quad needs a higher apex (its corner normals lean away from the mean
    // normal): raise it, doubling, up to cap_height_limit times the quad's longest
    // diagonal, and stop at the first valid cap.
    const double diagonal = std::max(
        (out.points[static_cast<std::size_t>(corners[2])] - out.points[static_cast<std::size_t>(corners[0])])
            .norm(),
        (out.points[static_cast<std::size_t>(corners[3])] - out.points[static_cast<std::size_t>(corners[1])])
            .norm());
    // (A quad with an edge of zero length gets no cap: its height would stay zero.)
    for (double height = cap_height * reach; height > 0.0 &&
                                             !cell_shape(CellType::pyramid, out.points, pyramid).valid() &&
                                             2.0 * height <= options.cap_height_limit * diagonal;) {
      height *= 2.0;
      out.points.back() = middle + height * normal;
    }
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
                            height,
                            cap_height * lowest_reach,
                            {corners[0], corners[1], corners[2], corners[3], apex},
                            result.hull.size()});
    for (int corner = 0; corner < 4; ++corner)
      result.hull.push_back({corners[corner], corners[(corner + 1) % 4], apex});
  }
  ++result.capped_cells;
}

}  // namespace

InterfaceResult split_interface(const MixedMesh& mesh, const OuterLayer& layer,
                                const InterfaceOptions& options) {
  for (const auto& [option, value] : {std::pair{"cap_height", options.cap_height},
                                      std::pair{"marked_cap_height", options.marked_cap_height}})
    if (!(value > 0.0) || !std::isfinite(value))
      throw Error(std::string("interface: ") + option + " must be > 0, got " + std::to_string(value));
  validate(mesh, layer);

  InterfaceResult result;
  MixedMesh& out = result.mesh;
  out.points = mesh.points;
  out.marker_names = mesh.marker_names;
  for (CellType type : {CellType::tetrahedron, CellType::pyramid}) out.block(type) = mesh.block(type);

  // The boundary quads tagged capped_marker: their cells are capped, not split.
  std::set<FaceKey> capped_quads;
  const int capped_marker = options.capped_marker.empty() ? -1 : mesh.find_marker(options.capped_marker);
  if (capped_marker >= 0)
    for (std::size_t face = 0; face < mesh.face_count(FaceType::quad); ++face)
      if (mesh.faces(FaceType::quad).markers[face] == capped_marker)
        capped_quads.insert(sorted_face_key(mesh.face(FaceType::quad, face), 4));

  // Edges used by one outer face: the footprint on the symmetry plane. A marked
  // hexahedron with its outer quad there is split, not capped: the cap's apex would
  // stand half the quad's width from the plane, and the tetrahedra between it and the
  // plane's triangles were flat (175-176 deg along the ONERA M6 wake's root).
  std::map<std::pair<Index, Index>, int> outer_edge_uses;
  for (const auto& [type, cells] :
       {std::pair{CellType::hexahedron, &layer.hexahedra}, std::pair{CellType::prism, &layer.prisms}})
    for (const OuterCell& outer : *cells) {
      Index corners[4] = {-1, -1, -1, -1};
      const int count = face_nodes(mesh, {type, static_cast<Index>(outer.cell), outer.outer_face}, corners);
      for (int k = 0; k < count; ++k) ++outer_edge_uses[std::minmax(corners[k], corners[(k + 1) % count])];
    }
  auto on_footprint = [&](const Index* corners, int count) {
    for (int k = 0; k < count; ++k)
      if (outer_edge_uses[std::minmax(corners[k], corners[(k + 1) % count])] == 1) return true;
    return false;
  };

  // Nodes of the other outer faces: a hexahedron touching them is split as usual, so
  // caps stay away from where the marked hull meets the rest (a wake's trailing edge,
  // the tip trailing edge), whose faces meet at angles a cap could cross (a twisted tip).
  // Prisms are capped regardless: the one marked prism of the march, the first cell
  // between the two sheet lines at a junction, has no split point off its edges.
  std::vector<char> plain_hull_node(mesh.points.size(), 0);
  for (const auto& [type, cells] :
       {std::pair{CellType::hexahedron, &layer.hexahedra}, std::pair{CellType::prism, &layer.prisms}})
    for (const OuterCell& outer : *cells) {
      Index corners[4] = {-1, -1, -1, -1};
      const int count = face_nodes(mesh, {type, static_cast<Index>(outer.cell), outer.outer_face}, corners);
      if (count == 4 && capped_quads.count(sorted_face_key(corners, 4))) continue;
      for (int corner = 0; corner < count; ++corner)
        plain_hull_node[static_cast<std::size_t>(corners[corner])] = 1;
    }

  std::vector<interface_detail::TallCap> tall_caps;
  // Outer faces per cell as bit masks; cells in order of their first listing.
  std::set<FaceKey> hull_faces;  // to drop the old tags of the outer faces
  for (const auto& [type, cells] :
       {std::pair{CellType::hexahedron, &layer.hexahedra}, std::pair{CellType::prism, &layer.prisms}}) {
    std::vector<unsigned> outer_faces(mesh.cell_count(type), 0u);
    std::vector<std::size_t> order;
    for (const OuterCell& outer : *cells) {
      if (outer_faces[outer.cell] == 0u) order.push_back(outer.cell);
      outer_faces[outer.cell] |= 1u << outer.outer_face;
      Index corners[4] = {-1, -1, -1, -1};
      const int count = face_nodes(mesh, {type, static_cast<Index>(outer.cell), outer.outer_face}, corners);
      hull_faces.insert(sorted_face_key(corners, count));
    }
    // A cell is split when a quad faces the far field; a prism whose outer faces are
    // triangles passes through and adds them to the hull as they are.
    // Cells with an outer quad tagged capped_marker are capped instead, except hexahedra
    // that touch another outer face or have a marked quad on the footprint.
    std::vector<char> split(outer_faces.size(), 0), capped(outer_faces.size(), 0);
    for (std::size_t cell : order) {
      bool quad = false, footprint = false;
      for (int face = 0; face < descriptor(type).face_count; ++face) {
        if (!((outer_faces[cell] >> face) & 1u)) continue;
        Index corners[4] = {-1, -1, -1, -1};
        if (face_nodes(mesh, {type, static_cast<Index>(cell), face}, corners) != 4) continue;
        quad = true;
        const bool marked = capped_quads.count(sorted_face_key(corners, 4)) > 0;
        capped[cell] = capped[cell] || marked;
        footprint = footprint || (marked && on_footprint(corners, 4));
      }
      const Index* nodes = mesh.cell(type, cell);
      auto plain = [&](Index node) { return plain_hull_node[static_cast<std::size_t>(node)] != 0; };
      if (type == CellType::hexahedron && (footprint || std::any_of(nodes, nodes + node_count(type), plain)))
        capped[cell] = 0;
      split[cell] = quad && !capped[cell];
    }
    const CellBlock& block = mesh.block(type);
    for (std::size_t cell = 0; cell < outer_faces.size(); ++cell)
      if (!split[cell]) out.add_cell(type, mesh.cell(type, cell), block.regions[cell]);
    for (std::size_t cell : order)
      if (capped[cell])
        cap_cell(type, cell, mesh.cell(type, cell), outer_faces[cell], block.regions[cell], options,
                 options.marked_cap_height, false, result, &tall_caps);
    // The split points, found side by side: each search evaluates hundreds of piece
    // shapes on the thin cells of free edges, and depends on its own cell alone.
    std::vector<SplitChoice> choices(order.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, order.size(), 64),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t item = range.begin(); item != range.end(); ++item) {
                          const std::size_t cell = order[item];
                          if (split[cell])
                            choices[item] = choose_split(type, mesh.points, mesh.cell(type, cell),
                                                         outer_faces[cell], options);
                        }
                      });
    for (std::size_t item = 0; item < order.size(); ++item) {
      const std::size_t cell = order[item];
      if (capped[cell]) continue;
      if (split[cell]) {
        // The centre split unless no split point keeps every piece valid (thin cells with
        // a warped face): then, if allowed, the cell stays whole and its outer quads are
        // capped; if not, split_cell names the inverted piece.
        if (choices[item].worst > 0.0 || !options.cap_unsplittable_cells) {
          split_cell(type, cell, mesh.cell(type, cell), outer_faces[cell], block.regions[cell], options,
                     choices[item], result);
        } else {
          out.add_cell(type, mesh.cell(type, cell), block.regions[cell]);
          cap_cell(type, cell, mesh.cell(type, cell), outer_faces[cell], block.regions[cell], options,
                   options.cap_height, true, result);
        }
        continue;
      }
      for (int face = 0; face < descriptor(type).face_count; ++face) {
        if (!((outer_faces[cell] >> face) & 1u)) continue;
        const LocalFace& local = descriptor(type).faces[static_cast<std::size_t>(face)];
        const Index* nodes = mesh.cell(type, cell);
        result.hull.push_back({nodes[local.nodes[0]], nodes[local.nodes[1]], nodes[local.nodes[2]]});
      }
    }
  }

  for (FaceType type : all_face_types) {
    const int count = node_count(type);
    for (std::size_t face = 0; face < mesh.face_count(type); ++face) {
      const Index* nodes = mesh.face(type, face);
      if (hull_faces.count(sorted_face_key(nodes, count))) continue;
      out.add_face(type, nodes, mesh.faces(type).markers[face]);
    }
  }
  result.lowered_caps = interface_detail::lower_crossing_caps(out, result.hull, tall_caps);
  const int hull_marker = out.marker(options.hull_marker);
  for (const auto& triangle : result.hull) out.add_face(FaceType::triangle, triangle.data(), hull_marker);
  return result;
}

}  // namespace mixmesh
