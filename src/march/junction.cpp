#include "junction.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "mixmesh/mesh/cell_geometry.hpp"

namespace mixmesh::march_detail {

std::vector<int> junction_faces(const Front& front, const Junction& junction) {
  const FrontFace& split = front.faces[static_cast<std::size_t>(junction.face)];
  std::vector<int> faces{junction.face};
  for (int end : {0, 1}) {
    const int line = split.columns[end == 0 ? 0 : 3];
    const int sheet = junction.sheet[static_cast<std::size_t>(end)];
    for (int face : front.column_faces[static_cast<std::size_t>(line)]) {
      const auto& columns = front.faces[static_cast<std::size_t>(face)].columns;
      if (face != junction.face && std::find(columns.begin(), columns.end(), sheet) != columns.end())
        faces.push_back(face);
    }
  }
  return faces;
}

const Junction* junction_of(const Front& front, int face) {
  for (const Junction& junction : front.junctions)
    if (junction.face == face) return &junction;
  return nullptr;
}

namespace {

// The stack's faces, outward: per layer the sides over the split face's edges 0 -> 1,
// 1 -> 2 and 2 -> 3 and (above layer 0) 3 -> 0, then the top; the triangles are the wall
// triangle and the side over edge 3 -> 0 on layer 0, where its two lines start at t.
void stack_faces(int layers, std::vector<std::array<int, 4>>& quads,
                 std::vector<std::array<int, 3>>& triangles) {
  quads.clear();
  for (int layer = 0; layer < layers; ++layer)
    for (int corner = 0; corner < 4; ++corner) {
      if (layer == 0 && corner == 3) continue;
      const int next = (corner + 1) % 4;
      quads.push_back({stack_point(layer, corner), stack_point(layer, next), stack_point(layer + 1, next),
                       stack_point(layer + 1, corner)});
    }
  quads.push_back(
      {stack_point(layers, 0), stack_point(layers, 1), stack_point(layers, 2), stack_point(layers, 3)});
  triangles = {{stack_point(0, 0), stack_point(0, 2), stack_point(0, 1)},
               {stack_point(0, 0), stack_point(1, 0), stack_point(1, 3)}};
}

// A piece's node numbers as cell_shape takes them, without a heap allocation: the search
// below weighs every piece hundreds of times.
std::array<Index, 5> piece_nodes(const JunctionCell& cell) {
  std::array<Index, 5> nodes{};
  std::copy(cell.nodes.begin(), cell.nodes.end(), nodes.begin());
  return nodes;
}

double piece_quality(const JunctionCell& cell, const std::vector<Vector3>& points) {
  const std::array<Index, 5> indices = piece_nodes(cell);
  const CellShape shape = cell_shape(cell.type, points, indices.data());
  if (!shape.valid()) return -1.0;
  if (cell.type != CellType::tetrahedron) return shape.min_corner_jacobian;
  const double largest = largest_dihedral_degrees(points[indices[0]], points[indices[1]], points[indices[2]],
                                                  points[indices[3]]);
  return std::sin((180.0 - largest) * std::acos(-1.0) / 180.0);
}

}  // namespace

JunctionCells junction_cells(const JunctionLevels& levels) {
  const int layers = static_cast<int>(levels.size()) - 1;
  JunctionCells result;
  std::vector<Vector3>& points = result.points;
  for (const auto& level : levels) points.insert(points.end(), level.begin(), level.end());
  points.push_back(Vector3::Zero());
  const auto centre = static_cast<std::size_t>(result.centre_point());

  // The pieces are cones from the inner point over the stack's faces, so a point
  // outside the stack gives an inverted piece (never turned round to hide it).
  std::vector<std::array<int, 4>> quads;
  std::vector<std::array<int, 3>> triangles;
  stack_faces(layers, quads, triangles);
  const int inner = result.centre_point();
  for (const auto& quad : quads)  // pyramid face 0 is (0, 3, 2, 1), outward
    result.cells.push_back({CellType::pyramid, {quad[0], quad[3], quad[2], quad[1], inner}});
  for (const auto& triangle : triangles)  // tetrahedron face 0 is (0, 2, 1), outward
    result.cells.push_back({CellType::tetrahedron, {triangle[0], triangle[2], triangle[1], inner}});

  // The inner point: barycentric (u, v) in the split face's triangle at a fraction w of
  // the stack's height, following its lines (t the middle of the two lines of corners 0
  // and 3). A first cell alone is a thin slab with its split corner at one end, so the
  // best point is near that corner; the mean of the nodes gives needle pieces there.
  auto place = [&](double u, double v, double w) {
    const double height = w * layers;
    const int below = std::min(static_cast<int>(height), layers - 1);
    const double up = height - below;
    std::array<Vector3, 4> at;
    for (std::size_t c = 0; c < 4; ++c)
      at[c] = (1.0 - up) * levels[static_cast<std::size_t>(below)][c] +
              up * levels[static_cast<std::size_t>(below + 1)][c];
    const Vector3 corner = 0.5 * (at[0] + at[3]);
    points[centre] = corner + u * (at[1] - corner) + v * (at[2] - corner);
  };
  // The worst piece, or any value at most `bound` once a piece falls to it (the search
  // only asks whether a point beats the best so far).
  auto worst = [&](double u, double v, double w, double bound) {
    place(u, v, w);
    double quality = 1.0;
    for (const JunctionCell& cell : result.cells) {
      quality = std::min(quality, piece_quality(cell, points));
      if (quality <= bound) break;
    }
    return quality;
  };
  std::array<double, 3> best{1.0 / 3.0, 1.0 / 3.0, 0.5};
  double best_quality = -2.0;
  for (double u : {1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 3e-2, 0.1, 0.2, 1.0 / 3.0})
    for (double v : {1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 3e-2, 0.1, 0.2, 1.0 / 3.0})
      for (double w : {0.2, 0.35, 0.5, 0.65, 0.8}) {
        const double quality = worst(u, v, w, best_quality);
        if (quality > best_quality) {
          best_quality = quality;
          best = {u, v, w};
        }
      }
  // Compass refinement: relative steps in u and v, absolute in w.
  for (double step = 0.5; step > 1e-3; step *= 0.5) {
    bool improved = true;
    while (improved) {
      improved = false;
      for (int axis = 0; axis < 3; ++axis)
        for (double sign : {-1.0, 1.0}) {
          std::array<double, 3> trial = best;
          const auto a = static_cast<std::size_t>(axis);
          trial[a] = axis < 2 ? trial[a] * (1.0 + sign * step) : trial[a] + sign * 0.25 * step;
          if (trial[0] + trial[1] >= 1.0 || trial[2] <= 0.0 || trial[2] >= 1.0) continue;
          const double quality = worst(trial[0], trial[1], trial[2], best_quality);
          if (quality > best_quality) {
            best_quality = quality;
            best = trial;
            improved = true;
          }
        }
    }
  }
  place(best[0], best[1], best[2]);
  result.quality = best_quality;
  return result;
}

JunctionCells junction_cells(const Front& front, const Junction& junction, const std::vector<Vector3>& bottom,
                             const std::vector<Vector3>& top) {
  const FrontFace& face = front.faces[static_cast<std::size_t>(junction.face)];
  JunctionLevels levels(2);
  for (std::size_t c = 0; c < 4; ++c) {
    const auto column = static_cast<std::size_t>(face.columns[c]);
    levels[0][c] = bottom[column];
    levels[1][c] = top[column];
  }
  return junction_cells(levels);
}

bool junction_valid(const JunctionCells& cells) {
  return std::all_of(cells.cells.begin(), cells.cells.end(), [&](const JunctionCell& cell) {
    const std::array<Index, 5> indices = piece_nodes(cell);
    return cell_shape(cell.type, cells.points, indices.data()).valid();
  });
}

}  // namespace mixmesh::march_detail
