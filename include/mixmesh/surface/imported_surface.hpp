// Surface patches from files, combined into one SurfaceMesh.
//
//   Plot3D   multi-block surface grid, ASCII, whole (x, y, z): a block count line,
//            "ni nj 1" (or "ni nj") per block, then per block all x, all y, all z with
//            i fastest. Each block becomes a structured patch <name>_<block number>.
//   STL, OBJ, OFF  triangles (polygons are fanned into triangles) read by OpenMesh,
//            one triangle patch <name>.
//
// Seams: nodes of all patches closer than the tolerance are merged into one point (the
// first one read), so patches that meet share nodes as the SurfaceMesh contract asks.
// A face whose nodes merge into fewer than its corners is an error naming the patch.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "mixmesh/surface/surface_mesh.hpp"

namespace mixmesh {

struct SurfaceImport {
  std::filesystem::path file;  // .p3d/.xyz/.g (Plot3D) or .stl/.obj/.off
  std::string name;            // patch name (marker); default: the file stem
  PatchRole role = PatchRole::wall;
  bool flip = false;  // reverse the orientation (normals must point into the flow)
};

struct ImportOptions {
  double merge_tolerance = 1e-8;  // absolute distance below which nodes are one node
  double symmetry_y = 0.0;
  double symmetry_tolerance = -1.0;  // copied to the SurfaceMesh; negative: no symmetry plane
};

// Reads every file and combines the patches; errors name file:line (Plot3D) or the file.
SurfaceMesh import_surfaces(const std::vector<SurfaceImport>& imports, const ImportOptions& options);

// The single readers, before merging (each patch has its own points).
SurfaceMesh read_plot3d_surface(const std::filesystem::path& path, const std::string& name);
SurfaceMesh read_triangle_surface(const std::filesystem::path& path, const std::string& name);

// Appends `part` to `whole` (points and patches, indices shifted).
void append_surface(SurfaceMesh& whole, const SurfaceMesh& part);

// Merges nodes closer than `tolerance` (grid hashing), renumbers every patch and drops
// unused points. Throws mixmesh::Error if a face collapses.
void merge_coincident_nodes(SurfaceMesh& surface, double tolerance);

}  // namespace mixmesh
