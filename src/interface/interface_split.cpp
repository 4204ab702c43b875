#include "mixmesh/interface/interface_split.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <set>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "cap_clearance.hpp"
#include "interface_caps.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/mesh/face_connectivity.hpp"
#include "split_choice.hpp"

namespace mixmesh {

namespace {

using interface_detail::cap_cell;
using interface_detail::cap_rules;
using interface_detail::CapRules;
using interface_detail::choose_split;
using interface_detail::choose_stack;
using interface_detail::FaceKey;
using interface_detail::FaceNeighbours;
using interface_detail::for_each_piece;
using interface_detail::joined_stack;
using interface_detail::meets_bounds;
using interface_detail::same_type_neighbours;
using interface_detail::SplitChoice;
using interface_detail::unsplittable_cap_quality;

// Checks the outer-layer listing against the mesh before anything is built, so a bad
// listing fails with the offending cell named rather than with a broken mesh.
FaceConnectivity validate(const MixedMesh& mesh, const OuterLayer& layer) {
  FaceConnectivity connectivity = match_faces(mesh);
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
  return connectivity;
}

// Splits one cell or stack about its chosen point: a pyramid on every quad face that
// stays, two tetrahedra on every outer quad, one tetrahedron on every triangle face.
// Outer faces join the hull.
void split_cell(const MixedMesh& mesh, CellType type, const std::vector<unsigned>& outer_faces,
                const InterfaceOptions& options, const SplitChoice& choice, InterfaceResult& result) {
  MixedMesh& out = result.mesh;
  const Vector3& point = choice.point;
  const Index centre = static_cast<Index>(out.points.size());
  out.points.push_back(point);
  result.centres.push_back(centre);
  const std::size_t cell = choice.cells.front();
  for (std::size_t level = 0; level < choice.cells.size(); ++level) {
    const std::size_t here = choice.cells[level];
    const unsigned skipped = choice.skipped_faces.empty() ? 0u : choice.skipped_faces[level];
    const int region = mesh.block(type).regions[here];
    for_each_piece(type, out.points, mesh.cell(type, here), outer_faces[here], skipped, choice.flipped,
                   options, centre, [&](CellType piece, const Index* corners, bool outer) {
                     if (!cell_shape(piece, out.points, corners).valid())
                       throw Error("interface: splitting " + std::string(name(type)) + " " +
                                   std::to_string(cell) + " near " + point_text(point) +
                                   " gives an inverted " + std::string(name(piece)));
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
  if (choice.cells.size() > 1) {
    ++result.stacks;
    result.stacked_cells += choice.cells.size();
  }
}

// The outer cells of one type with their outer faces as bit masks, in the order of
// their first listing.
struct OuterCells {
  CellType type;
  std::vector<unsigned> outer_faces;  // per cell of the type
  std::vector<std::size_t> order;
};

OuterCells outer_cells(const MixedMesh& mesh, CellType type, const std::vector<OuterCell>& cells) {
  OuterCells outer{type, std::vector<unsigned>(mesh.cell_count(type), 0u), {}};
  for (const OuterCell& entry : cells) {
    if (outer.outer_faces[entry.cell] == 0u) outer.order.push_back(entry.cell);
    outer.outer_faces[entry.cell] |= 1u << entry.outer_face;
  }
  return outer;
}

// A cell is split when a quad faces the far field; a prism whose outer faces are
// triangles passes through and adds them to the hull as they are. Cells with an outer
// quad tagged capped_marker are capped instead, except hexahedra that touch another
// outer face or have a marked quad on the footprint that cannot lean on the plane (more
// than one footprint edge, or no plane quad under it).
void choose_treatment(const MixedMesh& mesh, const OuterCells& outer, const CapRules& rules,
                      std::vector<char>& split, std::vector<char>& capped) {
  const CellType type = outer.type;
  split.assign(outer.outer_faces.size(), 0);
  capped.assign(outer.outer_faces.size(), 0);
  for (std::size_t cell : outer.order) {
    bool quad = false, footprint = false;
    for (int face = 0; face < descriptor(type).face_count; ++face) {
      if (!((outer.outer_faces[cell] >> face) & 1u)) continue;
      Index corners[4] = {-1, -1, -1, -1};
      if (face_nodes(mesh, {type, static_cast<Index>(cell), face}, corners) != 4) continue;
      quad = true;
      const bool marked = rules.capped_quads.count(sorted_face_key(corners, 4)) > 0;
      capped[cell] = capped[cell] || marked;
      footprint = footprint || (marked && rules.on_footprint(corners, 4) && rules.plane_edge(corners) < 0);
    }
    const Index* nodes = mesh.cell(type, cell);
    auto plain = [&](Index node) { return rules.plain_hull_node[static_cast<std::size_t>(node)] != 0; };
    if (type == CellType::hexahedron && (footprint || std::any_of(nodes, nodes + node_count(type), plain)))
      capped[cell] = 0;
    split[cell] = quad && !capped[cell];
  }
}

// A split whose pieces miss the bounds joins the split next to it along a column of
// outer cells (`column_axis`) where the two split better together: the stacks chosen
// one after another along the column can leave its last cells to a stack too thin for
// its length. As long as that goes on helping.
void join_splits(const MixedMesh& mesh, const OuterCells& outer, const std::vector<char>& split,
                 const FaceNeighbours& neighbours, const InterfaceOptions& options,
                 std::vector<SplitChoice>& choices) {
  const CellType type = outer.type;
  const int faces = descriptor(type).face_count;
  constexpr std::size_t none = static_cast<std::size_t>(-1);
  std::vector<std::size_t> owner(outer.outer_faces.size(), none);  // the item splitting each cell
  for (std::size_t item = 0; item < choices.size(); ++item)
    for (std::size_t cell : choices[item].cells) owner[cell] = item;
  for (std::size_t item = 0; item < choices.size(); ++item) {
    if (!split[outer.order[item]]) continue;
    bool joined_one = true;
    while (joined_one) {
      joined_one = false;
      SplitChoice& here = choices[item];
      if (here.cells.empty() || here.quality.worst <= 0.0 || meets_bounds(here.quality, options)) break;
      for (std::size_t level = 0; level < here.cells.size() && !joined_one; ++level)
        for (int face = 0; face < faces && !joined_one; ++face) {
          const Index neighbour =
              neighbours[here.cells[level] * static_cast<std::size_t>(faces) + static_cast<std::size_t>(face)]
                  .first;
          if (neighbour < 0) continue;
          const std::size_t other = owner[static_cast<std::size_t>(neighbour)];
          if (other == none || other == item || choices[other].cells.empty()) continue;
          std::optional<SplitChoice> joined =
              joined_stack(mesh, type, here, choices[other], neighbours, outer.outer_faces, options);
          if (!joined) continue;
          for (std::size_t cell : choices[other].cells) owner[cell] = item;
          choices[other].cells.clear();
          here = std::move(*joined);
          joined_one = true;
        }
    }
  }
}

// The split points, found side by side: each search evaluates hundreds of piece shapes
// on the thin cells of free edges, and depends on its own cell alone. Then each cell
// goes to one split: a stack that reaches a cell another split took already is chosen
// again round the cells taken (in a column of outer cells, as along a wake's last cell
// at its tip edge, the stacks then follow one another), and an outer cell a stack took
// is not split again (its choice is left empty; a capped one loses its cap).
std::vector<SplitChoice> choose_splits(const MixedMesh& mesh, const OuterCells& outer,
                                       const std::vector<char>& split, std::vector<char>& capped,
                                       const FaceConnectivity& connectivity, const InterfaceOptions& options,
                                       std::vector<char>& stacked) {
  const CellType type = outer.type;
  const FaceNeighbours neighbours = same_type_neighbours(mesh, type, connectivity);
  std::vector<SplitChoice> choices(outer.order.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, outer.order.size(), 64),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t item = range.begin(); item != range.end(); ++item) {
                        const std::size_t cell = outer.order[item];
                        if (split[cell])
                          choices[item] =
                              choose_stack(mesh, type, cell, outer.outer_faces, capped, neighbours, options);
                      }
                    });
  stacked.assign(outer.outer_faces.size(), 0);
  std::vector<char> barred = capped;  // for stacks chosen again: 2 where another split took the cell
  for (std::size_t item = 0; item < outer.order.size(); ++item) {
    const std::size_t cell = outer.order[item];
    SplitChoice& choice = choices[item];
    if (!split[cell]) continue;
    if (stacked[cell]) {
      choice.cells.clear();
      continue;
    }
    if (std::any_of(choice.cells.begin() + 1, choice.cells.end(),
                    [&](std::size_t below) { return stacked[below] != 0; })) {
      choice = choose_stack(mesh, type, cell, outer.outer_faces, barred, neighbours, options);
    }
    for (std::size_t taken : choice.cells) stacked[taken] = 1, barred[taken] = 2;
  }
  join_splits(mesh, outer, split, neighbours, options, choices);
  // A capped cell a column's stack took is split with it instead.
  for (std::size_t cell = 0; cell < capped.size(); ++cell)
    if (stacked[cell]) capped[cell] = 0;
  return choices;
}

// The edges of a cell's outer faces.
std::vector<std::pair<Index, Index>> outer_edges(CellType type, const Index* nodes, unsigned outer_faces) {
  std::vector<std::pair<Index, Index>> edges;
  const CellDescriptor& shape = descriptor(type);
  for (int face = 0; face < shape.face_count; ++face) {
    if (!((outer_faces >> face) & 1u)) continue;
    const LocalFace& local = shape.faces[static_cast<std::size_t>(face)];
    for (int corner = 0; corner < local.node_count; ++corner)
      edges.push_back(
          std::minmax(nodes[local.nodes[static_cast<std::size_t>(corner)]],
                      nodes[local.nodes[static_cast<std::size_t>((corner + 1) % local.node_count)]]));
  }
  return edges;
}

// Whether a valid split (of a cell or a stack) leaves a pyramid below
// split_pyramid_floor where capping its outer cell gives valid caps with better
// pyramids, the cells under it in the stack have no face on the hull, and no cap of
// this kind stands next to it already (`capped_edges`): the valley between two low caps
// over a long shared edge is flat.
bool caps_beat_split(CellType type, const MixedMesh& mesh, const std::vector<unsigned>& outer_faces,
                     const SplitChoice& choice, const std::set<std::pair<Index, Index>>& capped_edges,
                     const InterfaceOptions& options) {
  if (choice.quality.worst_pyramid >= options.split_pyramid_floor) return false;
  for (std::size_t level = 1; level < choice.cells.size(); ++level)
    if (outer_faces[choice.cells[level]] != 0u) return false;
  const std::size_t cell = choice.cells.front();
  for (const auto& edge : outer_edges(type, mesh.cell(type, cell), outer_faces[cell]))
    if (capped_edges.count(edge)) return false;
  return unsplittable_cap_quality(type, mesh.points, mesh.cell(type, cell), outer_faces[cell], options) >
         choice.quality.worst_pyramid;
}

// The cells of one type into the result: untouched cells as they are, then the caps of
// the marked cells, then the splits (or, for an unsplittable cell where allowed, the
// whole cell capped) and the outer faces of the cells that pass through.
void replace_outer_cells(const MixedMesh& mesh, const OuterCells& outer, const CapRules& rules,
                         const FaceConnectivity& connectivity, const InterfaceOptions& options,
                         InterfaceResult& result, std::vector<interface_detail::TallCap>& tall_caps,
                         std::set<std::pair<Index, Index>>& capped_edges) {
  const CellType type = outer.type;
  std::vector<char> split, capped, stacked;
  choose_treatment(mesh, outer, rules, split, capped);
  const std::vector<SplitChoice> choices =
      choose_splits(mesh, outer, split, capped, connectivity, options, stacked);
  const CellBlock& block = mesh.block(type);
  const std::vector<unsigned>& outer_faces = outer.outer_faces;
  for (std::size_t cell = 0; cell < outer_faces.size(); ++cell)
    if (!stacked[cell]) result.mesh.add_cell(type, mesh.cell(type, cell), block.regions[cell]);
  for (std::size_t cell : outer.order)
    if (capped[cell])
      cap_cell(type, cell, mesh.cell(type, cell), outer_faces[cell], block.regions[cell], options,
               options.marked_cap_height, false, result, &tall_caps, &rules);
  for (std::size_t item = 0; item < outer.order.size(); ++item) {
    const std::size_t cell = outer.order[item];
    if (capped[cell]) continue;
    if (split[cell]) {
      if (choices[item].cells.empty()) continue;  // in another cell's stack
      // The centre split unless no split point keeps every piece valid (thin cells with
      // a warped face): then, if allowed, the cell stays whole and its outer quads are
      // capped; if not, split_cell names the inverted piece.
      // So also a cell or stack whose best split leaves a pyramid under the floor, where
      // its outer cell's caps are better (InterfaceOptions::split_pyramid_floor); a
      // stack's other cells stay whole (caps_beat_split takes no stack whose other cells
      // face the far field, so a column's cells, capped ones among them, never get here).
      const SplitChoice& choice = choices[item];
      if ((choice.quality.worst > 0.0 &&
           !caps_beat_split(type, mesh, outer_faces, choice, capped_edges, options)) ||
          !options.cap_unsplittable_cells) {
        split_cell(mesh, type, outer_faces, options, choice, result);
      } else {
        for (std::size_t here : choice.cells)
          result.mesh.add_cell(type, mesh.cell(type, here), block.regions[here]);
        cap_cell(type, cell, mesh.cell(type, cell), outer_faces[cell], block.regions[cell], options,
                 options.cap_height, true, result);
        for (const auto& edge : outer_edges(type, mesh.cell(type, cell), outer_faces[cell]))
          capped_edges.insert(edge);
      }
      continue;
    }
    if (stacked[cell]) continue;  // a capped cell split in a column's stack
    for (int face = 0; face < descriptor(type).face_count; ++face) {
      if (!((outer_faces[cell] >> face) & 1u)) continue;
      const LocalFace& local = descriptor(type).faces[static_cast<std::size_t>(face)];
      const Index* nodes = mesh.cell(type, cell);
      result.hull.push_back({nodes[local.nodes[0]], nodes[local.nodes[1]], nodes[local.nodes[2]]});
    }
  }
}

}  // namespace

InterfaceResult split_interface(const MixedMesh& mesh, const OuterLayer& layer,
                                const InterfaceOptions& options) {
  for (const auto& [option, value] : {std::pair{"cap_height", options.cap_height},
                                      std::pair{"marked_cap_height", options.marked_cap_height}})
    if (!(value > 0.0) || !std::isfinite(value))
      throw Error(std::string("interface: ") + option + " must be > 0, got " + std::to_string(value));
  for (const auto& [option, value] : {std::pair{"stack_pyramid_quality", options.stack_pyramid_quality},
                                      std::pair{"split_pyramid_floor", options.split_pyramid_floor}})
    if (!(value > 0.0 && value <= 1.0))
      throw Error(std::string("interface: ") + option + " is a scaled Jacobian in (0, 1], got " +
                  std::to_string(value));
  const FaceConnectivity connectivity = validate(mesh, layer);

  InterfaceResult result;
  MixedMesh& out = result.mesh;
  out.points = mesh.points;
  out.marker_names = mesh.marker_names;
  for (CellType type : {CellType::tetrahedron, CellType::pyramid}) out.block(type) = mesh.block(type);

  const CapRules rules = cap_rules(mesh, layer, options);
  std::vector<interface_detail::TallCap> tall_caps;
  std::set<std::pair<Index, Index>> capped_edges;  // of the cells capped for a flat split
  std::set<FaceKey> hull_faces;  // to drop the old tags of the outer faces
  for (const auto& [type, cells] :
       {std::pair{CellType::hexahedron, &layer.hexahedra}, std::pair{CellType::prism, &layer.prisms}}) {
    for (const OuterCell& entry : *cells) {
      Index corners[4] = {-1, -1, -1, -1};
      const int count = face_nodes(mesh, {type, static_cast<Index>(entry.cell), entry.outer_face}, corners);
      hull_faces.insert(sorted_face_key(corners, count));
    }
    replace_outer_cells(mesh, outer_cells(mesh, type, *cells), rules, connectivity, options, result,
                        tall_caps, capped_edges);
  }

  for (FaceType type : all_face_types) {
    const int count = node_count(type);
    for (std::size_t face = 0; face < mesh.face_count(type); ++face) {
      const Index* nodes = mesh.face(type, face);
      if (hull_faces.count(sorted_face_key(nodes, count))) continue;
      out.add_face(type, nodes, mesh.faces(type).markers[face]);
    }
  }
  std::optional<interface_detail::Plane> plane;
  if (!rules.plane_quads.empty())
    plane = interface_detail::Plane{mesh.points[static_cast<std::size_t>(rules.plane_quads.begin()->first.first)],
                                    rules.plane_quads.begin()->second.second};
  result.lowered_caps = interface_detail::lower_crossing_caps(out, result.hull, tall_caps, plane);
  const int hull_marker = out.marker(options.hull_marker);
  for (const auto& triangle : result.hull) out.add_face(FaceType::triangle, triangle.data(), hull_marker);
  return result;
}

}  // namespace mixmesh
