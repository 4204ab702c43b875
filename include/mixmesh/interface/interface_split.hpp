// Interface layer (Wild §II.C, Fig. 2): the outermost structured layer becomes a
// triangulated hull for the far-field tetrahedralisation.
//
// Every listed hexahedron is split about its centre point (the mean of its nodes)
// into pyramids, one per face with the apex at the centre, and the pyramid on each
// outer face is split into two tetrahedra along one diagonal of the outer quad. Side
// and inner faces keep their quads (the pyramid bases are those quads), so
// neighbouring hexahedra, prisms and split hexahedra stay conforming. A cell may have
// several outer faces (the top and an exposed side of a column standing above a
// neighbour whose growth stopped earlier): list it once per outer face. A prism whose
// outer faces are its triangles passes through; a prism with an outer quad is split
// the same way (tetrahedra on its triangles and outer quads, pyramids on the rest).
//
//   input   MixedMesh (the boundary layers) + OuterLayer (which cells, which face is outer)
//   output  the same mesh with the hexahedra replaced (#centres points appended after
//           the input points, regions inherited), and the hull: triangles oriented
//           with their right-hand normal pointing away from the layers (into the far field)
//
// Boundary faces: tagged faces on a split hexahedron's side faces stay as they are (the
// split keeps those quads). A tagged face on an outer face is replaced by the hull
// triangles, which carry the marker `hull_marker`; every other tag is kept.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "mixmesh/core/error.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/mesh/mixed_mesh.hpp"

namespace mixmesh {

// One cell of the outermost layer and which of its faces (local face number in the
// cell's descriptor, e.g. 1 = the top 4-5-6-7 of a hexahedron, 1 = the top 3-5-4 of a
// prism) faces the far field.
struct OuterCell {
  std::size_t cell = 0;  // index in the mesh's block of that cell type
  int outer_face = 1;
};

struct OuterLayer {
  std::vector<OuterCell> hexahedra;
  std::vector<OuterCell> prisms;
};

// How each outer quad is cut into two hull triangles. The two triangles of a quad
// belong to one hexahedron, so any choice conforms; the rule only has to be
// deterministic (same mesh → same hull).
enum class HullDiagonal {
  shorter,        // the shorter diagonal (better triangles); ties go to smallest_node
  smallest_node,  // the diagonal through the quad's smallest global node index
};

struct InterfaceOptions {
  HullDiagonal diagonal = HullDiagonal::shorter;
  std::string hull_marker = "interface";
  // Cells are split about their centre (the mean of their nodes) unless the worst
  // piece's scaled corner Jacobian would fall below this; then the split point is the
  // best one a compass search around the centre finds. 0: only where a piece about the
  // centre is inverted. (At 0.1 every flat outer cell was searched, as its pieces are
  // all flatter than that, and the point moved along the cell's long side, off the
  // middle of the outer quad's diagonal: its two tetrahedra on the outer quad became
  // slivers the sliver pass could not mend; on a random 7.7 m-chord wing 2,088
  // tetrahedra above 175 deg against 1,582.)
  double centre_quality = 0.0;
  // Cells with an outer quad tagged with this marker are kept whole and capped, as
  // below, instead of being split about a centre point (even with
  // cap_unsplittable_cells false). The march tags the hull faces of a sheet's layers (a
  // wake's) with it: the tops of its columns and the sides along free edges, also the
  // free-edge sides of a wall surface (a plate's edge). A wake's cells are as long as its
  // streamwise cells (0.86 m at the end of the ONERA M6 wake) and the split point would
  // sit half a layer from faces that long, so any motion of the mesh that is not affine
  // over that length (a deformation) folds the pieces; a cap spans its own quad only,
  // its apex marked_cap_height times the quad's shortest edge out. Hexahedra with a node
  // on another outer face (where the marked hull meets the rest: a wake's trailing edge,
  // the tip trailing edge) are split as usual. Empty: every cell with an outer quad is
  // split. (mixmesh::generate passes the march's hull_side_marker.)
  std::string capped_marker = "hull_side";
  // The layers' faces on the symmetry plane carry this marker. A capped cell whose outer
  // quad has an edge on the plane leans its cap on it: the apex stands in the plane over
  // that edge, and the cap's face there takes this marker (docs/interface.md, *Caps
  // near the symmetry plane*). Empty, or no such face: such cells are split.
  std::string symmetry_marker = "symmetry";
  // Cap height of those cells, times the quad's shortest edge (a wake's quads are long
  // and narrow: a higher apex keeps the cap from being flat along the quad); > 0.
  double marked_cap_height = 0.5;
  // A cell whose split would still give an inverted piece (a thin cell with a warped
  // face, e.g. deep in the layers beside a free edge) is kept whole and each of its
  // outer quads gets a pyramid outside it, apex above the quad's centre at cap_height
  // times the quad's shortest edge; false: such a cell is an error.
  bool cap_unsplittable_cells = true;
  double cap_height = 0.25;  // > 0
  // A cap on a twisted quad that is inverted at cap_height is raised (doubling) up to
  // this multiple of the quad's longest diagonal.
  double cap_height_limit = 0.5;
  // An outer hexahedron whose split leaves a tetrahedron with a dihedral angle above
  // stack_dihedral degrees (a cell much thinner than wide) is split together with up to
  // stack_cells - 1 hexahedra under it, as one stack about its middle (see
  // docs/interface.md); stack_cells 1 splits the outermost cells alone.
  double stack_dihedral = 160.0;
  // ... or whose split leaves a pyramid with a scaled corner Jacobian below
  // stack_pyramid_quality (the pyramid on the inner quad of a cell much thinner than long,
  // as where a blunt base meets a wake: thin stacks under spanwise cells up to metres
  // long); twice the robustness suite's floor of 1e-3.
  double stack_pyramid_quality = 2e-3;
  int stack_cells = 16;
  // A cell or stack whose best split point still leaves a pyramid below this scaled
  // corner Jacobian (a layer cell twisted nearly flat at a tip's trailing edge, a stack
  // sheared along the span at a blunt base's end there) keeps its cells whole and its
  // outer quads are capped as an unsplittable cell's, where those caps' pyramids are
  // better and no such cap stands next to it (the valley between two low caps over a
  // long shared edge is flat). The robustness suite's floor, 1e-3 in Verdict's units.
  double split_pyramid_floor = 1e-3 / verdict_corner_factor;
};

// An outer cell that can neither be split about its centre nor capped (a layer cell
// twisted more than it is thick): where, so that the pipeline can lower the layers there.
class UnsplittableCellError : public Error {
 public:
  UnsplittableCellError(const std::string& message, const Vector3& where) : Error(message), location(where) {}
  Vector3 location;
};

struct InterfaceResult {
  MixedMesh mesh;
  std::vector<std::array<Index, 3>> hull;  // outward triangles, node indices into mesh.points
  std::vector<Index> centres;              // the centre point of each split cell, in input order
  std::size_t pyramids = 0;
  std::size_t tetrahedra = 0;
  std::size_t capped_cells = 0;  // kept whole with pyramids outside (see InterfaceOptions)
  std::size_t lowered_caps = 0;  // marked caps brought down: clear of the hull, or level with a neighbour
  std::size_t stacks = 0;        // outer hexahedra split with cells under them
  std::size_t stacked_cells = 0;  // the hexahedra those stacks hold
};

// Throws mixmesh::Error for a cell index out of range, an outer face number out of
// range, the same face listed twice, an outer face shared with another cell, or a
// split that would give an inverted piece (naming the cell, the face and a location).
InterfaceResult split_interface(const MixedMesh& mesh, const OuterLayer& layer,
                                const InterfaceOptions& options = {});

}  // namespace mixmesh
