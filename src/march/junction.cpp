#include "junction.hpp"

#include <algorithm>
#include <array>

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

JunctionCells junction_cells(const Front& front, const Junction& junction, const std::vector<Vector3>& bottom,
                             const std::vector<Vector3>& top) {
  const FrontFace& face = front.faces[static_cast<std::size_t>(junction.face)];
  auto column = [&](int k) { return static_cast<std::size_t>(face.columns[static_cast<std::size_t>(k)]); };
  JunctionCells result;
  std::vector<Vector3>& points = result.points;
  points = {bottom[column(0)], bottom[column(1)], bottom[column(2)], top[column(0)],
            top[column(1)],    top[column(2)],    top[column(3)],    Vector3::Zero()};

  // The cut cell's faces, outward: four quads (pyramid bases) and two triangles. The
  // pieces are cones from the centre over them, so a centre outside the cell gives an
  // inverted piece (never turned round to hide it).
  const std::vector<std::vector<int>> quads = {{wall_corner, wall_after, top_a, top_after},
                                               {wall_after, wall_before, top_b, top_a},
                                               {wall_before, wall_corner, top_before, top_b},
                                               {top_after, top_a, top_b, top_before}};
  const std::vector<std::vector<int>> triangles = {{wall_corner, wall_before, wall_after},
                                                   {wall_corner, top_after, top_before}};
  auto cut = [&](std::vector<JunctionCell>& cells) {
    cells.clear();
    // Pyramid face 0 is (0, 3, 2, 1) and tetrahedron face 0 is (0, 2, 1), outward.
    for (const auto& quad : quads)
      cells.push_back({CellType::pyramid, {quad[0], quad[3], quad[2], quad[1], centre}});
    for (const auto& triangle : triangles)
      cells.push_back({CellType::tetrahedron, {triangle[0], triangle[2], triangle[1], centre}});
  };
  // The centre: the point of the cell (barycentric in the wall triangle, a fraction of
  // the way up) whose worst piece is best. The cell is a thin slab with its split
  // corner at one end, so the best point is near that corner; the mean of the nodes
  // gives needle tetrahedra there.
  const Vector3 up = (points[top_after] + points[top_a] + points[top_b] + points[top_before]) / 4.0 -
                     (points[wall_corner] + points[wall_after] + points[wall_before]) / 3.0;
  auto place = [&](double u, double v, double w) {
    points[centre] = points[wall_corner] + u * (points[wall_after] - points[wall_corner]) +
                     v * (points[wall_before] - points[wall_corner]) + w * up;
  };
  auto worst = [&](double u, double v, double w) {
    place(u, v, w);
    cut(result.cells);
    double quality = 1.0;
    for (const JunctionCell& cell : result.cells) {
      std::vector<Index> indices(cell.nodes.begin(), cell.nodes.end());
      const CellShape shape = cell_shape(cell.type, points, indices.data());
      quality = std::min(quality, shape.valid() ? shape.min_corner_jacobian : -1.0);
    }
    return quality;
  };
  std::array<double, 3> best{1.0 / 3.0, 1.0 / 3.0, 0.5};
  double best_quality = -2.0;
  for (double u : {1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 3e-2, 0.1, 0.2, 1.0 / 3.0})
    for (double v : {1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 3e-2, 0.1, 0.2, 1.0 / 3.0})
      for (double w : {0.2, 0.35, 0.5, 0.65, 0.8}) {
        const double quality = worst(u, v, w);
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
          const double quality = worst(trial[0], trial[1], trial[2]);
          if (quality > best_quality) {
            best_quality = quality;
            best = trial;
            improved = true;
          }
        }
    }
  }
  place(best[0], best[1], best[2]);
  cut(result.cells);
  return result;
}

bool junction_valid(const JunctionCells& cells) {
  return std::all_of(cells.cells.begin(), cells.cells.end(), [&](const JunctionCell& cell) {
    std::vector<Index> indices(cell.nodes.begin(), cell.nodes.end());
    return cell_shape(cell.type, cells.points, indices.data()).valid();
  });
}

}  // namespace mixmesh::march_detail
