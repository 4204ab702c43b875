#include "layer_checks.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <utility>

#include "junction.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"

namespace mixmesh::march_detail {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, int>;

Kernel::Point_3 point(const Vector3& x) {
  return {x.x(), x.y(), x.z()};
}

// A quad is tested as its two triangles (0, 1, 2) and (0, 2, 3).
int triangles_of(const Front& front, int face, const std::vector<Vector3>& top,
                 Kernel::Triangle_3* triangles) {
  const FrontFace& f = front.faces[static_cast<std::size_t>(face)];
  auto at = [&](int k) {
    return point(top[static_cast<std::size_t>(f.columns[static_cast<std::size_t>(k)])]);
  };
  triangles[0] = Kernel::Triangle_3(at(0), at(1), at(2));
  if (f.corner_count == 3) return 1;
  triangles[1] = Kernel::Triangle_3(at(0), at(2), at(3));
  return 2;
}

}  // namespace

CellType swept_cell(const Front& front, int face, const std::vector<Vector3>& bottom,
                    const std::vector<Vector3>& top, std::vector<Vector3>& points) {
  const FrontFace& f = front.faces[static_cast<std::size_t>(face)];
  auto column = [&](int k) { return static_cast<std::size_t>(f.columns[static_cast<std::size_t>(k)]); };
  points.clear();
  if (f.wrap && bottom[column(0)] == bottom[column(3)]) {
    // The first cell of a wrap face: the prism of layer_mesh.cpp, add_swept_cell.
    constexpr std::array<std::pair<int, int>, 6> corners{{{0, 0}, {0, 1}, {3, 1}, {1, 0}, {1, 1}, {2, 1}}};
    for (const auto& [k, level] : corners) points.push_back((level == 0 ? bottom : top)[column(k)]);
    return CellType::prism;
  }
  if (f.corner_count == 4) {
    for (int k = 0; k < 4; ++k) points.push_back(bottom[column(k)]);
    for (int k = 0; k < 4; ++k) points.push_back(top[column(k)]);
    return CellType::hexahedron;
  }
  // VTK wedge: the bottom triangle runs clockwise seen from the top, so (a, c, b).
  for (int k : {0, 2, 1}) points.push_back(bottom[column(k)]);
  for (int k : {0, 2, 1}) points.push_back(top[column(k)]);
  return CellType::prism;
}

std::vector<int> invalid_cells(const Front& front, const std::vector<int>& faces,
                               const std::vector<Vector3>& bottom, const std::vector<Vector3>& top) {
  std::vector<char> bad(faces.size(), 0);
  tbb::parallel_for(std::size_t{0}, faces.size(), [&](std::size_t n) {
    const FrontFace& f = front.faces[static_cast<std::size_t>(faces[n])];
    if (f.split &&
        bottom[static_cast<std::size_t>(f.columns[0])] == bottom[static_cast<std::size_t>(f.columns[3])]) {
      // The first cell of a split face: its cut pieces.
      const Junction* junction = junction_of(front, faces[n]);
      bad[n] = junction == nullptr || !junction_valid(junction_cells(front, *junction, bottom, top));
      return;
    }
    std::vector<Vector3> points;
    const CellType type = swept_cell(front, faces[n], bottom, top, points);
    static constexpr std::array<Index, 8> local{0, 1, 2, 3, 4, 5, 6, 7};
    bad[n] = !cell_shape(type, points, local.data()).valid();
  });
  std::vector<int> result;
  for (std::size_t n = 0; n < faces.size(); ++n)
    if (bad[n]) result.push_back(faces[n]);
  return result;
}

std::vector<int> intersecting_faces(const Front& front, const std::vector<int>& faces,
                                    const std::vector<Vector3>& bottom, const std::vector<Vector3>& top) {
  // Boxes of the faces where the layer was (bottom, info 2 f) and where it goes
  // (top, info 2 f + 1), and of the marching segments of their columns.
  std::vector<Box> face_boxes, top_boxes, segments;
  face_boxes.reserve(2 * faces.size());
  std::vector<char> column_seen(bottom.size(), 0);
  for (int face : faces) {
    const FrontFace& f = front.faces[static_cast<std::size_t>(face)];
    CGAL::Bbox_3 low, high;
    for (int k = 0; k < f.corner_count; ++k) {
      const auto column = static_cast<std::size_t>(f.columns[static_cast<std::size_t>(k)]);
      low += point(bottom[column]).bbox();
      high += point(top[column]).bbox();
      if (column_seen[column]) continue;
      column_seen[column] = 1;
      segments.emplace_back(point(bottom[column]).bbox() + point(top[column]).bbox(),
                            static_cast<int>(column));
    }
    face_boxes.emplace_back(low, 2 * face);
    top_boxes.emplace_back(high, 2 * face + 1);
  }
  face_boxes.insert(face_boxes.end(), top_boxes.begin(), top_boxes.end());
  constexpr std::ptrdiff_t cutoff = 200;  // brute force below this many boxes: faster here

  std::vector<char> hit(front.faces.size(), 0);
  auto report_faces = [&](const Box& a, const Box& b) {
    const FrontFace& first = front.faces[static_cast<std::size_t>(a.info() / 2)];
    const FrontFace& second = front.faces[static_cast<std::size_t>(b.info() / 2)];
    for (int i = 0; i < first.corner_count; ++i)
      for (int j = 0; j < second.corner_count; ++j)
        if (first.columns[static_cast<std::size_t>(i)] == second.columns[static_cast<std::size_t>(j)]) return;
    Kernel::Triangle_3 left[2], right[2];
    const int left_count = triangles_of(front, a.info() / 2, top, left);
    const int right_count = triangles_of(front, b.info() / 2, top, right);
    for (int i = 0; i < left_count; ++i)
      for (int j = 0; j < right_count; ++j)
        if (!left[i].is_degenerate() && !right[j].is_degenerate() && CGAL::do_intersect(left[i], right[j])) {
          hit[static_cast<std::size_t>(a.info() / 2)] = 1;
          hit[static_cast<std::size_t>(b.info() / 2)] = 1;
          return;
        }
  };

  // New faces against new faces (report_faces), and marching segments against the old
  // and the new faces: two fronts that pass each other within one step have tops that
  // never meet, but a step crosses a face.
  std::vector<char> crossed(bottom.size(), 0), stepped_on(front.faces.size(), 0);
  auto report_segment = [&](const Box& segment_box, const Box& face_box) {
    // Skip the faces around the segment's own surface node (on either side of a
    // sheet, where two lines start from one point).
    const int face = face_box.info() / 2;
    const FrontFace& f = front.faces[static_cast<std::size_t>(face)];
    const auto column = static_cast<std::size_t>(segment_box.info());
    const Index node = front.column_node[column];
    for (int k = 0; k < f.corner_count; ++k)
      if (front.column_node[static_cast<std::size_t>(f.columns[static_cast<std::size_t>(k)])] == node) return;
    const Kernel::Segment_3 segment(point(bottom[column]), point(top[column]));
    if (segment.is_degenerate()) return;
    Kernel::Triangle_3 triangles[2];
    const int count = triangles_of(front, face, face_box.info() % 2 ? top : bottom, triangles);
    for (int i = 0; i < count; ++i)
      if (!triangles[i].is_degenerate() && CGAL::do_intersect(segment, triangles[i])) {
        stepped_on[static_cast<std::size_t>(face)] = 1;
        crossed[column] = 1;
        return;
      }
  };
  // The two searches write separate flags, so they run side by side.
  tbb::parallel_invoke(
      [&] { CGAL::box_self_intersection_d(top_boxes.begin(), top_boxes.end(), report_faces, cutoff); },
      [&] {
        CGAL::box_intersection_d(segments.begin(), segments.end(), face_boxes.begin(), face_boxes.end(),
                                 report_segment, cutoff);
      });
  for (std::size_t face = 0; face < hit.size(); ++face) hit[face] |= stepped_on[face];
  for (int face : faces) {
    const FrontFace& f = front.faces[static_cast<std::size_t>(face)];
    for (int k = 0; k < f.corner_count; ++k)
      if (crossed[static_cast<std::size_t>(f.columns[static_cast<std::size_t>(k)])])
        hit[static_cast<std::size_t>(face)] = 1;
  }
  std::vector<int> result;
  for (int face : faces)
    if (hit[static_cast<std::size_t>(face)]) result.push_back(face);
  return result;
}

}  // namespace mixmesh::march_detail
