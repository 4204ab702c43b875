// The outer boundary (sphere or box) and the symmetry-plane triangulation.

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_criteria_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_no_edge_refinement_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>
#include <map>
#include <queue>

#include "farfield/farfield_parts.hpp"
#include "mixmesh/core/error.hpp"

namespace mixmesh::farfield_detail {

double SizeField::operator()(const Vector3& point) const {
  double size = maximum;
  for (std::size_t source = 0; source < sources.size(); ++source)
    size = std::min(size, sizes[source] + gradient * (point - sources[source]).norm());
  return size;
}

namespace {

// Orients a triangle so its normal points away from `centre` (outward on a convex
// outer boundary).
Triangle outward(Triangle triangle, const std::vector<Vector3>& points, const Vector3& centre) {
  const Vector3& a = points[static_cast<std::size_t>(triangle[0])];
  const Vector3& b = points[static_cast<std::size_t>(triangle[1])];
  const Vector3& c = points[static_cast<std::size_t>(triangle[2])];
  if ((b - a).cross(c - a).dot((a + b + c) / 3.0 - centre) < 0.0) std::swap(triangle[1], triangle[2]);
  return triangle;
}

// Rings of constant polar angle θ about the y axis (θ = 0 at +y), each ring's points
// spaced ≈ size apart, neighbouring rings zipped together by azimuth.
OuterBoundary sphere(const Vector3& centre, double radius, double size, bool half,
                     std::vector<Vector3>& points) {
  OuterBoundary result;
  const double last_angle = half ? M_PI / 2 : M_PI;
  const int ring_count = std::max(2, static_cast<int>(std::ceil(last_angle * radius / size)));
  std::vector<std::vector<Index>> rings;
  std::vector<double> offsets;
  for (int ring = 0; ring <= ring_count; ++ring) {
    const double polar = last_angle * ring / ring_count;
    const double circumference = 2 * M_PI * radius * std::sin(polar);
    const bool pole = ring == 0 || (!half && ring == ring_count);
    const int count = pole ? 1 : std::max(3, static_cast<int>(std::lround(circumference / size)));
    const double offset = (ring % 2) * M_PI / count;  // staggered rings give better triangles
    std::vector<Index> indices;
    for (int slot = 0; slot < count; ++slot) {
      const double azimuth = offset + 2 * M_PI * slot / count;
      Vector3 point = centre + radius * Vector3(std::sin(polar) * std::cos(azimuth), std::cos(polar),
                                                std::sin(polar) * std::sin(azimuth));
      if (half && ring == ring_count) point.y() = centre.y();  // exactly on the plane
      indices.push_back(static_cast<Index>(points.size()));
      points.push_back(point);
    }
    rings.push_back(indices);
    offsets.push_back(offset);
  }
  for (std::size_t ring = 0; ring + 1 < rings.size(); ++ring) {
    const auto& upper = rings[ring];
    const auto& lower = rings[ring + 1];
    const std::size_t a = upper.size(), b = lower.size();
    auto angle = [](double offset, std::size_t slot, std::size_t count) {
      return offset + 2 * M_PI * static_cast<double>(slot) / static_cast<double>(count);
    };
    std::size_t i = 0, j = 0;
    while (i < a || j < b) {
      // A pole (one point) only fans; otherwise advance the ring whose next azimuth comes first.
      const bool advance_upper =
          b == 1 ||
          (a > 1 &&
           (j == b || (i < a && angle(offsets[ring], i + 1, a) < angle(offsets[ring + 1], j + 1, b))));
      if (advance_upper) {
        result.triangles.push_back(outward({upper[i % a], upper[(i + 1) % a], lower[j % b]}, points, centre));
        ++i;
        if (b == 1 && i == a) j = b;
      } else {
        result.triangles.push_back(outward({upper[i % a], lower[j % b], lower[(j + 1) % b]}, points, centre));
        ++j;
        if (a == 1 && j == b) i = a;
      }
    }
  }
  if (half) result.rim = rings.back();
  return result;
}

// The surface of a lattice box; half boxes leave out the face y = centre.y.
OuterBoundary box(const Vector3& centre, double radius, double size, bool half,
                  std::vector<Vector3>& points) {
  OuterBoundary result;
  const Vector3 low(centre.x() - radius, half ? centre.y() : centre.y() - radius, centre.z() - radius);
  const Vector3 extent(2 * radius, half ? radius : 2 * radius, 2 * radius);
  std::array<int, 3> cells{};
  for (int axis = 0; axis < 3; ++axis)
    cells[axis] = std::max(1, static_cast<int>(std::ceil(extent(axis) / size)));
  std::map<std::array<int, 3>, Index> lattice;
  auto node = [&](std::array<int, 3> at) {
    const auto found = lattice.find(at);
    if (found != lattice.end()) return found->second;
    Vector3 point;
    for (int axis = 0; axis < 3; ++axis) point(axis) = low(axis) + extent(axis) * at[axis] / cells[axis];
    const Index created = static_cast<Index>(points.size());
    points.push_back(point);
    lattice.emplace(at, created);
    return created;
  };
  const Vector3 middle = low + 0.5 * extent;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      if (half && axis == 1 && side == 0) continue;  // the symmetry plane
      for (int i = 0; i < cells[u]; ++i)
        for (int j = 0; j < cells[v]; ++j) {
          std::array<Index, 4> quad{};
          const std::array<std::array<int, 2>, 4> corners = {
              {{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}}};
          for (int corner = 0; corner < 4; ++corner) {
            std::array<int, 3> at{};
            at[axis] = side * cells[axis];
            at[u] = corners[corner][0];
            at[v] = corners[corner][1];
            quad[corner] = node(at);
          }
          result.triangles.push_back(outward({quad[0], quad[1], quad[2]}, points, middle));
          result.triangles.push_back(outward({quad[0], quad[2], quad[3]}, points, middle));
        }
    }
  }
  if (half) {
    // Walk the rectangle y = low.y: along x at z = 0, along z at x = max, back.
    const int nx = cells[0], nz = cells[2];
    for (int i = 0; i < nx; ++i) result.rim.push_back(node({i, 0, 0}));
    for (int k = 0; k < nz; ++k) result.rim.push_back(node({nx, 0, k}));
    for (int i = nx; i > 0; --i) result.rim.push_back(node({i, 0, nz}));
    for (int k = nz; k > 0; --k) result.rim.push_back(node({0, 0, k}));
  }
  return result;
}

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Delaunay_mesh_vertex_base_2<Kernel>;
using FaceBase = CGAL::Delaunay_mesh_face_base_2<Kernel>;
using Structure = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Triangulation =
    CGAL::Constrained_Delaunay_triangulation_2<Kernel, Structure, CGAL::Exact_predicates_tag>;
using Point2 = Kernel::Point_2;

// Delaunay refinement criteria with a size that varies in the plane: a face is
// imperatively bad when its longest edge exceeds the size field at its centroid.
class GradedCriteria : public CGAL::Delaunay_mesh_criteria_2<Triangulation> {
  using Base = CGAL::Delaunay_mesh_criteria_2<Triangulation>;

 public:
  // first: squared minimum sine, second: (longest edge / size)².
  struct Quality : public std::pair<double, double> {
    Quality() = default;
    Quality(double sine, double size) : std::pair<double, double>(sine, size) {}
    double sine() const { return first; }
    double size() const { return second; }
    bool operator<(const Quality& other) const {  // true: *this is refined first
      if (size() > 1 || other.size() > 1) return size() > other.size();
      return sine() < other.sine();
    }
  };

  class Is_bad : public Base::Is_bad {
   public:
    Is_bad(double bound, const Kernel& traits, const SizeField* size, double plane_y)
        : Base::Is_bad(bound, traits), size_(size), plane_y_(plane_y) {}
    CGAL::Mesh_2::Face_badness operator()(const Quality& quality) const {
      if (quality.size() > 1) return CGAL::Mesh_2::IMPERATIVELY_BAD;
      return quality.sine() < this->B ? CGAL::Mesh_2::BAD : CGAL::Mesh_2::NOT_BAD;
    }
    CGAL::Mesh_2::Face_badness operator()(const Triangulation::Face_handle& face, Quality& quality) const {
      const Point2& a = face->vertex(0)->point();
      const Point2& b = face->vertex(1)->point();
      const Point2& c = face->vertex(2)->point();
      std::array<double, 3> lengths = {CGAL::squared_distance(b, c), CGAL::squared_distance(c, a),
                                       CGAL::squared_distance(a, b)};
      std::sort(lengths.begin(), lengths.end());
      const Vector3 centroid((a.x() + b.x() + c.x()) / 3, plane_y_, (a.y() + b.y() + c.y()) / 3);
      const double target = (*size_)(centroid);
      quality.second = lengths[2] / (target * target);
      const double area2 = 2 * CGAL::area(a, b, c);
      quality.first = area2 * area2 / (lengths[2] * lengths[1]);
      return (*this)(quality);
    }

   private:
    const SizeField* size_;
    double plane_y_;
  };

  GradedCriteria(double bound, const SizeField& size, double plane_y)
      : Base(bound), size_(&size), plane_y_(plane_y) {}
  Is_bad is_bad_object() const { return Is_bad(this->bound(), this->traits, size_, plane_y_); }

 private:
  const SizeField* size_;
  double plane_y_;
};

}  // namespace

OuterBoundary outer_boundary(FarFieldShape shape, const Vector3& centre, double radius, double size,
                             bool half, std::vector<Vector3>& points) {
  return shape == FarFieldShape::sphere ? sphere(centre, radius, size, half, points)
                                        : box(centre, radius, size, half, points);
}

std::vector<Triangle> symmetry_plane(double plane_y, const std::vector<Index>& rim,
                                     const std::vector<std::array<Index, 2>>& footprint,
                                     const std::vector<Vector3>& extra_points, const SizeField& size,
                                     double minimum_angle_degrees, std::vector<Vector3>& points) {
  // Plane coordinates (x, z); every existing point is found again by its exact coordinates.
  Triangulation triangulation;
  std::map<std::pair<double, double>, Index> existing;
  std::map<Index, Triangulation::Vertex_handle> handles;
  auto insert = [&](Index node) {
    const Vector3& point = points[static_cast<std::size_t>(node)];
    const auto handle = triangulation.insert(Point2(point.x(), point.z()));
    existing[{point.x(), point.z()}] = node;
    handles[node] = handle;
    return handle;
  };
  for (std::size_t corner = 0; corner < rim.size(); ++corner)
    triangulation.insert_constraint(insert(rim[corner]), insert(rim[(corner + 1) % rim.size()]));
  for (const auto& edge : footprint) triangulation.insert_constraint(insert(edge[0]), insert(edge[1]));
  for (const Vector3& point : extra_points) triangulation.insert(Point2(point.x(), point.z()));

  // Nesting depth across constraints from the infinite face: 0 outside the rim, 1 in
  // the domain, 2 inside a footprint. Seeds mark the footprint interiors as holes.
  std::map<Triangulation::Face_handle, int> depth;
  std::queue<Triangulation::Face_handle> current;
  current.push(triangulation.infinite_face());
  std::list<Point2> seeds;
  for (int level = 0; !current.empty(); ++level) {
    std::queue<Triangulation::Face_handle> across;  // behind a constraint: the next level
    while (!current.empty()) {
      const auto face = current.front();
      current.pop();
      if (depth.count(face)) continue;
      depth[face] = level;
      if (level == 2 && !triangulation.is_infinite(face))
        seeds.push_back(
            CGAL::centroid(face->vertex(0)->point(), face->vertex(1)->point(), face->vertex(2)->point()));
      for (int side = 0; side < 3; ++side) {
        const auto neighbour = face->neighbor(side);
        if (!depth.count(neighbour)) (face->is_constrained(side) ? across : current).push(neighbour);
      }
    }
    current = std::move(across);
  }

  const double sine = std::sin(minimum_angle_degrees * M_PI / 180.0);
  CGAL::Delaunay_mesher_no_edge_refinement_2<Triangulation, GradedCriteria> mesher(
      triangulation, GradedCriteria(sine * sine, size, plane_y));
  mesher.set_seeds(seeds.begin(), seeds.end(), false);
  mesher.refine_mesh();

  for (const auto& edge : footprint)
    if (!triangulation.is_edge(handles[edge[0]], handles[edge[1]])) {
      const Vector3 where(points[static_cast<std::size_t>(edge[0])].x(), plane_y,
                          points[static_cast<std::size_t>(edge[0])].z());
      throw HullIntersectionError(
          "farfield: the hull footprint on the symmetry plane crosses itself or the far-field edge near " +
              point_text(where),
          where);
    }

  std::vector<Triangle> triangles;
  for (auto face = triangulation.finite_faces_begin(); face != triangulation.finite_faces_end(); ++face) {
    if (!face->is_in_domain()) continue;
    Triangle triangle{};
    for (int corner = 0; corner < 3; ++corner) {
      const Point2& point = face->vertex(corner)->point();
      const auto found = existing.find({point.x(), point.y()});
      if (found != existing.end()) {
        triangle[static_cast<std::size_t>(corner)] = found->second;
        continue;
      }
      const Index created = static_cast<Index>(points.size());
      points.emplace_back(point.x(), plane_y, point.y());
      existing[{point.x(), point.y()}] = created;
      triangle[static_cast<std::size_t>(corner)] = created;
    }
    triangles.push_back(triangle);
  }
  return triangles;
}

}  // namespace mixmesh::farfield_detail
