// Figures of merit of a marched boundary layer, the ones users judge a marching
// method by: cell validity and shape, orthogonality of the first grid line, growth
// of the spacing along the lines, smoothness of the lines.
#pragma once

#include <string>

#include "mixmesh/march/march_layers.hpp"

namespace mixmesh {

struct MarchMetrics {
  int invalid_cells = 0;  // over all cells
  // Smallest corner Jacobian / edge lengths over the hexahedra and prisms (the swept
  // cells of the columns, which both methods build the same way).
  double minimum_scaled_jacobian = 0.0;
  // The same over the pyramids that cut the stack of a split face at a junction
  // (march_layers.hpp); 1 when there are none.
  double junction_minimum_scaled_jacobian = 1.0;
  // Angle between the first segment of a marching line and the wall normal (the
  // angle-weighted normal of the wall faces around the node), over the lines of the
  // measured patch.
  double maximum_normal_deviation_degrees = 0.0;
  double percentile99_normal_deviation_degrees = 0.0;
  double fraction_within_2_degrees = 0.0;
  // Largest change of the ratio of successive segment lengths along one line (of a
  // full line, below its outermost segment: that one is MarchOptions::outer_layer_height).
  double maximum_growth_jump = 0.0;
  // Angle between successive segments of a line.
  double maximum_line_turn_degrees = 0.0;
  double percentile99_line_turn_degrees = 0.0;
  int lines = 0;
};

// Measures `layer` marched from `surface`; the line figures cover the lines that
// start on a face of the patch named `patch` (every wall patch when empty). Throws
// mixmesh::Error when no line starts on such a patch.
MarchMetrics measure_march(const BoundaryLayer& layer, const SurfaceMesh& surface,
                           const std::string& patch = "");

}  // namespace mixmesh
