// Planar cap triangulation: CGAL 2D constrained Delaunay triangulation of a closed
// outline, refined by Delaunay refinement (Ruppert/Shewchuk) for a minimum angle and a
// maximum edge, without ever splitting the outline, so that the cap shares exactly the
// outline's nodes with the neighbouring structured patch.

#include <cmath>
#include <limits>
#include <set>
#include <sstream>

#include "mixmesh/core/error.hpp"
#include "mixmesh/surface/wing_surface.hpp"
#include "surface/constrained_mesher.hpp"

namespace mixmesh {
namespace {

using namespace surface_detail;
using Point = Kernel::Point_2;

}  // namespace

std::vector<Index> triangulate_planar_cap(std::vector<Vector3>& points, const std::vector<Index>& outline,
                                          const TipCapOptions& options, bool normal_positive_y,
                                          const std::vector<std::array<Vector3, 2>>& inner_edges) {
  if (outline.size() < 3) throw Error("cap outline needs at least three nodes");
  if (!(options.minimum_angle_degrees > 0.0 && options.minimum_angle_degrees <= 20.7)) {
    throw Error(
        "tip minimum_angle must lie in (0, 20.7] degrees (Delaunay refinement terminates below 20.7)");
  }
  const double plane_y = points[static_cast<std::size_t>(outline.front())].y();
  Triangulation triangulation;
  std::vector<Triangulation::Vertex_handle> handles;
  handles.reserve(outline.size());
  double longest = 0.0;
  for (std::size_t k = 0; k < outline.size(); ++k) {
    const Vector3& point = points[static_cast<std::size_t>(outline[k])];
    auto handle = triangulation.insert(Point(point.x(), point.z()));
    handle->info() = outline[k];
    handles.push_back(handle);
    longest = std::max(longest,
                       (point - points[static_cast<std::size_t>(outline[(k + 1) % outline.size()])]).norm());
  }
  for (std::size_t k = 0; k < handles.size(); ++k) {
    triangulation.insert_constraint(handles[k], handles[(k + 1) % handles.size()]);
  }
  if (triangulation.number_of_vertices() != outline.size()) {
    throw Error("cap outline touches or crosses itself (the constrained triangulation has " +
                std::to_string(triangulation.number_of_vertices()) + " vertices for " +
                std::to_string(outline.size()) + " outline nodes)");
  }
  // An end at an outline point finds that point's vertex (insert returns it).
  for (const auto& [from, to] : inner_edges)
    triangulation.insert_constraint(triangulation.insert(Point(from.x(), from.z())),
                                    triangulation.insert(Point(to.x(), to.z())));
  const double angle = options.minimum_angle_degrees * M_PI / 180.0;
  const double size = options.maximum_edge > 0.0 ? options.maximum_edge : longest;
  Mesher mesher(triangulation, Criteria(std::sin(angle) * std::sin(angle), size));
  // Without seeds the domain is the inside of the constraints; clear_seeds() also sets
  // the seed mark, which CGAL's constructor leaves uninitialised.
  mesher.clear_seeds();
  mesher.refine_mesh();

  // New vertices are interior points of the cap.
  const std::set<Triangulation::Vertex_handle> outline_handles(handles.begin(), handles.end());
  for (auto vertex = triangulation.finite_vertices_begin(); vertex != triangulation.finite_vertices_end();
       ++vertex) {
    if (outline_handles.count(vertex) != 0) continue;
    // (An inner edge's end outside the outline touches no face of the cap.)
    bool in_cap = false;
    auto face = triangulation.incident_faces(vertex), end = face;
    do in_cap |= !triangulation.is_infinite(face) && face->is_in_domain();
    while (++face != end);
    if (!in_cap) continue;
    vertex->info() = static_cast<Index>(points.size());
    points.emplace_back(vertex->point().x(), plane_y, vertex->point().y());
  }
  std::vector<Index> triangles;
  for (auto face = triangulation.finite_faces_begin(); face != triangulation.finite_faces_end(); ++face) {
    if (!face->is_in_domain()) continue;
    const Index a = face->vertex(0)->info(), b = face->vertex(1)->info(), c = face->vertex(2)->info();
    // CGAL's faces run counter-clockwise in (x, z), whose right-hand normal is -y.
    if (normal_positive_y) {
      triangles.insert(triangles.end(), {a, c, b});
    } else {
      triangles.insert(triangles.end(), {a, b, c});
    }
  }
  // Every outline edge must still be an edge: the outline was not split.
  for (std::size_t k = 0; k < handles.size(); ++k) {
    Triangulation::Face_handle face;
    int index = 0;
    if (!triangulation.is_edge(handles[k], handles[(k + 1) % handles.size()], face, index)) {
      throw Error("cap triangulation split the outline between nodes " + std::to_string(outline[k]) +
                  " and " + std::to_string(outline[(k + 1) % outline.size()]));
    }
  }
  return triangles;
}

void round_cap(std::vector<Vector3>& points, const std::vector<Index>& outline, std::size_t first_interior,
               bool towards_positive_y) {
  const double direction = towards_positive_y ? 1.0 : -1.0;
  for (std::size_t node = first_interior; node < points.size(); ++node) {
    Vector3& point = points[node];
    // The outline crossings of the vertical line through the point nearest above and below.
    double above = std::numeric_limits<double>::infinity();
    double below = -std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < outline.size(); ++k) {
      const Vector3& a = points[static_cast<std::size_t>(outline[k])];
      const Vector3& b = points[static_cast<std::size_t>(outline[(k + 1) % outline.size()])];
      if ((a.x() - point.x()) * (b.x() - point.x()) > 0.0 || a.x() == b.x()) continue;
      const double z = a.z() + (point.x() - a.x()) / (b.x() - a.x()) * (b.z() - a.z());
      if (z >= point.z()) above = std::min(above, z);
      if (z <= point.z()) below = std::max(below, z);
    }
    if (!std::isfinite(above) || !std::isfinite(below)) continue;  // cannot happen inside the outline
    const double centre = 0.5 * (above + below);
    const double half = 0.5 * (above - below);
    const double offset = point.z() - centre;
    point.y() += direction * std::sqrt(std::max(0.0, half * half - offset * offset));
  }
}

}  // namespace mixmesh
