// Layer lines: the grid lines of the stacked layers of hexahedra and prisms that grow
// from a wall or from both sides of an interior sheet (a wake), found from the mesh's
// topology alone, and the transport that moves every stack with its base.
//
// Why: a layer is as thin as the wall spacing (1.5 µm at the ONERA M6's trailing edge,
// 1.8 cm under 0.86 m long cells at its wake's end), while both methods move nodes by
// fields that are smooth on the scale of the cells around them (ARA interpolates the
// rigid motions of cells up to a metre across; IDW averages the motion of the nearest
// boundary nodes, a set that changes from node to node). Two nodes a layer apart then
// differ in their motion by more than the layer is thick, and the cell folds. Moving the
// nodes of a line rigidly with the surface at its base removes the shear across the
// layers. A wall's line moves rigidly to its top, and the difference between the method
// and that motion at the top is carried to the nodes outside the layers, fading one wall
// face size above and beside them (layer_lines.cpp, carry_top_offsets): the method is
// wrong on the scale of the wall's faces, which the cells there match. A sheet's line
// keeps the method's position at its top (its base moves by the method too), and the
// difference is spread along the line by arc length.
//
// A stack is a column of hexahedra (entered through a quad) and prisms (through a
// triangle), each cell left through the face opposite the one it was entered by. Columns
// start at wall faces (fixed or moving markers) and at sheet faces; a column that
// reaches a boundary face is a structured block, not a layer stack, and is left to the
// method. The sheet grows from the faces that leave a wall edge between two layer cells
// that no wall column holds (the wake's first faces at the trailing edge), face to face
// across the first layer of the cells beside it.
#pragma once

#include <cstddef>
#include <vector>

#include "deform/dual_mesh.hpp"
#include "mixmesh/deform/deform.hpp"

namespace mixmesh::deform::detail {

struct LayerLines {
  // Per point: the surface node its line starts from (-1: not on a line, or a surface
  // node), the line's outermost node, and the arc length from the base (undeformed).
  std::vector<Index> base;
  std::vector<Index> top;
  std::vector<double> height;
  // Base surfaces (wall and sheet faces a column starts from), CSR per point: the other
  // nodes of those faces, to fit the rotation of the surface at a base node.
  std::vector<std::size_t> star_offsets;
  std::vector<Index> star_nodes;

  std::size_t wall_columns = 0;
  std::size_t sheet_faces = 0;
  std::size_t sheet_columns = 0;
  std::size_t columns_to_boundary = 0;  // left to the method
  std::size_t line_nodes = 0;
  std::size_t conflicts = 0;  // nodes two columns gave different bases (the first kept)
};

LayerLines find_layer_lines(const DualMesh& dual, const std::vector<MarkerRole>& marker_roles,
                            const std::vector<Vector3>& points);

// Moves every line node of `moved` (positions after the method, boundary nodes already
// where the motion puts them) with its base: x′ = b′ + R (x − b) on a wall's line, with
// the method's offset at the top carried to the nodes outside the layers; on a sheet's
// line x′ = b′ + R (x − b) + s (t′ − (b′ + R (t − b))), t the line's top, s = height /
// height of t. R is the rotation fitted to the base's star. Prescribed nodes are left alone.
void transport_layer_lines(const LayerLines& lines, const BoundaryMotion& boundary,
                           const std::vector<Vector3>& original, std::vector<Vector3>& moved);

}  // namespace mixmesh::deform::detail
