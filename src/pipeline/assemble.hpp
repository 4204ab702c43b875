// Pieces of the generate pipeline that join the stages: which cells face the far
// field, and the one mesh made of the layers and the far-field tetrahedra.
#pragma once

#include <string>
#include <vector>

#include "mixmesh/farfield/farfield.hpp"
#include "mixmesh/interface/interface_split.hpp"

namespace mixmesh::pipeline_detail {

// Cells of the layer mesh with a boundary face tagged by one of `markers` (the top of
// each column and the sides left open at free edges or stopped columns), and which
// face it is. A cell with several such faces is listed once per face.
OuterLayer outer_layer(const MixedMesh& layers, const std::vector<std::string>& markers);

// The layers (after the interface split) plus the far-field tetrahedra and their
// boundary faces; the hull faces become interior and lose their tag. With
// merge_wall_markers the markers of `wall_markers` become one "wall".
MixedMesh assemble(const MixedMesh& layers, const std::string& hull_marker, const FarFieldResult& farfield,
                   const std::vector<std::string>& wall_markers, bool merge_wall_markers);

}  // namespace mixmesh::pipeline_detail
