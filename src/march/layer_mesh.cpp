#include "layer_mesh.hpp"

#include <algorithm>
#include <cmath>

#include "junction.hpp"

namespace mixmesh::march_detail {

namespace {

Index column_point(const BoundaryLayer& result, int column, int layer) {
  return result.column_points[static_cast<std::size_t>(column)][static_cast<std::size_t>(layer)];
}

// The side face over front edge corner -> corner + 1 of `face` in cell layer
// `layer`, outward from that cell: (u_k, v_k, v_k+1, u_k+1).
std::array<Index, 4> side_face(const Front& front, const BoundaryLayer& result, int face, int corner,
                               int layer) {
  const FrontFace& f = front.faces[static_cast<std::size_t>(face)];
  const int u = f.columns[static_cast<std::size_t>(corner)];
  const int v = f.columns[static_cast<std::size_t>((corner + 1) % f.corner_count)];
  return {column_point(result, u, layer), column_point(result, v, layer), column_point(result, v, layer + 1),
          column_point(result, u, layer + 1)};
}

// Adds a side face; one whose first two (or last two) nodes coincide, where the two
// lines of a split or wrap face start at one point, is the triangle of the others.
void add_side_face(MixedMesh& mesh, const std::array<Index, 4>& nodes, int marker) {
  if (nodes[0] == nodes[1] || nodes[2] == nodes[3]) {
    const std::array<Index, 3> triangle = nodes[0] == nodes[1]
                                              ? std::array<Index, 3>{nodes[0], nodes[2], nodes[3]}
                                              : std::array<Index, 3>{nodes[0], nodes[1], nodes[2]};
    mesh.add_face(FaceType::triangle, triangle.data(), marker);
    return;
  }
  mesh.add_face(FaceType::quad, nodes.data(), marker);
}

}  // namespace

void add_swept_cell(const Front& front, int face, int layer, BoundaryLayer& result) {
  const FrontFace& f = front.faces[static_cast<std::size_t>(face)];
  if (f.split && layer == 0) return;  // add_junction_stacks cuts it with the cells above
  auto at = [&](int k, int level) {
    return column_point(result, f.columns[static_cast<std::size_t>(k)], level);
  };
  if (f.wrap && at(0, layer) == at(3, layer)) {
    // The first cell of a wrap face (above b, above a, below a, below b): a prism between
    // its triangles at b and at a, the one at b first (VTK: turned away from the other).
    const std::array<Index, 6> nodes{at(0, layer), at(0, layer + 1), at(3, layer + 1),
                                     at(1, layer), at(1, layer + 1), at(2, layer + 1)};
    result.mesh.add_cell(CellType::prism, nodes.data(), f.patch);
    result.prism_face.push_back(face);
    result.prism_layer.push_back(layer);
    return;
  }
  if (f.corner_count == 4) {
    const std::array<Index, 8> nodes{at(0, layer),     at(1, layer),     at(2, layer),     at(3, layer),
                                     at(0, layer + 1), at(1, layer + 1), at(2, layer + 1), at(3, layer + 1)};
    result.mesh.add_cell(CellType::hexahedron, nodes.data(), f.patch);
    result.hexahedron_face.push_back(face);
    result.hexahedron_layer.push_back(layer);
    return;
  }
  // VTK wedge: bottom (a, c, b) so that its right-hand normal points away from the top.
  const std::array<Index, 6> nodes{at(0, layer),     at(2, layer),     at(1, layer),
                                   at(0, layer + 1), at(2, layer + 1), at(1, layer + 1)};
  result.mesh.add_cell(CellType::prism, nodes.data(), f.patch);
  result.prism_face.push_back(face);
  result.prism_layer.push_back(layer);
}

void add_junction_stacks(const Front& front, BoundaryLayer& result) {
  for (const Junction& junction : front.junctions) {
    const FrontFace& f = front.faces[static_cast<std::size_t>(junction.face)];
    const int grown = result.face_layers[static_cast<std::size_t>(junction.face)];
    if (grown == 0) continue;
    auto level = [&](int layer) {
      std::array<Vector3, 4> corners;
      for (std::size_t c = 0; c < 4; ++c)
        corners[c] = result.mesh.points[static_cast<std::size_t>(column_point(result, f.columns[c], layer))];
      return corners;
    };
    // The lowest stack whose worst piece is good (a tetrahedron's largest dihedral
    // angle at most 160 degrees, the sliver pass's default target; a pyramid's corners
    // as square), else the best one. The quality grows with the stack's height until it
    // is about as high as wide, so a taller stack only trades hexahedra for pyramids.
    // The top stays below the face's outermost cell, which the interface splits as
    // every other outermost hexahedron.
    const double good = std::sin(20.0 * std::acos(-1.0) / 180.0);
    JunctionLevels levels{level(0), level(1)};
    JunctionCells best = junction_cells(levels);
    for (int layers = 2; layers < grown && best.quality < good; ++layers) {
      levels.push_back(level(layers));
      JunctionCells cells = junction_cells(levels);
      if (cells.quality > best.quality) best = std::move(cells);
    }
    const int layers = best.layers();

    // The hexahedra of the stack (layers 1 … layers - 1) leave the mesh.
    CellBlock& hexahedra = result.mesh.block(CellType::hexahedron);
    std::size_t kept = 0;
    for (std::size_t cell = 0; cell < result.hexahedron_face.size(); ++cell) {
      if (result.hexahedron_face[cell] == junction.face && result.hexahedron_layer[cell] < layers) continue;
      std::copy_n(hexahedra.nodes.begin() + static_cast<std::ptrdiff_t>(8 * cell), 8,
                  hexahedra.nodes.begin() + static_cast<std::ptrdiff_t>(8 * kept));
      hexahedra.regions[kept] = hexahedra.regions[cell];
      result.hexahedron_face[kept] = result.hexahedron_face[cell];
      result.hexahedron_layer[kept] = result.hexahedron_layer[cell];
      ++kept;
    }
    hexahedra.nodes.resize(8 * kept);
    hexahedra.regions.resize(kept);
    result.hexahedron_face.resize(kept);
    result.hexahedron_layer.resize(kept);

    std::vector<Index> global;
    for (int layer = 0; layer <= layers; ++layer)
      for (int c = 0; c < 4; ++c)
        global.push_back(column_point(result, f.columns[static_cast<std::size_t>(c)], layer));
    global.push_back(static_cast<Index>(result.mesh.points.size()));
    result.mesh.points.push_back(best.points[static_cast<std::size_t>(best.centre_point())]);
    for (const JunctionCell& cell : best.cells) {
      std::vector<Index> nodes;
      for (int local : cell.nodes) nodes.push_back(global[static_cast<std::size_t>(local)]);
      result.mesh.add_cell(cell.type, nodes.data(), f.patch);
      (cell.type == CellType::pyramid ? result.pyramid_face : result.tetrahedron_face)
          .push_back(junction.face);
    }
  }
}

void add_boundary_faces(const Front& front, const MarchOptions& options, BoundaryLayer& result) {
  MixedMesh& mesh = result.mesh;
  const int hull = mesh.marker(options.outer_hull_marker);
  for (std::size_t face = 0; face < front.faces.size(); ++face) {
    const FrontFace& f = front.faces[face];
    const int layers = result.face_layers[face];
    if (layers == 0) continue;
    std::array<Index, 4> bottom{}, top{};
    for (int k = 0; k < f.corner_count; ++k) {
      // Outward from the cell: the wall face runs against the front's winding.
      bottom[static_cast<std::size_t>(k)] =
          column_point(result, f.columns[static_cast<std::size_t>(f.corner_count - 1 - k)], 0);
      top[static_cast<std::size_t>(k)] = column_point(result, f.columns[static_cast<std::size_t>(k)], layers);
    }
    const FaceType type = f.corner_count == 4 ? FaceType::quad : FaceType::triangle;
    if (f.wall) {
      // A split face's wall is its triangle: the bottom lists corner 0's wall point
      // last, after corner 3's, which is the same point.
      mesh.add_face(f.split ? FaceType::triangle : type, bottom.data(),
                    mesh.marker(front.patch_names[static_cast<std::size_t>(f.patch)]));
    }
    // The tops of a sheet's columns are hull_side faces, as its free-edge sides: the
    // interface caps their cells rather than splitting them (InterfaceOptions::
    // capped_marker), since a sheet's cells are as long as its streamwise cells.
    mesh.add_face(type, top.data(), f.wall ? hull : mesh.marker(options.hull_side_marker));
  }
  // Sides along free edges of the front.
  for (const FreeEdge& edge : front.free_edges) {
    const FrontFace& f = front.faces[static_cast<std::size_t>(edge.face)];
    const int u = f.columns[static_cast<std::size_t>(edge.corner)];
    const int v = f.columns[static_cast<std::size_t>((edge.corner + 1) % f.corner_count)];
    const bool symmetry =
        front.on_symmetry[static_cast<std::size_t>(u)] && front.on_symmetry[static_cast<std::size_t>(v)];
    const int marker = mesh.marker(symmetry ? options.symmetry_marker : options.hull_side_marker);
    for (int layer = 0; layer < result.face_layers[static_cast<std::size_t>(edge.face)]; ++layer)
      add_side_face(mesh, side_face(front, result, edge.face, edge.corner, layer), marker);
  }
  // Sides of a column standing above its stopped neighbour belong to the hull.
  for (const SharedEdge& edge : front.shared_edges) {
    const int first = result.face_layers[static_cast<std::size_t>(edge.faces[0])];
    const int second = result.face_layers[static_cast<std::size_t>(edge.faces[1])];
    if (first == second) continue;
    const int taller = first > second ? 0 : 1;
    for (int layer = std::min(first, second); layer < std::max(first, second); ++layer) {
      add_side_face(mesh,
                    side_face(front, result, edge.faces[static_cast<std::size_t>(taller)],
                              edge.corners[static_cast<std::size_t>(taller)], layer),
                    hull);
    }
  }
}

}  // namespace mixmesh::march_detail
