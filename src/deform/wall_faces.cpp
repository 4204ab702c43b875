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
                      for (std::size_t cell = range.begin(); cell != range.end(); ++cell) {
                        const Vector3& centre = centres[cell];
                        // Best face of each boundary; keep the two closest boundaries.
                        double best_distance[2] = {std::numeric_limits<double>::infinity(),
                                                   std::numeric_limits<double>::infinity()};
                        Index best_face[2] = {-1, -1};
                        for (const BoundaryTree& tree : trees) {
                          const std::size_t count =
                              tree.tree->knnSearch(centre.data(), wanted, found.data(), squared.data());
                          double distance = std::numeric_limits<double>::infinity();
                          Index face = -1;
                          for (std::size_t slot = 0; slot < count; ++slot) {
                            const Index wall = tree.wall_index[found[slot]];
                            const double exact = wall_distance(dual, walls, wall, centre, points);
                            if (exact < distance) {
                              distance = exact;
                              face = wall;
                            }
                          }
                          if (distance < best_distance[0]) {
                            best_distance[1] = best_distance[0];
                            best_face[1] = best_face[0];
                            best_distance[0] = distance;
                            best_face[0] = face;
                          } else if (distance < best_distance[1]) {
                            best_distance[1] = distance;
                            best_face[1] = face;
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
