#include "deform/wall_faces.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <nanoflann.hpp>
#include <numeric>

#include "mixmesh/mesh/point_cloud.hpp"

namespace mixmesh::deform::detail {

namespace {

int find_root(std::vector<Index>& parent, Index node) {
  while (parent[static_cast<std::size_t>(node)] != node) {
    parent[static_cast<std::size_t>(node)] =
        parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(node)])];
    node = parent[static_cast<std::size_t>(node)];
  }
  return node;
}

// Closest point of triangle (a, b, c) to p, by the Voronoi regions of its features.
Vector3 closest_on_triangle(const Vector3& p, const Vector3& a, const Vector3& b, const Vector3& c) {
  const Vector3 ab = b - a;
  const Vector3 ac = c - a;
  const Vector3 ap = p - a;
  const double d1 = ab.dot(ap);
  const double d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Vector3 bp = p - b;
  const double d3 = ab.dot(bp);
  const double d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + ab * (d1 / (d1 - d3));
  const Vector3 cp = p - c;
  const double d5 = ab.dot(cp);
  const double d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denominator = va + vb + vc;
  if (denominator <= 0.0) return a;  // degenerate triangle: fall back to a corner
  return a + ab * (vb / denominator) + ac * (vc / denominator);
}

using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, PointCloud<>>,
                                                 PointCloud<>, 3, std::size_t>;

// The search for a cell's nearest faces runs in two rounds. A boundary that encloses
// the cell at a distance, the far field round a wing, leaves every one of its faces at
// nearly the same distance from the cells near its middle, and an exact k-d search
// then visits nearly all of them (on the ONERA M6, the 1,279 far-field faces cost more
// than the wing's 8,838). So every boundary is first searched approximately for one
// face, nanoflann accepting a centre within 1 + `approximate_slack` of the nearest,
// and the boundaries whose face lies within `exact_range` times the nearest distance
// are searched again, exactly and for `candidates` faces as before. Those carry the
// weight of the blend (eq. 2, 11): beyond three times the nearest distance a
// boundary's share is under 6 % with γ = 4, and there only its distance, not its
// face's motion, is approximate.
constexpr float approximate_slack = 0.5f;
constexpr double exact_range = 3.0;

struct BoundaryTree {
  std::vector<Vector3> centres;
  PointCloud<> cloud;             // over centres, once they are all in
  std::vector<Index> wall_index;  // cloud point → index into WallFaces::faces
  std::unique_ptr<Tree> tree;
};

double wall_distance(const DualMesh& dual, const WallFaces& walls, Index wall, const Vector3& point,
                     const std::vector<Vector3>& points) {
  const std::size_t face = static_cast<std::size_t>(walls.faces[static_cast<std::size_t>(wall)]);
  const Index* nodes = dual.boundary_nodes(face);
  const int count = dual.face_size(face);
  Vector3 corners[4];
  for (int local = 0; local < count; ++local) corners[local] = points[static_cast<std::size_t>(nodes[local])];
  return point_face_distance(point, corners, count);
}

}  // namespace

double point_face_distance(const Vector3& point, const Vector3* corners, int corner_count) {
  if (corner_count == 2) {
    const Vector3 edge = corners[1] - corners[0];
    const double length2 = edge.squaredNorm();
    const double t = length2 > 0.0 ? std::clamp((point - corners[0]).dot(edge) / length2, 0.0, 1.0) : 0.0;
    return (corners[0] + t * edge - point).norm();
  }
  double best = (closest_on_triangle(point, corners[0], corners[1], corners[2]) - point).norm();
  if (corner_count == 4)
    best = std::min(best, (closest_on_triangle(point, corners[0], corners[2], corners[3]) - point).norm());
  return best;
}

WallFaces wall_faces(const DualMesh& dual, const std::vector<MarkerRole>& marker_roles) {
  WallFaces walls;
  for (std::size_t face = 0; face < dual.face_count(); ++face) {
    const int marker = dual.face_marker[face];
    const bool sliding = marker >= 0 && static_cast<std::size_t>(marker) < marker_roles.size() &&
                         marker_roles[static_cast<std::size_t>(marker)] == MarkerRole::sliding;
    if (!sliding) walls.faces.push_back(static_cast<Index>(face));
  }
  // Boundaries: connected components of wall faces through shared nodes.
  std::vector<Index> parent(dual.point_count);
  std::iota(parent.begin(), parent.end(), 0);
  for (Index face : walls.faces) {
    const Index* nodes = dual.boundary_nodes(static_cast<std::size_t>(face));
    const int count = dual.face_size(static_cast<std::size_t>(face));
    const Index root = find_root(parent, nodes[0]);
    for (int local = 1; local < count; ++local)
      parent[static_cast<std::size_t>(find_root(parent, nodes[local]))] = root;
  }
  std::vector<int> label(dual.point_count, -1);
  walls.boundary.resize(walls.faces.size());
  for (std::size_t wall = 0; wall < walls.faces.size(); ++wall) {
    const Index root = find_root(parent, dual.boundary_nodes(static_cast<std::size_t>(walls.faces[wall]))[0]);
    int& id = label[static_cast<std::size_t>(root)];
    if (id < 0) id = walls.boundary_count++;
    walls.boundary[wall] = id;
  }
  return walls;
}

NearestFaces find_nearest_faces(const DualMesh& dual, const WallFaces& walls,
                                const std::vector<Vector3>& centres, const std::vector<Vector3>& points,
                                int candidates) {
  std::vector<BoundaryTree> trees(static_cast<std::size_t>(walls.boundary_count));
  for (std::size_t wall = 0; wall < walls.faces.size(); ++wall) {
    BoundaryTree& tree = trees[static_cast<std::size_t>(walls.boundary[wall])];
    tree.centres.push_back(face_centre(dual, static_cast<std::size_t>(walls.faces[wall]), points));
    tree.wall_index.push_back(static_cast<Index>(wall));
  }
  for (BoundaryTree& tree : trees) {
    tree.cloud.elements = &tree.centres;
    tree.tree = std::make_unique<Tree>(3, tree.cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
    tree.tree->buildIndex();
  }

  NearestFaces nearest;
  nearest.cell_count = dual.cell_count();
  nearest.wall_face_count = walls.faces.size();
  nearest.faces.assign(dual.cell_count(), {-1, -1});
  const std::size_t wanted = static_cast<std::size_t>(std::max(candidates, 1));
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, dual.cell_count()),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      std::vector<std::size_t> found(wanted);
                      std::vector<double> squared(wanted);
                      std::vector<double> distance(trees.size());
                      std::vector<Index> face(trees.size());
                      // The nearest of the `count` faces whose centres the search returns.
                      auto search = [&](const BoundaryTree& tree, const Vector3& centre, std::size_t count,
                                        float slack, double& best_distance, Index& best_face) {
                        nanoflann::KNNResultSet<double> result(count);
                        result.init(found.data(), squared.data());
                        tree.tree->findNeighbors(result, centre.data(), nanoflann::SearchParams(32, slack));
                        best_distance = std::numeric_limits<double>::infinity();
                        best_face = -1;
                        for (std::size_t slot = 0; slot < result.size(); ++slot) {
                          const Index wall = tree.wall_index[found[slot]];
                          const double exact = wall_distance(dual, walls, wall, centre, points);
                          if (exact < best_distance) {
                            best_distance = exact;
                            best_face = wall;
                          }
                        }
                      };
                      for (std::size_t cell = range.begin(); cell != range.end(); ++cell) {
                        const Vector3& centre = centres[cell];
                        double nearest_distance = std::numeric_limits<double>::infinity();
                        for (std::size_t boundary = 0; boundary < trees.size(); ++boundary) {
                          search(trees[boundary], centre, 1, approximate_slack, distance[boundary],
                                 face[boundary]);
                          nearest_distance = std::min(nearest_distance, distance[boundary]);
                        }
                        for (std::size_t boundary = 0; boundary < trees.size(); ++boundary)
                          if (distance[boundary] <= exact_range * nearest_distance)
                            search(trees[boundary], centre, wanted, 0.0f, distance[boundary], face[boundary]);
                        // The two closest boundaries.
                        double best_distance[2] = {std::numeric_limits<double>::infinity(),
                                                   std::numeric_limits<double>::infinity()};
                        Index best_face[2] = {-1, -1};
                        for (std::size_t boundary = 0; boundary < trees.size(); ++boundary) {
                          if (distance[boundary] < best_distance[0]) {
                            best_distance[1] = best_distance[0];
                            best_face[1] = best_face[0];
                            best_distance[0] = distance[boundary];
                            best_face[0] = face[boundary];
                          } else if (distance[boundary] < best_distance[1]) {
                            best_distance[1] = distance[boundary];
                            best_face[1] = face[boundary];
                          }
                        }
                        nearest.faces[cell] = {best_face[0], best_face[1]};
                      }
                    });
  return nearest;
}

void nearest_distances(const DualMesh& dual, const WallFaces& walls, const NearestFaces& nearest,
                       const std::vector<Vector3>& centres, const std::vector<Vector3>& points,
                       std::vector<double>& first, std::vector<double>& second) {
  first.assign(dual.cell_count(), std::numeric_limits<double>::infinity());
  second.assign(dual.cell_count(), std::numeric_limits<double>::infinity());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, dual.cell_count()),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t cell = range.begin(); cell != range.end(); ++cell) {
                        const auto& faces = nearest.faces[cell];
                        if (faces[0] >= 0)
                          first[cell] = wall_distance(dual, walls, faces[0], centres[cell], points);
                        if (faces[1] >= 0)
                          second[cell] = wall_distance(dual, walls, faces[1], centres[cell], points);
                      }
                    });
}

}  // namespace mixmesh::deform::detail
