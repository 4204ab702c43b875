// Quality figures on a dual mesh and wall lines built once: a deformation step measures
// the mesh before and after on the same topology. Internal to the deform module.
#pragma once

#include "deform/dual_mesh.hpp"
#include "mixmesh/deform/deform.hpp"

namespace mixmesh::deform::detail {

WallLines wall_lines(const MixedMesh& mesh, const DualMesh& dual,
                     const std::vector<MarkerRole>& marker_roles);

// `dual` may come from another mesh with the same cells (the undeformed one); `angles`
// are wall_angles(mesh, lines) of this mesh; `invalid` (per cell, when known) saves
// checking each cell's validity again.
QualitySummary summarise_quality(const MixedMesh& mesh, const DualMesh& dual,
                                 const std::vector<double>& angles,
                                 const std::vector<char>* invalid = nullptr);

}  // namespace mixmesh::deform::detail
