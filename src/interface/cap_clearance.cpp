#include "cap_clearance.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <queue>
#include <utility>
#include <vector>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include "mixmesh/interface/interface_split.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/mesh/face_connectivity.hpp"

namespace mixmesh::interface_detail {

namespace {

// Neighbouring caps whose quads' normals are within this many degrees stand on one
// nearly flat sheet: they are aligned, and the valleys between them opened.
constexpr double fold_degrees = 20.0;
// A valley tetrahedron (two neighbouring caps' shared edge and apexes) flatter than this
// is opened: the sliver pass's target.
constexpr double valley_dihedral = 160.0;

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Triangle3 = Kernel::Triangle_3;
using Point3 = Kernel::Point_3;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<Triangle3>::const_iterator>;
using HullTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

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

// Two caps whose quads share an edge, and that edge.
struct SharedEdge {
  std::size_t one = 0, other = 0;
  std::pair<Index, Index> ends;
};

struct CapPairs {
  std::vector<std::vector<std::size_t>> neighbours;  // per cap, the caps sharing an edge of its quad
  std::vector<SharedEdge> shared;                    // each such pair once
};

CapPairs cap_pairs(const std::vector<TallCap>& caps) {
  std::map<std::pair<Index, Index>, std::vector<std::size_t>> edge_caps;
  for (std::size_t cap = 0; cap < caps.size(); ++cap)
    for (int k = 0; k < 4; ++k)
      edge_caps[std::minmax(caps[cap].pyramid[static_cast<std::size_t>(k)],
                            caps[cap].pyramid[static_cast<std::size_t>((k + 1) % 4)])]
          .push_back(cap);
  CapPairs pairs;
  pairs.neighbours.resize(caps.size());
  for (const auto& [edge, sharing] : edge_caps)
    for (std::size_t first : sharing)
      for (std::size_t second : sharing) {
        if (first == second) continue;
        pairs.neighbours[first].push_back(second);
        if (first < second) pairs.shared.push_back({first, second, edge});
      }
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
    for (std::size_t neighbour : pairs.neighbours[cap]) {
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

// Neighbouring caps keep their apexes apart across their shared edge: at least half as
// far as their quads' middles are. The far field fills the valley between them with
// the tetrahedron of that edge and the two apexes, which is flat once the apexes' edge
// runs along the shared one. Over a concave fold the caps of two narrow quads lean
// together, and tens of quad widths high their apexes meet: on random wings of seed 59
// and seed 3 (the first wake rows behind a swept trailing edge, quads a few centimetres
// by 1-2 m, caps 0.3 m high) the apexes ended 2-6 mm apart, offset along the edge, and
// that tetrahedron had 175.8-179.9 deg; the alignment along the mean normal narrows
// such a fold but does not close it. Both caps come down by the same factor until the
// bound holds (not below their lowest). Lowering brings an apex towards its quad, so
// nothing new crosses. Returns the caps lowered.
std::vector<char> separate_neighbouring_caps(MixedMesh& mesh, std::vector<TallCap>& caps,
                                             const CapPairs& pairs) {
  std::vector<char> lowered(caps.size(), 0);
  for (int pass = 0; pass < 4; ++pass) {
    bool moved = false;
    for (const SharedEdge& pair : pairs.shared) {
      TallCap& one = caps[pair.one];
      TallCap& other = caps[pair.other];
      const Vector3 edge = (mesh.points[static_cast<std::size_t>(pair.ends.second)] -
                            mesh.points[static_cast<std::size_t>(pair.ends.first)])
                               .normalized();
      Vector3 across = other.middle - one.middle;
      across -= across.dot(edge) * edge;
      const double distance = across.norm();
      if (!(distance > 0.0)) continue;
      across /= distance;
      // The apexes' separation across the edge with both heights scaled by s:
      // distance - s closing.
      const double closing = -(other.height * other.direction - one.height * one.direction).dot(across);
      if (!(closing > 0.5 * distance)) continue;
      const double scale = 0.5 * distance / closing;
      for (const std::size_t cap : {pair.one, pair.other}) {
        const double height = std::max(caps[cap].lowest, scale * caps[cap].height);
        if (caps[cap].height > height * (1.0 + 1e-9) && lower_to(mesh, caps[cap], height)) {
          lowered[cap] = 1;
          moved = true;
        }
      }
    }
    if (!moved) break;
  }
  return lowered;
}

// The far field fills the valley between two neighbouring caps of nearly coplanar quads
// with the tetrahedron of their shared edge and their two apexes. Where the caps were
// lowered to keep clear of the hull (a fifth of a long edge high no longer, only a
// twentieth), the 45 degrees the levelling allows between their apexes is too steep:
// over the wake's first rows behind a swept trailing edge (random wing 58 of seed 70,
// quads 3 mm x 365 mm, caps 16 and 19 mm high) the apexes' edge then points at the
// shared edge and that tetrahedron is flat (173-174 deg). So the taller cap of such a
// pair comes down, towards its neighbour's height, to the highest of eight steps at
// which that tetrahedron's largest dihedral angle is within valley_dihedral, or where
// none is, to the step where it is smallest. Returns the caps lowered.
std::vector<char> open_valleys(MixedMesh& mesh, std::vector<TallCap>& caps, const CapPairs& pairs) {
  const double least_cosine = std::cos(fold_degrees * M_PI / 180.0);
  std::vector<char> lowered(caps.size(), 0);
  auto valley = [&](const SharedEdge& pair) {
    return largest_dihedral_degrees(mesh.points[static_cast<std::size_t>(pair.ends.first)],
                                    mesh.points[static_cast<std::size_t>(pair.ends.second)],
                                    mesh.points[static_cast<std::size_t>(caps[pair.one].apex)],
                                    mesh.points[static_cast<std::size_t>(caps[pair.other].apex)]);
  };
  for (int pass = 0; pass < 4; ++pass) {
    bool moved = false;
    for (const SharedEdge& pair : pairs.shared) {
      if (caps[pair.one].normal.dot(caps[pair.other].normal) < least_cosine) continue;
      const double now = valley(pair);
      if (!(now > valley_dihedral)) continue;
      const bool one_taller = caps[pair.one].height > caps[pair.other].height;
      const std::size_t taller_cap = one_taller ? pair.one : pair.other;
      TallCap& taller = caps[taller_cap];
      const double low = std::max(taller.lowest, caps[one_taller ? pair.other : pair.one].height);
      const double high = taller.height;
      if (!(high > low * (1.0 + 1e-9))) continue;
      double best_height = high, best_angle = now;
      for (int step = 1; step <= 8; ++step) {
        const double height = high - (high - low) * step / 8.0;
        if (!lower_to(mesh, taller, height)) break;
        const double angle = valley(pair);
        if (angle < best_angle) best_angle = angle, best_height = height;
        if (angle <= valley_dihedral) break;
      }
      // Every step tried was valid, so the chosen height is too.
      const bool opened = best_height < high && best_angle < now - 1e-9;
      lower_to(mesh, taller, opened ? best_height : high);
      if (opened) {
        lowered[taller_cap] = 1;
        moved = true;
      }
    }
    if (!moved) break;
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
  const double least_cosine = std::cos(fold_degrees * M_PI / 180.0);
  // The fold is judged on the quads' own normals, so a chain of gentle folds does not
  // carry a cap past fold_degrees.
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<Vector3> direction(caps.size());
    for (std::size_t cap = 0; cap < caps.size(); ++cap) {
      direction[cap] = caps[cap].direction;
      for (std::size_t neighbour : pairs.neighbours[cap])
        if (caps[neighbour].normal.dot(caps[cap].normal) > least_cosine) direction[cap] += caps[neighbour].direction;
      direction[cap].normalize();
    }
    for (std::size_t cap = 0; cap < caps.size(); ++cap) {
      TallCap& tall = caps[cap];
      // Its apex stays in the plane. A standard cap (tall only because its sheared quad
      // is narrower than its short edges) stays on its own normal as it did before it
      // could come down: turned with its neighbours over a rounded tip's trailing edge,
      // such caps left a hull TetGen could not recover (random wing 6 of seed 93).
      if (tall.on_plane || tall.standard) continue;
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
                                std::vector<TallCap>& caps, const std::optional<Plane>& plane) {
  std::vector<char> lowered(caps.size(), 0);
  const CapPairs pairs = cap_pairs(caps);
  align_neighbouring_caps(mesh, caps, pairs);
  // On a sheet with dihedral the caps on one side lean towards the symmetry plane, and
  // next to it a tall cap leaned across it. So a cap's direction loses its component
  // towards the plane: the caps stand parallel to the plane and to the leaning caps on
  // it (lowering them instead left the narrow rows by the plane with caps so low over
  // their long quads that the valleys between them were flat, 176.9 deg on random wing
  // 64 of seed 59, with 7.8 deg of dihedral). A cap whose pyramid would then be inverted
  // keeps its direction.
  if (plane) {
    const Vector3 normal = plane->normal.normalized();
    for (TallCap& tall : caps) {
      if (tall.on_plane || tall.standard) continue;
      const double side = (tall.middle - plane->point).dot(normal) < 0.0 ? -1.0 : 1.0;
      const double towards = -side * tall.direction.dot(normal);
      if (!(towards > 0.0)) continue;
      const Vector3 direction = tall.direction;
      tall.direction = (direction - direction.dot(normal) * normal).normalized();
      if (!lower_to(mesh, tall, tall.height)) tall.direction = direction;
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
      for (std::size_t side = 0; side < caps[cap].hull_triangles && !crosses; ++side) {
        const std::size_t own = caps[cap].first_hull_triangle + side;
        hits.clear();
        tree.all_intersected_primitives(shrunk(mesh, hull[own]), std::back_inserter(hits));
        for (const auto& hit : hits) {
          const auto index = static_cast<std::size_t>(hit - triangles.begin());
          if (index < caps[cap].first_hull_triangle ||
              index >= caps[cap].first_hull_triangle + caps[cap].hull_triangles)
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
  const std::vector<char> separated = separate_neighbouring_caps(mesh, caps, pairs);
  const std::vector<char> levelled = level_neighbouring_caps(mesh, caps, pairs);
  const std::vector<char> opened = open_valleys(mesh, caps, pairs);
  for (std::size_t cap = 0; cap < caps.size(); ++cap)
    lowered[cap] = lowered[cap] || separated[cap] || levelled[cap] || opened[cap];
  return static_cast<std::size_t>(std::count(lowered.begin(), lowered.end(), 1));
}

}  // namespace mixmesh::interface_detail
