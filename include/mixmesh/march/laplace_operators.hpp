// The corrector of one marching step: where the face-weighted Laplace equation puts
// a node of the new layer, given its neighbours in that layer and its predicted
// position on its marching line. Both return the weighted average that solves the
// discrete equation for the centre node with every other point held.
#pragma once

#include <array>
#include <vector>

#include "mixmesh/mesh/mixed_mesh.hpp"

namespace mixmesh {

// Neighbours of a structured node (i, j) in the new layer.
// Every member starts at zero: Eigen leaves a default-constructed vector unset.
struct StructuredStencil {
  Vector3 east = Vector3::Zero(), west = Vector3::Zero();    // (i+1, j), (i-1, j)
  Vector3 north = Vector3::Zero(), south = Vector3::Zero();  // (i, j+1), (i, j-1)
  Vector3 north_east = Vector3::Zero(), north_west = Vector3::Zero();
  Vector3 south_east = Vector3::Zero(), south_west = Vector3::Zero();
};

// Wild eq. (1), parabolised in the marching direction zeta: face-vector weights
// s_k.s_k on the second differences, 2 s1.s2 on the in-layer cross derivative, the
// marching second difference against `target` (the position on the marching line that
// the step h of the layer gives). `below` is the node on the previous layer.
// The zeta cross terms s2.s3, s3.s1 vanish for lines orthogonal to the layer, which
// the control functions enforce near the wall; they are not carried.
Vector3 structured_laplace_update(const StructuredStencil& layer, const Vector3& target,
                                  const Vector3& below);

// The discrete equation of either operator with its weights frozen at the given
// positions, a linear equation for the centre:
//   denominator * centre = sum_k neighbour[k] * point_k + target_weight * target.
// The structured neighbours are in StructuredStencil order (east, west, north, south,
// north-east, north-west, south-east, south-west); the ring neighbours in ring order.
// A degenerate stencil gives centre = target (no neighbour weight, denominator 1).
struct LaplaceWeights {
  std::vector<double> neighbour;
  double target_weight = 1.0;
  double denominator = 1.0;
};
LaplaceWeights structured_laplace_weights(const StructuredStencil& layer, const Vector3& target,
                                          const Vector3& below);
LaplaceWeights prism_laplace_weights(const std::vector<Vector3>& ring, const Vector3& centre,
                                     const Vector3& target, const Vector3& below);

// Wild eq. (3)-(7) for a prism column: `ring` holds the N >= 3 neighbours of the
// centre in the new layer, counter-clockwise about the marching direction; `centre`
// the current estimate of the centre, `below` the centre on the previous layer.
// Reconstructed details (the printed equations are garbled, see docs/march.md):
// the averages of eq. (5) are centred on edge n (cos 2 pi (i - n) / N), and the
// marching weight uses Q = q / cos^2(pi / N), which makes the operator the same
// discrete Laplacian as the structured one on a regular ring.
Vector3 prism_laplace_update(const std::vector<Vector3>& ring, const Vector3& centre, const Vector3& target,
                             const Vector3& below);

}  // namespace mixmesh
