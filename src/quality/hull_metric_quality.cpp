// A mesh file holds no metric, but it holds the cells the far field was matched to: the
// interface's tetrahedra on split outer cells, the caps' pyramids and the prisms whose
// tops face the far field. Each far-field tetrahedron that shares a triangle with one of
// them is judged in that cell's metric (Wild eq. 11-12 by its type: the Riemannian
// invariant of a tetrahedron, the affine invariant of a pyramid or prism), so a
// tetrahedron stretched as the cell beneath it is stretched measures as regular.
#include "hull_metric_quality.hpp"

#include <algorithm>
#include <cmath>

#include "mixmesh/core/error.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/metric/metric.hpp"

namespace mixmesh::quality_detail {

namespace {

// The interface's split points: points that are the apex of two or more pyramids and
// are used otherwise by tetrahedra only. A cap's apex tops one pyramid; a split cell has
// a pyramid on every quad that is not outer, so one with its top and a side on the hull
// has two (a prism) or four (a hexahedron). A prism with two sides outer as well, whose
// one pyramid looks like a cap, is the case this misses.
std::vector<char> split_points(const MixedMesh& mesh) {
  std::vector<int> apexes(mesh.points.size(), 0);
  std::vector<char> other_use(mesh.points.size(), 0);
  for (CellType type : {CellType::prism, CellType::hexahedron})
    for (Index node : mesh.block(type).nodes) other_use[static_cast<std::size_t>(node)] = 1;
  for (std::size_t pyramid = 0; pyramid < mesh.cell_count(CellType::pyramid); ++pyramid) {
    const Index* nodes = mesh.cell(CellType::pyramid, pyramid);
    for (int corner = 0; corner < 4; ++corner) other_use[static_cast<std::size_t>(nodes[corner])] = 1;
    ++apexes[static_cast<std::size_t>(nodes[4])];
  }
  std::vector<char> split(mesh.points.size(), 0);
  for (std::size_t point = 0; point < split.size(); ++point)
    split[point] = apexes[point] >= 2 && !other_use[point];
  return split;
}

// 1 for the regular tetrahedron in the metric, towards 0 as it flattens:
// 12 (3 V)^(2/3) / (sum of the squared edge lengths), all in the metric.
double mean_ratio(const std::array<Vector3, 4>& corners) {
  const double volume = std::abs(tetrahedron_volume6(corners[0], corners[1], corners[2], corners[3])) / 6.0;
  double squares = 0.0;
  for (int a = 0; a < 4; ++a)
    for (int b = a + 1; b < 4; ++b) squares += (corners[b] - corners[a]).squaredNorm();
  return squares > 0.0 ? 12.0 * std::cbrt(9.0 * volume * volume) / squares : std::nan("");
}

}  // namespace

HullMetricValues hull_metric_values(const MixedMesh& mesh, const FaceConnectivity& faces) {
  HullMetricValues values;
  if (mesh.cell_count(CellType::tetrahedron) == 0) return values;
  const std::vector<char> split = split_points(mesh);
  auto interface_tetrahedron = [&](Index cell) {
    const Index* nodes = mesh.cell(CellType::tetrahedron, static_cast<std::size_t>(cell));
    return std::any_of(nodes, nodes + 4, [&](Index node) { return split[static_cast<std::size_t>(node)] != 0; });
  };
  for (const auto& pair : faces.interior) {
    for (int side = 0; side < 2; ++side) {
      const CellFace& far = pair[static_cast<std::size_t>(side)];
      const CellFace& beneath = pair[static_cast<std::size_t>(1 - side)];
      if (far.type != CellType::tetrahedron || interface_tetrahedron(far.cell)) continue;
      if (beneath.type == CellType::hexahedron) continue;
      if (beneath.type == CellType::tetrahedron && !interface_tetrahedron(beneath.cell)) continue;
      Matrix3 metric;
      try {
        metric = cell_metric(beneath.type, mesh.points, mesh.cell(beneath.type, static_cast<std::size_t>(beneath.cell)));
      } catch (const Error&) {
        continue;  // a degenerate cell beneath, which the validity checks name
      }
      const Matrix3 transform = metric_transform(metric);
      const Index* nodes = mesh.cell(CellType::tetrahedron, static_cast<std::size_t>(far.cell));
      std::array<Vector3, 4> mapped;
      for (int corner = 0; corner < 4; ++corner)
        mapped[static_cast<std::size_t>(corner)] = transform * mesh.points[static_cast<std::size_t>(nodes[corner])];
      for (int a = 0; a < 4; ++a)
        for (int b = a + 1; b < 4; ++b)
          values.edge_lengths.push_back(
              (mapped[static_cast<std::size_t>(b)] - mapped[static_cast<std::size_t>(a)]).norm());
      values.shapes.push_back(mean_ratio(mapped));
    }
  }
  return values;
}

}  // namespace mixmesh::quality_detail
