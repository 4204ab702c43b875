// Tall caps of a sheet's cells, lowered where they cross the hull.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include "mixmesh/mesh/mixed_mesh.hpp"

namespace mixmesh::interface_detail {

// A cap whose apex stands above the lowest height its quad allows.
struct TallCap {
  Index apex = -1;
  Vector3 middle = Vector3::Zero();     // of its quad
  Vector3 normal = Vector3::Zero();     // of its quad, unit, outward
  Vector3 direction = Vector3::Zero();  // of its apex from the middle, unit (its normal, or aligned)
  double height = 0.0;                  // the apex's height over the middle now
  double lowest = 0.0;                  // the height it may come down to
  std::array<Index, 5> pyramid{};       // quad corners, apex
  std::size_t first_hull_triangle = 0;  // its hull triangles follow in order
  std::size_t hull_triangles = 4;       // 3 when it leans on the symmetry plane
  bool on_plane = false;                // its apex in the symmetry plane (kept there)
  bool standard = false;                // tall only by its quad's width (kept on its normal)
};

// The symmetry plane: a point in it and its normal (any length, either side).
struct Plane {
  Vector3 point = Vector3::Zero();
  Vector3 normal = Vector3::Zero();
};

// Aligns the caps with their neighbours' normals (not those leaning on the plane), turns
// those leaning towards the plane parallel to it, halves the height of every cap with a
// face crossing another hull triangle (not below `lowest`, and not to an inverted
// pyramid; a cap at its lowest that still crosses goes back to its own normal) until no
// cap crosses or none can come down further, and levels neighbouring caps. Returns the
// number of caps lowered (clear of the hull or level with a neighbour).
std::size_t lower_crossing_caps(MixedMesh& mesh, const std::vector<std::array<Index, 3>>& hull,
                                std::vector<TallCap>& caps, const std::optional<Plane>& plane);

}  // namespace mixmesh::interface_detail
