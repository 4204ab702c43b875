// Anisotropic points: the layer growth continued outward from the hull in metric space.

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <tbb/parallel_for.h>
#include <Eigen/Eigenvalues>
#include <nanoflann.hpp>

#include <algorithm>
#include <limits>
#include <map>
#include <numeric>

#include "farfield/farfield_parts.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/mesh/point_cloud.hpp"

namespace mixmesh::farfield_detail {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Triangle3 = Kernel::Triangle_3;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<Triangle3>::const_iterator>;
using HullTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

struct Candidate {
  Vector3 point;
  double spacing;   // the normal spacing of its layer: the smallest size around it
  double distance;  // from its hull node along the normal
  bool on_plane;
};

struct CandidatePoint {
  const Vector3& operator()(const Candidate& candidate) const { return candidate.point; }
};
using CandidateCloud = PointCloud<Candidate, CandidatePoint>;
using CandidateTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, CandidateCloud>, CandidateCloud,
                                        3>;

// Squared distance to the nearest of a fixed set of points (a k-d tree over them).
class NearestPoint {
 public:
  explicit NearestPoint(std::vector<Vector3> points) : points_(std::move(points)) { tree_.buildIndex(); }
  NearestPoint(const NearestPoint&) = delete;  // the tree refers to this object's points
  NearestPoint& operator=(const NearestPoint&) = delete;
  double squared_distance(const Vector3& query) const {
    unsigned nearest = 0;
    double squared = 0.0;
    tree_.knnSearch(query.data(), 1, &nearest, &squared);
    return squared;
  }

 private:
  using Cloud = PointCloud<>;
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Cloud>, Cloud, 3>;
  std::vector<Vector3> points_;
  Cloud cloud_{&points_};
  Tree tree_{3, cloud_, nanoflann::KDTreeSingleIndexAdaptorParams(16)};
};

// The hull's triangles for a CGAL AABB tree (which keeps iterators into the vector).
std::vector<Triangle3> hull_triangles(const std::vector<Vector3>& points, const std::vector<Triangle>& hull) {
  std::vector<Triangle3> triangles;
  triangles.reserve(hull.size());
  for (const Triangle& triangle : hull) {
    auto corner = [&](int local) {
      const Vector3& p = points[static_cast<std::size_t>(triangle[static_cast<std::size_t>(local)])];
      return Kernel::Point_3(p.x(), p.y(), p.z());
    };
    triangles.emplace_back(corner(0), corner(1), corner(2));
  }
  return triangles;
}

// The candidates `keep` accepts, in their order; `keep` is called in parallel.
template <typename Keep>
std::vector<Vector3> kept_in_order(const std::vector<Vector3>& candidates, const Keep& keep) {
  std::vector<char> kept_flag(candidates.size(), 0);
  tbb::parallel_for(std::size_t{0}, candidates.size(), [&](std::size_t candidate) {
    kept_flag[candidate] = keep(candidates[candidate]) ? 1 : 0;
  });
  std::vector<Vector3> kept;
  for (std::size_t candidate = 0; candidate < candidates.size(); ++candidate)
    if (kept_flag[candidate]) kept.push_back(candidates[candidate]);
  return kept;
}

}  // namespace

LayerPoints layer_points(const FarFieldInput& input, const std::vector<std::array<Index, 2>>& footprint,
                         bool symmetric, const std::vector<double>& isotropic_size,
                         const FarFieldOptions& options) {
  std::map<Index, std::size_t> slot;  // hull node → position in the node lists below
  std::vector<Index> nodes;
  for (const auto& triangle : input.hull)
    for (Index node : triangle)
      if (slot.emplace(node, nodes.size()).second) nodes.push_back(node);
  std::vector<const Matrix3*> metric(nodes.size(), nullptr);
  for (std::size_t entry = 0; entry < input.metric_nodes.size(); ++entry) {
    const auto found = slot.find(input.metric_nodes[entry]);
    if (found != slot.end()) metric[found->second] = &input.metrics[entry];
  }
  for (std::size_t position = 0; position < nodes.size(); ++position)
    if (!metric[position])
      throw Error("farfield: anisotropic sizing needs a metric at every hull node; node " +
                  std::to_string(nodes[position]) + " has none");

  // Area-weighted normals, smoothed twice over the hull's edges so that columns from
  // concave regions spread less.
  auto at = [&](Index node) -> const Vector3& { return input.points[static_cast<std::size_t>(node)]; };
  std::vector<Vector3> normal(nodes.size(), Vector3::Zero());
  std::vector<std::vector<std::size_t>> neighbours(nodes.size());
  // Nodes under a cap also keep the unit normals of their hull faces.
  std::vector<char> capped(nodes.size(), 0);
  for (Index node : input.capped_nodes) {
    const auto found = slot.find(node);
    if (found != slot.end()) capped[found->second] = 1;
  }
  std::vector<std::vector<Vector3>> face_normals(nodes.size());
  for (const auto& triangle : input.hull) {
    const Vector3 area = 0.5 * (at(triangle[1]) - at(triangle[0])).cross(at(triangle[2]) - at(triangle[0]));
    for (int corner = 0; corner < 3; ++corner) {
      const std::size_t here = slot[triangle[static_cast<std::size_t>(corner)]];
      normal[here] += area;
      neighbours[here].push_back(slot[triangle[static_cast<std::size_t>((corner + 1) % 3)]]);
      if (capped[here]) face_normals[here].push_back(area.normalized());
    }
  }
  std::vector<char> on_footprint(nodes.size(), 0);
  for (const auto& edge : footprint) on_footprint[slot[edge[0]]] = on_footprint[slot[edge[1]]] = 1;
  for (int pass = 0; pass < 3; ++pass) {
    std::vector<Vector3> smoothed(nodes.size());
    for (std::size_t position = 0; position < nodes.size(); ++position) {
      Vector3 sum = normal[position].normalized() * 2.0;
      for (std::size_t other : neighbours[position]) sum += normal[other].normalized();
      if (symmetric && on_footprint[position]) sum.y() = 0.0;  // footprint columns stay on the plane
      smoothed[position] = sum.normalized();
    }
    normal = smoothed;
  }

  const std::vector<Triangle3> triangles = hull_triangles(input.points, input.hull);
  HullTree hull_tree(triangles.begin(), triangles.end());
  // Built before the parallel queries below rather than lazily by the first of them.
  hull_tree.build();
  hull_tree.accelerate_distance_queries();

  // Longest hull edge at each node and the body's thickness below it (along −n to the
  // first hull triangle not incident to the node; infinite when the ray leaves the hull).
  std::vector<double> longest(nodes.size(), 0.0),
      thickness(nodes.size(), std::numeric_limits<double>::infinity());
  for (std::size_t position = 0; position < nodes.size(); ++position)
    for (std::size_t other : neighbours[position])
      longest[position] = std::max(longest[position], (at(nodes[position]) - at(nodes[other])).norm());
  tbb::parallel_for(std::size_t{0}, nodes.size(), [&](std::size_t position) {
    const Vector3& origin = at(nodes[position]);
    const Index node = nodes[position];
    const Kernel::Ray_3 ray(
        Kernel::Point_3(origin.x(), origin.y(), origin.z()),
        Kernel::Vector_3(-normal[position].x(), -normal[position].y(), -normal[position].z()));
    const auto hit = hull_tree.first_intersection(ray, [&](std::vector<Triangle3>::const_iterator face) {
      const auto& corners = input.hull[static_cast<std::size_t>(face - triangles.begin())];
      return std::find(corners.begin(), corners.end(), node) != corners.end();
    });
    if (!hit) return;
    if (const Kernel::Point_3* point = boost::get<Kernel::Point_3>(&hit->first))
      thickness[position] = (Vector3(point->x(), point->y(), point->z()) - origin).norm();
  });

  // Columns: normal spacing from the metric (1/√(nᵀ M n)), growing until it reaches
  // the isotropic size the far field has at the node, where the isotropic grading takes
  // over. (The metric's smallest tangential spacing is no such limit: a cell as tall as
  // its short side but ten times as long has isotropic tetrahedra ten times too tall
  // above it, and on the ONERA M6 a fifth of the hull nodes, along the leading and
  // trailing edges, got no point that way.)
  std::vector<std::vector<Candidate>> columns(nodes.size());  // filled in parallel, joined in node order
  tbb::parallel_for(std::size_t{0}, nodes.size(), [&](std::size_t position) {
    const Vector3& direction = normal[position];
    const Matrix3& node_metric = *metric[position];
    const double isotropic = isotropic_size[static_cast<std::size_t>(nodes[position])];
    // Over a thin part of the body (trailing edge, the wake's ends, the tip) a sphere
    // through a hull edge of length L cannot bulge far into the body: one through the
    // edge's ends whose deepest point stays within the thickness τ has its centre
    // d = (L²/4 − τ²)/(2τ) = L²/(8τ) − τ/2 above the hull, and a point over an end of
    // the edge lower than 2d lies inside it. The edge is then no longer Delaunay and
    // TetGen must recover it with Steiner points that it fails to remove under -Y.
    // Points lower than edge_protection × d are left out (TetGen recovers the few edges
    // the higher ones cost). Where the edge's diametral sphere fits in the body (L/2 ≤ τ:
    // the leading edge, most of the chord) d ≤ 0 and nothing is.
    const double protected_height =
        options.edge_protection *
        std::max(0.0, longest[position] * longest[position] / (8.0 * thickness[position]) - 0.5 * thickness[position]);
    double spacing = 1.0 / std::sqrt(direction.dot(node_metric * direction));
    double distance = 0.0;
    for (int layer = 0; layer < options.maximum_layers && spacing < isotropic;
         ++layer, spacing *= options.layer_growth) {
      // The first point stands lower than a whole spacing (FarFieldOptions::first_layer_height).
      distance += (layer == 0 ? options.first_layer_height : 1.0) * spacing;
      if (distance < protected_height) continue;
      Vector3 point = at(nodes[position]) + distance * direction;
      const bool plane = symmetric && on_footprint[position];
      if (plane) point.y() = options.symmetry_y;
      if (capped[position]) {
        bool beside_a_face = false;
        for (const Vector3& face_normal : face_normals[position])
          beside_a_face = beside_a_face || std::abs(face_normal.dot(point - at(nodes[position]))) <
                                               options.cap_face_clearance * distance;
        if (beside_a_face) break;
      }
      // A column that comes near another part of the hull (concave corners) stops.
      const Kernel::Point_3 query(point.x(), point.y(), point.z());
      if (hull_tree.squared_distance(query) < 0.25 * distance * distance) break;
      if (symmetric && !plane && point.y() < options.symmetry_y + 0.5 * spacing) break;
      columns[position].push_back({point, spacing, distance, plane});
    }
  });
  std::vector<Candidate> candidates;
  for (const std::vector<Candidate>& column : columns)
    candidates.insert(candidates.end(), column.begin(), column.end());

  // Greedy thinning, smallest spacing first: a candidate removes the later ones within
  // minimum_metric_distance of its own spacing.
  std::vector<std::size_t> order(candidates.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return candidates[a].spacing < candidates[b].spacing;
  });
  const CandidateCloud cloud{&candidates, {}};
  CandidateTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  tree.buildIndex();
  std::vector<char> alive(candidates.size(), 1);
  std::vector<std::size_t> rank(candidates.size());
  for (std::size_t position = 0; position < order.size(); ++position) rank[order[position]] = position;
  std::vector<std::pair<unsigned, double>> found;
  for (std::size_t candidate : order) {
    if (!alive[candidate]) continue;
    const double radius = options.minimum_metric_distance * candidates[candidate].spacing;
    found.clear();
    tree.radiusSearch(candidates[candidate].point.data(), radius * radius, found,
                      nanoflann::SearchParams(32, 0, false));
    for (const auto& [other, squared] : found)
      if (rank[other] > rank[candidate]) alive[other] = 0;
  }

  LayerPoints result;
  for (std::size_t candidate = 0; candidate < candidates.size(); ++candidate) {
    if (!alive[candidate]) continue;
    if (candidates[candidate].on_plane) {
      result.plane.push_back(candidates[candidate].point);
    } else {
      result.volume.push_back(candidates[candidate].point);
    }
  }
  return result;
}

std::vector<Vector3> points_beyond(const std::vector<Vector3>& candidates, const std::vector<Vector3>& near,
                                   const SizeField& size, double ratio) {
  const NearestPoint nearest(near);
  return kept_in_order(candidates, [&](const Vector3& candidate) {
    const double limit = ratio * size(candidate);
    return nearest.squared_distance(candidate) > limit * limit;
  });
}

std::vector<Vector3> points_off_hull(const std::vector<Vector3>& candidates,
                                     const std::vector<Vector3>& points, const std::vector<Triangle>& hull,
                                     double ratio) {
  std::vector<Vector3> nodes;
  std::vector<char> seen(points.size(), 0);
  for (const Triangle& triangle : hull)
    for (Index node : triangle)
      if (!seen[static_cast<std::size_t>(node)]) {
        seen[static_cast<std::size_t>(node)] = 1;
        nodes.push_back(points[static_cast<std::size_t>(node)]);
      }
  const std::vector<Triangle3> triangles = hull_triangles(points, hull);
  HullTree hull_tree(triangles.begin(), triangles.end());
  hull_tree.build();
  hull_tree.accelerate_distance_queries();
  const NearestPoint nearest(std::move(nodes));
  return kept_in_order(candidates, [&](const Vector3& candidate) {
    const double node_squared = nearest.squared_distance(candidate);
    const double surface_squared =
        hull_tree.squared_distance(Kernel::Point_3(candidate.x(), candidate.y(), candidate.z()));
    return surface_squared >= ratio * ratio * node_squared;
  });
}

}  // namespace mixmesh::farfield_detail
