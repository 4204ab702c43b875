// Untangling after the layer transport: the last stage of every step, for every method.
//
// Why: the methods repair their own inverted cells (ARA's eq. 27), but the layer
// transport (layer_lines.hpp) runs after them and moves the line nodes while the nodes
// beside the stacks keep the method's positions: the centres of the interface's split
// cells, the nodes of split columns at the wake's root and end. Where the method's
// field has a kink the transport spreads it down a line (ARA's velocity smoothing
// stops at its tolerance with the predictor's kinks left near the symmetry plane: on
// the ONERA M6 wake's end, nodes 2 cm from the plane lifted 5 cm less than those 5 cm
// from it), and cells that mix both kinds of node fold.
//
// The repair moves the free nodes of the inverted cells, and rings of nodes round them
// when that is not enough, to the position the least-squares affine map of their
// neighbours' motion gives them (an affine motion, rotations included, is kept exactly,
// so a node inside a rigidly turned region does not move). A region's move is kept only
// when fewer of the cells it touches are inverted afterwards; nodes the motion prescribes
// never move, sliding nodes stay in their plane.
//
// An affine map of the neighbours is not enough where the neighbours' motion is not
// affine over the cell: the flat cells above and below the ONERA M6's wake, 0.2–0.9 m
// long and a fraction of a millimetre thick. The cells still inverted then go to a local
// optimisation (untangle_optimise.cpp): the free nodes of the inverted cells, and up to
// two rings round them, move one at a time down the gradient of Knupp's untangling
// function of their cells (P. M. Knupp, Hexahedral and tetrahedral mesh untangling,
// Engineering with Computers 17, 2001), a node keeping its move only when no more of
// its cells are inverted.
#pragma once

#include <cstddef>
#include <vector>

#include "deform/dual_mesh.hpp"
#include "mixmesh/deform/deform.hpp"

namespace mixmesh::deform::detail {

struct UntangleReport {
  std::size_t inverted_before = 0;
  std::size_t inverted_after = 0;
  int rounds = 0;
  std::size_t optimise_before = 0;  // inverted cells handed to the optimisation
  std::size_t moved_nodes = 0;
  std::vector<char> invalid;  // per cell of the dual mesh, after (exact: every change rechecked)
};

// The nodes joined to `node` by an edge of one of its cells, sorted.
void edge_neighbours(const DualMesh& dual, std::size_t node, std::vector<Index>& out);

// The nodes of the cells flagged in `invalid` and `rings` rings of edge neighbours round
// them, each once.
std::vector<Index> inverted_region(const DualMesh& dual, const std::vector<char>& invalid, int rings);

// The optimisation stage: `invalid` flags the inverted cells and is kept up to date;
// nodes that move are flagged in `ever_moved`. Returns the inverted cells left.
std::size_t optimise_inverted(const DualMesh& dual, const BoundaryMotion& boundary,
                              const std::vector<Vector3>& original, std::vector<Vector3>& moved,
                              std::vector<char>& invalid, std::vector<char>& ever_moved);

UntangleReport untangle(const DualMesh& dual, const BoundaryMotion& boundary,
                        const std::vector<Vector3>& original, std::vector<Vector3>& moved);

}  // namespace mixmesh::deform::detail
