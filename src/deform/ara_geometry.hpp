// What the ARA method computes from the undeformed mesh alone (dual mesh, wall faces,
// smoothing matrix, interpolation weights), and its place in the cache file, so that a
// later run on the same mesh skips it. Internal to the deform module.
#pragma once

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "deform/ara_smoothing.hpp"
#include "deform/dual_mesh.hpp"
#include "deform/wall_faces.hpp"
#include "mixmesh/deform/ara.hpp"

namespace mixmesh::deform::detail {

// The parts of the method that depend only on the undeformed mesh and the roles of its
// markers, not on the motion.
struct AraGeometry {
  std::uint64_t connectivity = 0;
  std::uint64_t points = 0;
  std::vector<MarkerRole> marker_roles;
  std::uint64_t nearest_key = 0;  // connectivity and wall faces (NearestFaces::mesh_hash)
  DualMesh dual;
  WallFaces walls;
  std::vector<Vector3> centres;
  std::vector<Vector3> wall_centres;
  SmoothingStencil stencil;
  std::vector<double> node_weights;         // eq. 24–26, per entry of dual.point_cells
  std::vector<std::vector<Index>> colours;  // Gauss–Seidel only, built when first needed
};

// The nearest-face part of the cache file (ara_options.cpp): written, and skipped after
// checking its magic.
void write_nearest_part(std::ostream& stream, const NearestFaces& nearest);
void skip_nearest_part(std::istream& stream, const std::filesystem::path& file);

// The cache file: the nearest faces (the layout read_nearest_faces reads), then this
// geometry with its mesh's hashes and a checksum.
void write_ara_cache(const NearestFaces& nearest, const AraGeometry& geometry,
                     const std::filesystem::path& file);

// What a cache file offers: its geometry when it fits, else null and why not;
// `faces_only` when the file ends after the nearest faces (no geometry block at all).
struct StoredGeometry {
  std::shared_ptr<AraGeometry> geometry;
  bool faces_only = false;
  std::string why_not;
};
// The geometry stored in `file` when it was made for a mesh with this connectivity,
// these points (bit for bit) and these marker roles; none when the file holds none or
// one of another mesh (the points moved, say). Throws mixmesh::Error for a damaged
// geometry block.
StoredGeometry read_ara_geometry(const std::filesystem::path& file, std::uint64_t connectivity,
                                 std::uint64_t points, const std::vector<MarkerRole>& marker_roles);

}  // namespace mixmesh::deform::detail
