// Layer lines through the interface's split stacks (src/deform/layer_lines.cpp): the
// outermost cells of a column, split about one point with the cells under them, keep
// their side quads, and every node of the column stays on its wall node's line.
#include <gtest/gtest.h>

#include <vector>

#include "deform/dual_mesh.hpp"
#include "deform/layer_lines.hpp"
#include "mixmesh/interface/interface_split.hpp"

namespace mixmesh::deform {
namespace {

// A wall of nx × ny faces 0.5 wide with `layers` hexahedral layers 0.01 thick above it:
// its outer cells are fifty times wider than high, so the interface splits them in
// stacks. node(i, j, k) is number i + (nx + 1) (j + (ny + 1) k).
struct ThinLayers {
  static constexpr int nx = 3, ny = 2, layers = 5;
  static Index node(int i, int j, int k) { return static_cast<Index>(i + (nx + 1) * (j + (ny + 1) * k)); }
  MixedMesh mesh;
  OuterLayer outer;
};

ThinLayers thin_layers() {
  ThinLayers block;
  MixedMesh& mesh = block.mesh;
  mesh.marker_names = {"wall"};
  for (int k = 0; k <= ThinLayers::layers; ++k)
    for (int j = 0; j <= ThinLayers::ny; ++j)
      for (int i = 0; i <= ThinLayers::nx; ++i)
        mesh.points.emplace_back(0.5 * i + 0.003 * k, 0.5 * j, 0.01 * k);
  for (int k = 0; k < ThinLayers::layers; ++k)
    for (int j = 0; j < ThinLayers::ny; ++j)
      for (int i = 0; i < ThinLayers::nx; ++i) {
        const Index cell[8] = {ThinLayers::node(i, j, k),
                               ThinLayers::node(i + 1, j, k),
                               ThinLayers::node(i + 1, j + 1, k),
                               ThinLayers::node(i, j + 1, k),
                               ThinLayers::node(i, j, k + 1),
                               ThinLayers::node(i + 1, j, k + 1),
                               ThinLayers::node(i + 1, j + 1, k + 1),
                               ThinLayers::node(i, j + 1, k + 1)};
        if (k == ThinLayers::layers - 1)
          block.outer.hexahedra.push_back({mesh.cell_count(CellType::hexahedron), 1});
        mesh.add_cell(CellType::hexahedron, cell);
        if (k == 0) {
          const Index wall[4] = {cell[0], cell[3], cell[2], cell[1]};  // outward: down
          mesh.add_face(FaceType::quad, wall, 0);
        }
      }
  return block;
}

void expect_every_column_node_on_its_line(const InterfaceResult& split) {
  const detail::DualMesh dual = detail::build_dual_mesh(split.mesh);
  std::vector<MarkerRole> roles(split.mesh.marker_names.size(), MarkerRole::fixed);
  const detail::LayerLines lines = detail::find_layer_lines(dual, roles, split.mesh.points);
  EXPECT_EQ(lines.conflicts, 0u);
  for (int k = 1; k <= ThinLayers::layers; ++k)
    for (int j = 0; j <= ThinLayers::ny; ++j)
      for (int i = 0; i <= ThinLayers::nx; ++i) {
        const std::size_t node = static_cast<std::size_t>(ThinLayers::node(i, j, k));
        EXPECT_EQ(lines.base[node], ThinLayers::node(i, j, 0)) << "node " << i << " " << j << " " << k;
        EXPECT_EQ(lines.top[node], ThinLayers::node(i, j, ThinLayers::layers))
            << "node " << i << " " << j << " " << k;
      }
  for (Index centre : split.centres) EXPECT_EQ(lines.base[static_cast<std::size_t>(centre)], -1);
}

TEST(DeformSplitStack, ColumnsClimbThroughStacksToTheOuterFace) {
  const ThinLayers block = thin_layers();
  const InterfaceResult split = split_interface(block.mesh, block.outer);
  ASSERT_EQ(split.stacks, static_cast<std::size_t>(ThinLayers::nx * ThinLayers::ny));
  ASSERT_GT(split.stacked_cells, split.stacks);
  expect_every_column_node_on_its_line(split);
}

TEST(DeformSplitStack, ColumnsClimbThroughASplitOuterCellToo) {
  const ThinLayers block = thin_layers();
  InterfaceOptions alone;
  alone.stack_cells = 1;
  const InterfaceResult split = split_interface(block.mesh, block.outer, alone);
  ASSERT_EQ(split.stacks, 0u);
  expect_every_column_node_on_its_line(split);
}

}  // namespace
}  // namespace mixmesh::deform
