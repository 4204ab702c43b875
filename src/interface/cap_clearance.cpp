#include "cap_clearance.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <queue>
#include <utility>
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
  apex = cap.middle + height * cap.direction;
  if (!cell_shape(CellType::pyramid, mesh.points, cap.pyramid.data()).valid()) {
    apex = before;
    return false;
  }
  cap.height = height;
  return true;
}

using CapPairs = std::vector<std::vector<std::size_t>>;

// Per cap, the caps that share an edge of its quad.
CapPairs cap_pairs(const std::vector<TallCap>& caps) {
  std::map<std::pair<Index, Index>, std::vector<std::size_t>> edge_caps;
  for (std::size_t cap = 0; cap < caps.size(); ++cap)
    for (int k = 0; k < 4; ++k)
      edge_caps[std::minmax(caps[cap].pyramid[static_cast<std::size_t>(k)],
                            caps[cap].pyramid[static_cast<std::size_t>((k + 1) % 4)])]
          .push_back(cap);
  CapPairs pairs(caps.size());
  for (const auto& [edge, sharing] : edge_caps)
    for (std::size_t first : sharing)
      for (std::size_t second : sharing)
        if (first != second) pairs[first].push_back(second);
  return pairs;
}

// Neighbouring caps (sharing an edge of their quads) keep their apexes within 45 degrees
// of each other: a cap stands at most as much higher than its neighbour as their quads'
// middles are apart. The far field fills the valley between two caps with the
// tetrahedron of their shared edge and the two apexes; where one cap of a pair of narrow
// quads came down by half and the other did not (the wake's first rows behind a trailing
// edge, 0.7 mm x 86 mm: apexes 8.6 and 17.2 mm high 0.75 mm apart), the apexes' edge
// stands nearly upright in the plane of the shared edge and that tetrahedron is flat
// (176-179 deg on random wings 2, 3 and 13 of seed 53). Lowering a cap keeps it inside its
// taller self, so no new crossing arises. Returns the caps lowered.
std::vector<char> level_neighbouring_caps(MixedMesh& mesh, std::vector<TallCap>& caps,
                                          const CapPairs& pairs) {
  // Lowest first (a distance transform over the caps): each cap's height bounds its
  // neighbours' by the distance between the quads' middles.
  std::vector<char> lowered(caps.size(), 0);
  using Entry = std::pair<double, std::size_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  for (std::size_t cap = 0; cap < caps.size(); ++cap) queue.push({caps[cap].height, cap});
  while (!queue.empty()) {
    const auto [height, cap] = queue.top();
    queue.pop();
    if (height > caps[cap].height) continue;  // a stale entry
    for (std::size_t neighbour : pairs[cap]) {
      TallCap& next = caps[neighbour];
      const double bound = std::max(next.lowest, height + (next.middle - caps[cap].middle).norm());
      if (next.height > bound * (1.0 + 1e-9) && lower_to(mesh, next, bound)) {
        lowered[neighbour] = 1;
        queue.push({next.height, neighbour});
      }
    }
  }
  return lowered;
}

// Caps on nearly coplanar neighbouring quads stand along their mean normal. Over a fold
// of a few degrees between narrow quads their own normals turn towards each other, and
// apexes tens of quad widths high meet: on random wing 2 of seed 53 two caps 31 mm high
// over quads 1.6 mm wide at a 2.5 degree fold ended 0.9 mm apart along their shared
// edge, and the far field's tetrahedron of that edge and the two apexes had 179.2 deg.
// Two passes of averaging with the neighbours within fold_degrees; a cap whose pyramid
// would be inverted keeps its own normal.
void align_neighbouring_caps(MixedMesh& mesh, std::vector<TallCap>& caps, const CapPairs& pairs) {
  constexpr double fold_degrees = 20.0;
  const double least_cosine = std::cos(fold_degrees * M_PI / 180.0);
  // The fold is judged on the quads' own normals, so a chain of gentle folds does not
  // carry a cap past fold_degrees.
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<Vector3> direction(caps.size());
    for (std::size_t cap = 0; cap < caps.size(); ++cap) {
      direction[cap] = caps[cap].direction;
      for (std::size_t neighbour : pairs[cap])
        if (caps[neighbour].normal.dot(caps[cap].normal) > least_cosine) direction[cap] += caps[neighbour].direction;
      direction[cap].normalize();
    }
    for (std::size_t cap = 0; cap < caps.size(); ++cap) {
      TallCap& tall = caps[cap];
      Vector3& apex = mesh.points[static_cast<std::size_t>(tall.apex)];
      const Vector3 before = apex;
      apex = tall.middle + tall.height * direction[cap];
      if (cell_shape(CellType::pyramid, mesh.points, tall.pyramid.data()).valid())
        tall.direction = direction[cap];
      else
        apex = before;
    }
  }
}

}  // namespace

std::size_t lower_crossing_caps(MixedMesh& mesh, const std::vector<std::array<Index, 3>>& hull,
                                std::vector<TallCap>& caps) {
  std::vector<char> lowered(caps.size(), 0);
  const CapPairs pairs = cap_pairs(caps);
  align_neighbouring_caps(mesh, caps, pairs);
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
      const bool aligned = caps[cap].direction != caps[cap].normal;
      if (!(caps[cap].height > caps[cap].lowest) && !aligned) continue;
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
      if (!(tall.height > tall.lowest)) {
        // At its lowest and still crossing: back along its own normal, the standard cap.
        const Vector3 aligned = tall.direction;
        tall.direction = tall.normal;
        if (lower_to(mesh, tall, tall.height))
          ++moved;
        else
          tall.direction = aligned;
        continue;
      }
      if (!lower_to(mesh, tall, std::max(tall.lowest, 0.5 * tall.height))) {
        tall.lowest = tall.height;  // a twisted quad: no lower cap is valid
        continue;
      }
      lowered[cap] = 1;
      ++moved;
    }
    if (moved == 0) break;
  }
  const std::vector<char> levelled = level_neighbouring_caps(mesh, caps, pairs);
  for (std::size_t cap = 0; cap < caps.size(); ++cap) lowered[cap] = lowered[cap] || levelled[cap];
  return static_cast<std::size_t>(std::count(lowered.begin(), lowered.end(), 1));
}

}  // namespace mixmesh::interface_detail
