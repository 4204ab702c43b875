#include "cap_clearance.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include "mixmesh/interface/interface_split.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/mesh/face_connectivity.hpp"

namespace mixmesh::interface_detail {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Triangle3 = Kernel::Triangle_3;
using Point3 = Kernel::Point_3;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<Triangle3>::const_iterator>;
using HullTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
using Segment3 = Kernel::Segment_3;
using SegmentPrimitive = CGAL::AABB_segment_primitive<Kernel, std::vector<Segment3>::const_iterator>;
using SegmentTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, SegmentPrimitive>>;

Point3 cgal_point(const Vector3& p) {
  return {p.x(), p.y(), p.z()};
}

// The triangle pulled a millionth of the way towards its centroid: it then no longer
// touches the triangles that share an edge or a corner with it, only those it crosses.
Triangle3 shrunk(const MixedMesh& mesh, const std::array<Index, 3>& triangle) {
  Vector3 corners[3];
  for (int k = 0; k < 3; ++k)
    corners[k] = mesh.points[static_cast<std::size_t>(triangle[static_cast<std::size_t>(k)])];
  const Vector3 centroid = (corners[0] + corners[1] + corners[2]) / 3.0;
  for (Vector3& corner : corners) corner += 1e-6 * (centroid - corner);
  return {cgal_point(corners[0]), cgal_point(corners[1]), cgal_point(corners[2])};
}

// Moves the cap's apex to `height` over its quad, unless the pyramid would be inverted
// there (a twisted quad); says whether it moved.
bool lower_to(MixedMesh& mesh, TallCap& cap, double height) {
  Vector3& apex = mesh.points[static_cast<std::size_t>(cap.apex)];
  const Vector3 before = apex;
  apex = cap.middle + height * cap.normal;
  if (!cell_shape(CellType::pyramid, mesh.points, cap.pyramid.data()).valid()) {
    apex = before;
    return false;
  }
  cap.height = height;
  return true;
}

}  // namespace

std::size_t lower_crossing_caps(MixedMesh& mesh, const std::vector<std::array<Index, 3>>& hull,
                                std::vector<TallCap>& caps) {
  std::vector<char> lowered(caps.size(), 0);
  // Near the footprint (the hull's edges in the symmetry plane, used by one hull
  // triangle) a tall cap leans across the plane on a sheet with dihedral, and the slot
  // between a tall cap and the plane fills with thin tetrahedra that fold under a pitch
  // of the mesh. There a cap stands no higher than its distance from the footprint (and
  // not below its lowest height): the caps rise from the plane at 45 degrees.
  std::vector<Segment3> footprint;
  for (const auto& edge : triangle_free_edges(hull))
    footprint.emplace_back(cgal_point(mesh.points[static_cast<std::size_t>(edge[0])]),
                           cgal_point(mesh.points[static_cast<std::size_t>(edge[1])]));
  if (!footprint.empty()) {
    SegmentTree segments(footprint.begin(), footprint.end());
    segments.accelerate_distance_queries();
    for (std::size_t cap = 0; cap < caps.size(); ++cap) {
      const double limit =
          std::max(caps[cap].lowest,
                   std::sqrt(CGAL::to_double(segments.squared_distance(cgal_point(caps[cap].middle)))));
      if (caps[cap].height > limit && lower_to(mesh, caps[cap], limit)) lowered[cap] = 1;
    }
  }
  // Each round halves the crossing caps once; a cap comes down from its tall height to
  // its lowest in a few rounds (the tall height is at most 0.4 / 2 = a fifth of the
  // longest edge over the lowest, the shortest edge).
  for (int round = 0; round < 12; ++round) {
    std::vector<Triangle3> triangles;
    triangles.reserve(hull.size());
    for (const auto& triangle : hull)
      triangles.emplace_back(cgal_point(mesh.points[static_cast<std::size_t>(triangle[0])]),
                             cgal_point(mesh.points[static_cast<std::size_t>(triangle[1])]),
                             cgal_point(mesh.points[static_cast<std::size_t>(triangle[2])]));
    const HullTree tree(triangles.begin(), triangles.end());
    std::vector<std::size_t> crossing;
    std::vector<Primitive::Id> hits;
    for (std::size_t cap = 0; cap < caps.size(); ++cap) {
      if (!(caps[cap].height > caps[cap].lowest)) continue;
      bool crosses = false;
      for (std::size_t side = 0; side < 4 && !crosses; ++side) {
        const std::size_t own = caps[cap].first_hull_triangle + side;
        hits.clear();
        tree.all_intersected_primitives(shrunk(mesh, hull[own]), std::back_inserter(hits));
        for (const auto& hit : hits) {
          const auto index = static_cast<std::size_t>(hit - triangles.begin());
          if (index < caps[cap].first_hull_triangle || index >= caps[cap].first_hull_triangle + 4)
            crosses = true;
        }
      }
      if (crosses) crossing.push_back(cap);
    }
    if (crossing.empty()) break;
    std::size_t moved = 0;
    for (std::size_t cap : crossing) {
      TallCap& tall = caps[cap];
      if (!lower_to(mesh, tall, std::max(tall.lowest, 0.5 * tall.height))) {
        tall.lowest = tall.height;  // a twisted quad: no lower cap is valid
        continue;
      }
      lowered[cap] = 1;
      ++moved;
    }
    if (moved == 0) break;
  }
  return static_cast<std::size_t>(std::count(lowered.begin(), lowered.end(), 1));
}

}  // namespace mixmesh::interface_detail
