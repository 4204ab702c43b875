// Layer stacks found from the topology (layer_lines.hpp says why; their transport is in
// layer_transport.cpp).
#include "deform/layer_lines.hpp"

#include <algorithm>
#include <array>
#include <unordered_set>

#include "mixmesh/mesh/face_connectivity.hpp"
#include "mixmesh/mesh/topology.hpp"

namespace mixmesh::deform::detail {

namespace {

struct Face {
  std::array<Index, 4> nodes{-1, -1, -1, -1};
  int count = 0;
  bool has(Index node) const {
    return std::find(nodes.begin(), nodes.begin() + count, node) != nodes.begin() + count;
  }
};

bool is_layer_cell(const DualMesh& dual, std::size_t cell, int face_size) {
  const int kind = dual.cell_kind[cell];
  return (kind == static_cast<int>(CellType::hexahedron) && face_size == 4) ||
         (kind == static_cast<int>(CellType::prism) && face_size == 3);
}

const CellDescriptor& cell_descriptor(const DualMesh& dual, std::size_t cell) {
  return descriptor(static_cast<CellType>(dual.cell_kind[cell]));
}

bool cell_has(const DualMesh& dual, std::size_t cell, Index node) {
  const Index* nodes = dual.nodes(cell);
  return std::find(nodes, nodes + dual.cell_size(cell), node) != nodes + dual.cell_size(cell);
}

// The cell other than `cell` that has every node of `face`; -1 for a boundary face.
Index other_cell(const DualMesh& dual, const Face& face, std::size_t cell) {
  const std::size_t first = static_cast<std::size_t>(face.nodes[0]);
  for (std::size_t slot = dual.point_cell_offsets[first]; slot < dual.point_cell_offsets[first + 1]; ++slot) {
    const std::size_t candidate = static_cast<std::size_t>(dual.point_cells[slot]);
    if (candidate == cell) continue;
    bool all = true;
    for (int local = 1; local < face.count && all; ++local)
      all = cell_has(dual, candidate, face.nodes[local]);
    if (all) return static_cast<Index>(candidate);
  }
  return -1;
}

Face local_face_nodes(const DualMesh& dual, std::size_t cell, int local_face) {
  const LocalFace& entry = cell_descriptor(dual, cell).faces[static_cast<std::size_t>(local_face)];
  Face face;
  face.count = entry.node_count;
  for (int k = 0; k < entry.node_count; ++k) face.nodes[k] = dual.nodes(cell)[entry.nodes[k]];
  return face;
}

// The local face of `cell` with exactly the nodes of `face`; -1 when it has none.
int find_local_face(const DualMesh& dual, std::size_t cell, const Face& face) {
  const CellDescriptor& cell_type = cell_descriptor(dual, cell);
  for (int local = 0; local < cell_type.face_count; ++local) {
    const LocalFace& entry = cell_type.faces[static_cast<std::size_t>(local)];
    if (entry.node_count != face.count) continue;
    bool all = true;
    for (int k = 0; k < entry.node_count && all; ++k) all = face.has(dual.nodes(cell)[entry.nodes[k]]);
    if (all) return local;
  }
  return -1;
}

// Thickness of a layer cell across its entry face (centre to opposite centre), the
// opposite face and, per entry node, the node its line reaches on the opposite face.
struct Crossing {
  Face opposite;
  std::array<Index, 4> next{-1, -1, -1, -1};
};

Crossing cross_cell(const DualMesh& dual, std::size_t cell, const Face& entry) {
  const CellDescriptor& cell_type = cell_descriptor(dual, cell);
  const Index* nodes = dual.nodes(cell);
  Crossing crossing;
  for (int local = 0; local < cell_type.face_count; ++local) {
    const LocalFace& candidate = cell_type.faces[static_cast<std::size_t>(local)];
    if (candidate.node_count != entry.count) continue;
    bool shares = false;
    for (int k = 0; k < candidate.node_count && !shares; ++k) shares = entry.has(nodes[candidate.nodes[k]]);
    if (shares) continue;
    crossing.opposite.count = candidate.node_count;
    for (int k = 0; k < candidate.node_count; ++k) crossing.opposite.nodes[k] = nodes[candidate.nodes[k]];
  }
  for (int k = 0; k < entry.count; ++k)
    for (int edge = 0; edge < cell_type.edge_count; ++edge) {
      const Index from = nodes[cell_type.edges[static_cast<std::size_t>(edge)][0]];
      const Index to = nodes[cell_type.edges[static_cast<std::size_t>(edge)][1]];
      if (from == entry.nodes[k] && !entry.has(to)) crossing.next[k] = to;
      if (to == entry.nodes[k] && !entry.has(from)) crossing.next[k] = from;
    }
  return crossing;
}

struct Step {
  Index node;
  Index down;
};

enum class ColumnEnd { inside, boundary };

// The apex of the cell across `entry` when that cell is a pyramid on it (a tetrahedron
// on a triangle): the bottom piece of an outer cell or stack the interface split about
// one point (docs/interface.md); -1 otherwise.
Index split_apex(const DualMesh& dual, std::size_t cell, const Face& entry) {
  if (dual.cell_size(cell) != entry.count + 1) return -1;
  Index apex = -1;
  const Index* nodes = dual.nodes(cell);
  for (int k = 0; k < dual.cell_size(cell); ++k)
    if (!entry.has(nodes[k])) {
      if (apex >= 0) return -1;
      apex = nodes[k];
    }
  return apex;
}

// Continues a column through a split stack. Its pieces keep the stack's side quads as
// pyramid bases, so each entry node's next node up is its neighbour along the side quad
// over its entry edge that leaves the entry face; the climb ends at the stack's top
// (the outer face, where no side quad rises further).
void climb_split_stack(const DualMesh& dual, Index apex, Face entry, std::vector<Step>& steps) {
  std::vector<std::array<Index, 4>> sides;
  const std::size_t apex_node = static_cast<std::size_t>(apex);
  for (std::size_t at = dual.point_cell_offsets[apex_node]; at < dual.point_cell_offsets[apex_node + 1];
       ++at) {
    const std::size_t piece = static_cast<std::size_t>(dual.point_cells[at]);
    if (dual.cell_size(piece) != 5 || dual.nodes(piece)[4] != apex) continue;
    const Index* base = dual.nodes(piece);
    sides.push_back({base[0], base[1], base[2], base[3]});
  }
  Face below;
  for (std::size_t level = 0; level <= sides.size(); ++level) {
    Face next;
    next.count = entry.count;
    for (int k = 0; k < entry.count; ++k) {
      const Index node = entry.nodes[k], along = entry.nodes[(k + 1) % entry.count];
      for (const auto& side : sides) {
        const auto has = [&](Index n) { return std::find(side.begin(), side.end(), n) != side.end(); };
        if (!has(node) || !has(along) ||
            std::all_of(entry.nodes.begin(), entry.nodes.begin() + entry.count, has))
          continue;
        if (std::any_of(below.nodes.begin(), below.nodes.begin() + below.count, has)) continue;
        const int position = static_cast<int>(std::find(side.begin(), side.end(), node) - side.begin());
        const Index before = side[static_cast<std::size_t>((position + 3) % 4)];
        next.nodes[k] = before == along ? side[static_cast<std::size_t>((position + 1) % 4)] : before;
        break;
      }
      if (next.nodes[k] < 0) return;
    }
    for (int k = 0; k < entry.count; ++k) steps.push_back({next.nodes[k], entry.nodes[k]});
    below = entry;
    entry = next;
  }
}

// Walks the column that enters `cell` through `entry`; `steps` gets each node's
// neighbour one layer down, `cells` the column's cells. `stamp` marks the cells of this
// walk (a column that comes back to a cell is not a stack).
ColumnEnd walk_column(const DualMesh& dual, std::size_t cell, Face entry, std::vector<Step>& steps,
                      std::vector<Index>& cells, std::vector<std::size_t>& stamp, std::size_t walk) {
  steps.clear();
  cells.clear();
  while (is_layer_cell(dual, cell, entry.count) && find_local_face(dual, cell, entry) >= 0) {
    if (stamp[cell] == walk) return ColumnEnd::boundary;
    stamp[cell] = walk;
    const Crossing crossing = cross_cell(dual, cell, entry);
    for (int k = 0; k < entry.count; ++k) steps.push_back({crossing.next[k], entry.nodes[k]});
    cells.push_back(static_cast<Index>(cell));
    const Index next = other_cell(dual, crossing.opposite, cell);
    if (next < 0) return ColumnEnd::boundary;
    cell = static_cast<std::size_t>(next);
    entry = crossing.opposite;
  }
  const Index apex = split_apex(dual, cell, entry);
  if (apex >= 0) climb_split_stack(dual, apex, entry, steps);
  return ColumnEnd::inside;
}

struct FaceKey {
  std::size_t operator()(const std::array<Index, 4>& key) const {
    std::size_t hash = 0;
    for (Index node : key) hash = hash * 1000003u ^ static_cast<std::size_t>(node + 1);
    return hash;
  }
};

std::array<Index, 4> sorted_key(const Face& face) {
  return sorted_face_key(face.nodes.data(), face.count);
}

// A sheet face with the layer cell on one side (the other is across it).
struct SheetFace {
  Face face;
  std::size_t cell;
};

// What the column walks share: the step down from every node they reached, the cells
// of the wall columns, the nodes on a wall, the surface star of every node, and the
// stamps that keep one walk from entering a cell twice.
struct ColumnWalks {
  const DualMesh& dual;
  const std::vector<MarkerRole>& marker_roles;
  std::vector<Index> down;
  std::vector<char> in_wall_column;
  std::vector<char> on_wall;
  std::vector<std::vector<Index>> star;
  std::vector<std::size_t> stamp;
  std::size_t walk = 0;
  std::vector<Step> steps;
  std::vector<Index> column_cells;

  ColumnWalks(const DualMesh& mesh, const std::vector<MarkerRole>& roles, std::size_t point_count)
      : dual(mesh),
        marker_roles(roles),
        down(point_count, -1),
        in_wall_column(mesh.cell_count(), 0),
        on_wall(point_count, 0),
        star(point_count),
        stamp(mesh.cell_count(), 0) {}

  bool is_wall(std::size_t face) const {
    const int marker = dual.face_marker[face];
    return marker >= 0 && static_cast<std::size_t>(marker) < marker_roles.size() &&
           marker_roles[static_cast<std::size_t>(marker)] != MarkerRole::sliding;
  }
  void add_star(const Face& face) {
    for (int k = 0; k < face.count; ++k)
      for (int other = 0; other < face.count; ++other)
        if (other != k) star[static_cast<std::size_t>(face.nodes[k])].push_back(face.nodes[other]);
  }
  ColumnEnd walk_from(std::size_t cell, const Face& entry) {
    return walk_column(dual, cell, entry, steps, column_cells, stamp, ++walk);
  }
  // The last walk's steps become the nodes' steps down; a node reached with another
  // step before is a conflict, and keeps its first.
  void commit(LayerLines& lines) {
    for (const Step& step : steps) {
      Index& entry = down[static_cast<std::size_t>(step.node)];
      if (entry < 0)
        entry = step.down;
      else if (entry != step.down)
        ++lines.conflicts;
    }
  }
};

// A column from every wall face into the layer cell on it.
void walk_wall_columns(ColumnWalks& walks, LayerLines& lines) {
  const DualMesh& dual = walks.dual;
  for (std::size_t face = 0; face < dual.face_count(); ++face) {
    if (!walks.is_wall(face)) continue;
    Face entry;
    entry.count = dual.face_size(face);
    for (int k = 0; k < entry.count; ++k) {
      entry.nodes[k] = dual.boundary_nodes(face)[k];
      walks.on_wall[static_cast<std::size_t>(entry.nodes[k])] = 1;
    }
    walks.add_star(entry);
    const std::size_t cell = static_cast<std::size_t>(dual.face_cell[face]);
    // (A column split as one stack down to the wall starts with the stack's pyramid.)
    if (!is_layer_cell(dual, cell, entry.count) && split_apex(dual, cell, entry) < 0) continue;
    const ColumnEnd end = walks.walk_from(cell, entry);
    // A column that reaches a boundary is a structured block's (a C- or O-grid): its
    // cells are no sheet's either. Left unmarked, every face of such a block next to a
    // wall edge seeded a sheet that grew over the whole block, and each of its faces
    // walked two more columns to the boundary (a 1 M-node O-grid: a minute).
    for (Index member : walks.column_cells) walks.in_wall_column[static_cast<std::size_t>(member)] = 1;
    if (end == ColumnEnd::boundary) {
      ++lines.columns_to_boundary;
      continue;
    }
    walks.commit(lines);
    ++lines.wall_columns;
  }
}

// Sheet faces: seeds leave a wall edge between two layer cells outside the wall
// columns; the sheet grows across the first layer of the cells beside it.
std::vector<SheetFace> grow_sheet(const ColumnWalks& walks) {
  const DualMesh& dual = walks.dual;
  auto sheet_candidate = [&](std::size_t cell, const Face& face) -> Index {
    if (walks.in_wall_column[cell] || !is_layer_cell(dual, cell, face.count)) return -1;
    const Index other = other_cell(dual, face, cell);
    if (other < 0 || walks.in_wall_column[static_cast<std::size_t>(other)] ||
        !is_layer_cell(dual, static_cast<std::size_t>(other), face.count))
      return -1;
    return other;
  };
  std::unordered_set<std::array<Index, 4>, FaceKey> known;
  std::vector<SheetFace> sheet;
  for (std::size_t cell = 0; cell < dual.cell_count(); ++cell) {
    if (walks.in_wall_column[cell]) continue;
    const CellDescriptor& cell_type = cell_descriptor(dual, cell);
    for (int local = 0; local < cell_type.face_count; ++local) {
      const Face face = local_face_nodes(dual, cell, local);
      bool wall_edge = false;
      for (int k = 0; k < face.count && !wall_edge; ++k)
        wall_edge = walks.on_wall[static_cast<std::size_t>(face.nodes[k])] &&
                    walks.on_wall[static_cast<std::size_t>(face.nodes[(k + 1) % face.count])];
      if (!wall_edge || sheet_candidate(cell, face) < 0) continue;
      if (known.insert(sorted_key(face)).second) sheet.push_back({face, cell});
    }
  }
  for (std::size_t next = 0; next < sheet.size(); ++next) {
    const SheetFace current = sheet[next];
    const Face& face = current.face;
    const std::size_t cell = current.cell;
    for (int k = 0; k < face.count; ++k) {
      const Index first = face.nodes[k];
      const Index second = face.nodes[(k + 1) % face.count];
      // The side face of the cell across this edge, the cell beyond it, and that cell's
      // face on the same edge: the sheet's next face.
      const CellDescriptor& cell_type = cell_descriptor(dual, cell);
      for (int local = 0; local < cell_type.face_count; ++local) {
        const Face side = local_face_nodes(dual, cell, local);
        if (!side.has(first) || !side.has(second) || sorted_key(side) == sorted_key(face)) continue;
        const Index beside = other_cell(dual, side, cell);
        if (beside < 0) continue;
        const std::size_t neighbour = static_cast<std::size_t>(beside);
        const CellDescriptor& neighbour_type = cell_descriptor(dual, neighbour);
        for (int other = 0; other < neighbour_type.face_count; ++other) {
          const Face candidate = local_face_nodes(dual, neighbour, other);
          if (!candidate.has(first) || !candidate.has(second) || sorted_key(candidate) == sorted_key(side))
            continue;
          if (sheet_candidate(neighbour, candidate) < 0) continue;
          if (known.insert(sorted_key(candidate)).second) sheet.push_back({candidate, neighbour});
        }
      }
    }
  }
  return sheet;
}

// Sheet columns, on both sides of every sheet face.
void walk_sheet_columns(ColumnWalks& walks, const std::vector<SheetFace>& sheet, LayerLines& lines) {
  for (const SheetFace& entry : sheet) {
    walks.add_star(entry.face);
    const Index across = other_cell(walks.dual, entry.face, entry.cell);
    for (const std::size_t cell : {entry.cell, static_cast<std::size_t>(across)}) {
      if (walks.walk_from(cell, entry.face) == ColumnEnd::boundary) {
        ++lines.columns_to_boundary;
        continue;
      }
      walks.commit(lines);
      ++lines.sheet_columns;
    }
  }
}

// Bases, arc lengths and tops down each line of steps; the line is named by its first node.
void measure_lines(const std::vector<Index>& down, const std::vector<Vector3>& points, LayerLines& lines) {
  const std::size_t point_count = points.size();
  std::vector<Index> line(point_count, -1);
  std::vector<char> done(point_count, 0);
  std::vector<Index> path;
  for (std::size_t node = 0; node < point_count; ++node) {
    if (down[node] < 0 || done[node]) continue;
    path.clear();
    Index at = static_cast<Index>(node);
    while (down[static_cast<std::size_t>(at)] >= 0 && !done[static_cast<std::size_t>(at)] &&
           path.size() <= point_count) {
      path.push_back(at);
      at = down[static_cast<std::size_t>(at)];
    }
    if (path.size() > point_count) continue;  // a cycle: not a line
    for (auto step = path.rbegin(); step != path.rend(); ++step) {
      const std::size_t current = static_cast<std::size_t>(*step);
      const std::size_t below = static_cast<std::size_t>(down[current]);
      const double length = (points[current] - points[below]).norm();
      if (done[below]) {
        lines.base[current] = lines.base[below];
        line[current] = line[below];
        lines.height[current] = lines.height[below] + length;
      } else {  // `below` is the surface node
        lines.base[current] = static_cast<Index>(below);
        line[current] = static_cast<Index>(current);
        lines.height[current] = length;
      }
      done[current] = 1;
    }
  }
  std::vector<Index> line_top(point_count, -1);
  for (std::size_t node = 0; node < point_count; ++node) {
    if (line[node] < 0) continue;
    Index& top = line_top[static_cast<std::size_t>(line[node])];
    if (top < 0 || lines.height[node] > lines.height[static_cast<std::size_t>(top)])
      top = static_cast<Index>(node);
  }
  for (std::size_t node = 0; node < point_count; ++node) {
    if (line[node] < 0) continue;
    lines.top[node] = line_top[static_cast<std::size_t>(line[node])];
    ++lines.line_nodes;
  }
}

// The surface stars, sorted and without repeats, packed into LayerLines::star_nodes.
void pack_stars(std::vector<std::vector<Index>>& star, LayerLines& lines) {
  for (std::size_t node = 0; node < star.size(); ++node) {
    std::vector<Index>& around = star[node];
    std::sort(around.begin(), around.end());
    around.erase(std::unique(around.begin(), around.end()), around.end());
    lines.star_offsets[node + 1] = lines.star_offsets[node] + around.size();
    lines.star_nodes.insert(lines.star_nodes.end(), around.begin(), around.end());
  }
}

}  // namespace

LayerLines find_layer_lines(const DualMesh& dual, const std::vector<MarkerRole>& marker_roles,
                            const std::vector<Vector3>& points) {
  LayerLines lines;
  const std::size_t point_count = points.size();
  lines.base.assign(point_count, -1);
  lines.top.assign(point_count, -1);
  lines.height.assign(point_count, 0.0);
  lines.star_offsets.assign(point_count + 1, 0);
  if (dual.planar) return lines;
  ColumnWalks walks(dual, marker_roles, point_count);
  walk_wall_columns(walks, lines);
  const std::vector<SheetFace> sheet = grow_sheet(walks);
  lines.sheet_faces = sheet.size();
  walk_sheet_columns(walks, sheet, lines);
  measure_lines(walks.down, points, lines);
  pack_stars(walks.star, lines);
  return lines;
}

}  // namespace mixmesh::deform::detail
