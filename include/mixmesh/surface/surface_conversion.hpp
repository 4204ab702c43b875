// SurfaceMesh -> MixedMesh with boundary faces only, for writing and checking a
// surface with the mesh tools.
//
// Structured patch faces become quads (i, j), (i+1, j), (i+1, j+1), (i, j+1), whose
// right-hand normal is the patch's normal; triangle patches keep their triangles.
// Each face's marker is its patch name; a patch with leading_edge_i >= 0 is split into
// <name>_lower (i < leading_edge_i) and <name>_upper. Points are shared as in the
// SurfaceMesh (same indices).
#pragma once

#include "mixmesh/mesh/mixed_mesh.hpp"
#include "mixmesh/surface/surface_mesh.hpp"

namespace mixmesh {

MixedMesh to_mixed_mesh(const SurfaceMesh& surface);

}  // namespace mixmesh
