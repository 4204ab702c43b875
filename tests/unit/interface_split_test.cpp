#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "interface/cap_clearance.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/interface/interface_split.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/mesh/face_connectivity.hpp"
#include "reference_cells.hpp"

using namespace mixmesh;

namespace {

double total_volume(const MixedMesh& mesh) {
  double volume = 0.0;
  for (CellType type : all_cell_types)
    for (std::size_t cell = 0; cell < mesh.cell_count(type); ++cell)
      volume += signed_volume(type, mesh.points, mesh.cell(type, cell));
  return volume;
}

int invalid_cells(const MixedMesh& mesh) {
  int invalid = 0;
  for (CellType type : all_cell_types)
    for (std::size_t cell = 0; cell < mesh.cell_count(type); ++cell)
      invalid += !cell_shape(type, mesh.points, mesh.cell(type, cell)).valid();
  return invalid;
}

// An nx × ny × nz block of hexahedra on the unit grid, mapped by `map`; boundary
// tagged wall (z = 0) / farfield. Hexahedron (i, j, k) is number i + nx (j + ny k).
template <typename Map>
MixedMesh hexahedron_block(int nx, int ny, int nz, Map map) {
  MixedMesh mesh;
  auto node = [&](int i, int j, int k) { return static_cast<Index>(i + (nx + 1) * (j + (ny + 1) * k)); };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) mesh.points.push_back(map(Vector3(i, j, k)));
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const Index hexahedron[8] = {
            node(i, j, k),     node(i + 1, j, k),     node(i + 1, j + 1, k),     node(i, j + 1, k),
            node(i, j, k + 1), node(i + 1, j, k + 1), node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)};
        mesh.add_cell(CellType::hexahedron, hexahedron, 7);
      }
  reference::tag_boundary(mesh);
  return mesh;
}

OuterLayer top_layer(int nx, int ny, int nz) {
  OuterLayer layer;
  for (int cell = nx * ny * (nz - 1); cell < nx * ny * nz; ++cell)
    layer.hexahedra.push_back({static_cast<std::size_t>(cell), 1});
  return layer;
}

Vector3 shear(const Vector3& point) {
  return Vector3(point.x() + 0.7 * point.z() + 0.2 * point.y(), 0.5 * point.y() + 0.3 * point.z(),
                 0.05 * point.z());
}

void expect_sound_split(const MixedMesh& input, const InterfaceResult& result) {
  EXPECT_NEAR(total_volume(result.mesh), total_volume(input), 1e-12 * total_volume(input));
  EXPECT_EQ(invalid_cells(result.mesh), 0);
  const FaceConnectivity faces = match_faces(result.mesh);
  EXPECT_TRUE(faces.conforming());
  EXPECT_TRUE(faces.untagged_boundary.empty());
  EXPECT_TRUE(faces.stray_boundary_faces.empty());
  EXPECT_EQ(result.mesh.face_count(), faces.boundary.size());
}

}  // namespace

TEST(InterfaceSplit, OneHexahedronBecomesFivePyramidsAndTwoTetrahedra) {
  const MixedMesh input = hexahedron_block(1, 1, 1, [](const Vector3& p) { return p; });
  const InterfaceResult result = split_interface(input, top_layer(1, 1, 1));
  EXPECT_EQ(result.mesh.cell_count(CellType::hexahedron), 0u);
  EXPECT_EQ(result.mesh.cell_count(CellType::pyramid), 5u);
  EXPECT_EQ(result.mesh.cell_count(CellType::tetrahedron), 2u);
  ASSERT_EQ(result.centres.size(), 1u);
  EXPECT_TRUE(
      result.mesh.points[static_cast<std::size_t>(result.centres[0])].isApprox(Vector3(0.5, 0.5, 0.5)));
  ASSERT_EQ(result.hull.size(), 2u);
  for (const auto& triangle : result.hull) {
    const Vector3 normal = face_area_vector(result.mesh.points, triangle.data(), 3);
    EXPECT_NEAR(normal.dot(Vector3::UnitZ()), 0.5, 1e-15) << "hull triangles point away from the layer";
  }
  EXPECT_EQ(result.mesh.face_count(FaceType::quad), 5u);
  const int hull_marker = result.mesh.find_marker("interface");
  ASSERT_GE(hull_marker, 0);
  EXPECT_EQ(std::count(result.mesh.faces(FaceType::triangle).markers.begin(),
                       result.mesh.faces(FaceType::triangle).markers.end(), hull_marker),
            2);
  expect_sound_split(input, result);
}

TEST(InterfaceSplit, ShearedHexahedronSplitsIntoValidPiecesOfTheSameVolume) {
  const MixedMesh input = hexahedron_block(1, 1, 1, shear);
  ASSERT_EQ(invalid_cells(input), 0);
  expect_sound_split(input, split_interface(input, top_layer(1, 1, 1)));
}

TEST(InterfaceSplit, BlockOfThreeByThreeByTwoStaysConformingWithTheInnerLayer) {
  for (auto diagonal : {HullDiagonal::shorter, HullDiagonal::smallest_node}) {
    const MixedMesh input = hexahedron_block(3, 3, 2, shear);
    InterfaceOptions options{diagonal, "interface"};
    options.stack_cells = 1;  // the outer layer alone (stacks: ThinOuterCells... below)
    const InterfaceResult result = split_interface(input, top_layer(3, 3, 2), options);
    EXPECT_EQ(result.mesh.cell_count(CellType::hexahedron), 9u) << "the inner layer keeps its hexahedra";
    EXPECT_EQ(result.mesh.cell_count(CellType::pyramid), 45u);
    EXPECT_EQ(result.mesh.cell_count(CellType::tetrahedron), 18u);
    EXPECT_EQ(result.mesh.points.size(), input.points.size() + 9);
    for (int region : result.mesh.block(CellType::pyramid).regions) EXPECT_EQ(region, 7);
    ASSERT_EQ(result.hull.size(), 18u);
    // The hull is a disc: its free edges are the 12 edges of the block's top rim.
    EXPECT_EQ(triangle_free_edges(result.hull).size(), 12u);
    // Side quads of the split layer keep their farfield tag: 4 sides × 3 (inner) + 4 × 3 (outer).
    EXPECT_EQ(result.mesh.face_count(FaceType::quad), 24u + 9u);
    expect_sound_split(input, result);
  }
}

// Cells 20 times wider than high, leaning a little: split alone, each outer quad's
// two tetrahedra have their apex half a cell under the quad's diagonal and are slivers.
// Split with the cells under them, as stacks about their middle, they are not, and the
// stacks' side quads keep the columns conforming.
double largest_tetrahedron_dihedral(const MixedMesh& mesh) {
  double largest = 0.0;
  for (std::size_t cell = 0; cell < mesh.cell_count(CellType::tetrahedron); ++cell) {
    const Index* nodes = mesh.cell(CellType::tetrahedron, cell);
    auto at = [&](int k) -> const Vector3& { return mesh.points[static_cast<std::size_t>(nodes[k])]; };
    largest = std::max(largest, largest_dihedral_degrees(at(0), at(1), at(2), at(3)));
  }
  return largest;
}

TEST(InterfaceSplit, ThinOuterCellsAreSplitWithTheCellsUnderThem) {
  const MixedMesh input = hexahedron_block(3, 3, 12, [](const Vector3& p) {
    return Vector3(p.x() + 0.02 * p.z() + 0.01 * p.y() * p.y(), 0.8 * p.y() + 0.01 * p.z(), 0.05 * p.z());
  });
  InterfaceOptions alone;
  alone.stack_cells = 1;
  const InterfaceResult single = split_interface(input, top_layer(3, 3, 12), alone);
  EXPECT_EQ(single.stacks, 0u);
  EXPECT_GT(largest_tetrahedron_dihedral(single.mesh), 170.0);

  const InterfaceResult stacked = split_interface(input, top_layer(3, 3, 12));
  EXPECT_EQ(stacked.stacks, 9u);
  EXPECT_GT(stacked.stacked_cells, 2u * 9u);
  EXPECT_LE(largest_tetrahedron_dihedral(stacked.mesh), InterfaceOptions().stack_dihedral);
  EXPECT_EQ(stacked.mesh.cell_count(CellType::hexahedron) + stacked.stacked_cells, 3u * 3u * 12u);
  EXPECT_EQ(stacked.mesh.points.size(), input.points.size() + 9) << "one split point per column";
  EXPECT_EQ(stacked.hull.size(), 18u);
  expect_sound_split(input, stacked);

  // A stack never takes another outer cell's column, nor goes below the block.
  InterfaceOptions deep;
  deep.stack_dihedral = 0.0;
  const InterfaceResult deepest = split_interface(input, top_layer(3, 3, 12), deep);
  EXPECT_LE(deepest.stacked_cells, 3u * 3u * 12u);
  expect_sound_split(input, deepest);
}

// The smallest scaled corner Jacobian of the mesh's pyramids.
double worst_pyramid(const MixedMesh& mesh) {
  double worst = 1.0;
  for (std::size_t cell = 0; cell < mesh.cell_count(CellType::pyramid); ++cell)
    worst = std::min(
        worst,
        cell_shape(CellType::pyramid, mesh.points, mesh.cell(CellType::pyramid, cell)).min_corner_jacobian);
  return worst;
}

// Layers 0.2 mm thick on faces 1 mm wide and 0.45 m long, as where a blunt base meets a
// wake under long spanwise cells. Stacked for their tetrahedra alone (the stack about
// the mean of its cells' centres), the pyramid on a stack's inner quad stays flat: a
// scaled Jacobian under the suite's floor of 1e-3. Stacked until it stands up, it meets
// stack_pyramid_quality, and no tetrahedron gets flatter.
TEST(InterfaceSplit, CellsMuchThinnerThanLongAreStackedUntilTheirPyramidsStandUp) {
  const MixedMesh input = hexahedron_block(
      3, 3, 12, [](const Vector3& p) { return Vector3(0.001 * p.x(), 0.45 * p.y(), 0.0002 * p.z()); });
  InterfaceOptions flat;
  flat.stack_pyramid_quality = 1e-12;
  const InterfaceResult for_tetrahedra = split_interface(input, top_layer(3, 3, 12), flat);
  EXPECT_LT(worst_pyramid(for_tetrahedra.mesh), 1e-3);
  EXPECT_LE(largest_tetrahedron_dihedral(for_tetrahedra.mesh), flat.stack_dihedral);

  const InterfaceResult stacked = split_interface(input, top_layer(3, 3, 12));
  EXPECT_EQ(stacked.stacks, 9u);
  EXPECT_GE(worst_pyramid(stacked.mesh), InterfaceOptions().stack_pyramid_quality);
  EXPECT_LE(largest_tetrahedron_dihedral(stacked.mesh), InterfaceOptions().stack_dihedral);
  EXPECT_GT(stacked.stacked_cells, for_tetrahedra.stacked_cells);
  EXPECT_EQ(stacked.mesh.points.size(), input.points.size() + 9) << "one split point per column";
  expect_sound_split(input, stacked);

  // Faces 0.5 mm wide and 1 m long: the side quads' pyramids stay below the bound whatever the
  // stack (about w / L = 5e-4): the tetrahedra still choose the stack.
  const MixedMesh longer = hexahedron_block(
      3, 3, 16, [](const Vector3& p) { return Vector3(0.0005 * p.x(), p.y(), 0.00005 * p.z()); });
  const InterfaceResult sides = split_interface(longer, top_layer(3, 3, 16));
  EXPECT_LT(worst_pyramid(sides.mesh), InterfaceOptions().stack_pyramid_quality);
  EXPECT_LE(largest_tetrahedron_dihedral(sides.mesh), InterfaceOptions().stack_dihedral);
  expect_sound_split(longer, sides);

  InterfaceOptions above_one;
  above_one.stack_pyramid_quality = 2.0;
  EXPECT_THROW(split_interface(input, top_layer(3, 3, 12), above_one), Error);
}

// A stack over a blunt base: layers growing by 1.2 to 0.4 mm in all on faces 1 mm wide
// and 0.45 m long. Even about the stack's middle its inner pyramid stays under the
// suite's floor of 1e-3 (twice the middle's height over the length is 9e-4); the split
// point goes on past the middle until it meets the floor, and the tetrahedra on the top
// stay within the sliver bound.
TEST(InterfaceSplit, StacksThinnerThanAThousandthOfTheirLengthSplitAboveTheirMiddle) {
  const double total = std::pow(1.2, 12) - 1.0;
  const MixedMesh input = hexahedron_block(3, 3, 12, [&](const Vector3& p) {
    return Vector3(0.001 * p.x(), 0.45 * p.y(), 0.0004 * (std::pow(1.2, p.z()) - 1.0) / total);
  });
  const InterfaceResult stacked = split_interface(input, top_layer(3, 3, 12));
  EXPECT_GE(worst_pyramid(stacked.mesh), 1e-3);
  EXPECT_LE(largest_tetrahedron_dihedral(stacked.mesh), 170.0);
  expect_sound_split(input, stacked);
}

// A wake's last cell at its tip edge under 12 layers growing by 1.25 from 0.6 mm: 4 m
// long, 4 cm wide, each layer's cell facing the far field by its end quad (x = 4) alone.
MixedMesh end_column() {
  const double growth = 1.25;
  return hexahedron_block(1, 1, 12, [&](const Vector3& p) {
    return Vector3(4.0 * p.x(), 0.04 * p.y(), 0.0006 * (std::pow(growth, p.z()) - 1.0) / (growth - 1.0));
  });
}

OuterLayer column_ends(const MixedMesh& column) {
  OuterLayer layer;
  for (std::size_t cell = 0; cell < column.cell_count(CellType::hexahedron); ++cell)
    for (int face = 0; face < hexahedron_descriptor.face_count; ++face) {
      bool at_end = true;
      for (int corner = 0; corner < 4; ++corner)
        at_end =
            at_end &&
            column.points[static_cast<std::size_t>(column.cell(
                              CellType::hexahedron, cell)[hexahedron_descriptor.faces[face].nodes[corner]])]
                    .x() == 4.0;
      if (at_end) layer.hexahedra.push_back({cell, face});
    }
  return layer;
}

TEST(InterfaceSplit, AColumnOfCellsFacingTheFarFieldByTheirEndsStacksAlongTheColumn) {
  // Split one by one the pyramids on their long faces are as flat as the cells are thin
  // (about 2e-4).
  const MixedMesh input = end_column();
  const OuterLayer layer = column_ends(input);
  ASSERT_EQ(layer.hexahedra.size(), 12u);
  const InterfaceResult split = split_interface(input, layer);
  EXPECT_GE(worst_pyramid(split.mesh), 1e-3);
  EXPECT_LE(largest_tetrahedron_dihedral(split.mesh), 170.0);
  EXPECT_GT(split.stacks, 0u);
  expect_sound_split(input, split);

  // With stacks of one cell the column splits (or caps, outside it) cell by cell, as
  // flat as that is.
  InterfaceOptions alone;
  alone.stack_cells = 1;
  const InterfaceResult one_by_one = split_interface(input, layer, alone);
  EXPECT_EQ(one_by_one.stacks, 0u);
  EXPECT_LT(worst_pyramid(one_by_one.mesh), 1e-3);
  EXPECT_EQ(invalid_cells(one_by_one.mesh), 0);
  EXPECT_TRUE(match_faces(one_by_one.mesh).conforming());
}

TEST(InterfaceSplit, AColumnsStacksTakeItsCappedCellsWithoutTheirCaps) {
  // The end quads of the upper seven cells are hull_side, as the end row's of a wake.
  // The lowest of them touches the split cells' end quads and is split too; the six
  // above are capped, and the stacks from below climb into them.
  MixedMesh input = end_column();
  const OuterLayer layer = column_ends(input);
  const int hull_side = input.marker("hull_side");
  const double fifth_layer = input.points[20].z();  // node (0, 0, 5)
  for (std::size_t face = 0; face < input.face_count(FaceType::quad); ++face) {
    const Index* nodes = input.face(FaceType::quad, face);
    bool upper_end = true;
    for (int corner = 0; corner < 4; ++corner)
      upper_end = upper_end && input.points[static_cast<std::size_t>(nodes[corner])].x() == 4.0 &&
                  input.points[static_cast<std::size_t>(nodes[corner])].z() >= fifth_layer;
    if (upper_end) input.faces(FaceType::quad).markers[face] = hull_side;
  }
  const InterfaceResult split = split_interface(input, layer);
  EXPECT_GE(worst_pyramid(split.mesh), 1e-3);
  EXPECT_GT(split.stacked_cells, 6u);  // more than the six uncapped cells
  expect_sound_split(input, split);
  // Without the stacks the six capped cells keep their caps.
  InterfaceOptions alone;
  alone.stack_cells = 1;
  const InterfaceResult capped = split_interface(input, layer, alone);
  EXPECT_GT(capped.mesh.points.size(), input.points.size() + capped.centres.size());
}

TEST(InterfaceSplit, DiagonalRulesAreDeterministic) {
  // A rhombus top whose long diagonal a-c runs through the smallest top node a.
  MixedMesh input = hexahedron_block(1, 1, 1, [](const Vector3& p) { return p; });
  const Index* top = input.cell(CellType::hexahedron, 0) + 4;
  const Index a = top[0], b = top[1], c = top[2], d = top[3];
  ASSERT_EQ(*std::min_element(top, top + 4), a);
  input.points[static_cast<std::size_t>(a)] += Vector3(-0.3, -0.3, 0);
  input.points[static_cast<std::size_t>(c)] += Vector3(0.3, 0.3, 0);
  auto has_edge = [](const InterfaceResult& result, Index a, Index b) {
    for (const auto& triangle : result.hull) {
      const bool with_a = std::find(triangle.begin(), triangle.end(), a) != triangle.end();
      const bool with_b = std::find(triangle.begin(), triangle.end(), b) != triangle.end();
      if (with_a && with_b) return true;
    }
    return false;
  };
  const InterfaceResult by_length =
      split_interface(input, top_layer(1, 1, 1), {HullDiagonal::shorter, "interface"});
  EXPECT_TRUE(has_edge(by_length, b, d));
  EXPECT_FALSE(has_edge(by_length, a, c));
  const InterfaceResult by_node =
      split_interface(input, top_layer(1, 1, 1), {HullDiagonal::smallest_node, "interface"});
  EXPECT_TRUE(has_edge(by_node, a, c));
  EXPECT_FALSE(has_edge(by_node, b, d));
  expect_sound_split(input, by_length);
}

TEST(InterfaceSplit, PrismTopsPassThroughNextToSplitHexahedra) {
  // A hexahedron and a prism sharing the quad x = 1.
  MixedMesh input = hexahedron_block(1, 1, 1, [](const Vector3& p) { return p; });
  input.boundary = {};
  input.marker_names.clear();
  input.points.push_back({2, 0, 0});
  input.points.push_back({2, 0, 1});
  const Index prism[6] = {1, 8, 2, 5, 9, 6};
  input.add_cell(CellType::prism, prism);
  reference::orient_positively(input);
  reference::tag_boundary(input);
  ASSERT_EQ(invalid_cells(input), 0);
  int top_face = -1;  // the prism face at z = 1
  for (int face = 0; face < 2; ++face) {
    bool on_top = true;
    for (int corner = 0; corner < 3; ++corner)
      on_top = on_top && input.points[static_cast<std::size_t>(input.cell(
                                          CellType::prism, 0)[prism_descriptor.faces[face].nodes[corner]])]
                                 .z() == 1.0;
    if (on_top) top_face = face;
  }
  ASSERT_GE(top_face, 0);
  OuterLayer layer = top_layer(1, 1, 1);
  layer.prisms.push_back({0, top_face});
  const InterfaceResult result = split_interface(input, layer);
  EXPECT_EQ(result.hull.size(), 3u);
  EXPECT_EQ(result.mesh.cell_count(CellType::prism), 1u);
  expect_sound_split(input, result);
}

TEST(InterfaceSplit, BadListingsAreRejectedWithTheCellNamed) {
  const MixedMesh input = hexahedron_block(2, 1, 2, [](const Vector3& p) { return p; });
  auto message = [&](const OuterLayer& layer) {
    try {
      split_interface(input, layer);
    } catch (const Error& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({{{9, 1}}, {}}).find("hexahedron 9 does not exist"), std::string::npos);
  EXPECT_NE(message({{{2, 6}}, {}}).find("not a face number"), std::string::npos);
  EXPECT_NE(message({{{2, 1}, {2, 1}}, {}}).find("listed twice"), std::string::npos);
  // The top of the lower layer is shared with the upper layer.
  EXPECT_NE(message({{{0, 1}}, {}}).find("hexahedron 0 is shared"), std::string::npos);
  EXPECT_NE(message({{}, {{0, 1}}}).find("prism 0 does not exist"), std::string::npos);
}

TEST(InterfaceSplit, FreeEdgesOfAClosedHullAreNone) {
  const std::vector<std::array<Index, 3>> tetrahedron_surface = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  EXPECT_TRUE(triangle_free_edges(tetrahedron_surface).empty());
  const auto open = triangle_free_edges({{0, 1, 2}});
  EXPECT_EQ(open.size(), 3u);
}

TEST(InterfaceSplit, SteppedColumnsSplitEveryCellWithAnExposedQuad) {
  // Two columns of three hexahedra; the top of the second is removed, so the top
  // hexahedron of the first faces the far field with its top and its +x side.
  MixedMesh input = hexahedron_block(2, 1, 3, shear);
  auto& block = input.block(CellType::hexahedron);
  block.nodes.erase(block.nodes.begin() + 5 * 8, block.nodes.begin() + 6 * 8);
  block.regions.erase(block.regions.begin() + 5);
  input.boundary = {};
  reference::tag_boundary(input);
  OuterLayer layer;
  layer.hexahedra = {{4, 1}, {4, 3}, {3, 1}};
  const InterfaceResult result = split_interface(input, layer);
  EXPECT_EQ(result.centres.size(), 2u);
  EXPECT_EQ(result.mesh.cell_count(CellType::pyramid), 4u + 5u);
  EXPECT_EQ(result.hull.size(), 6u);
  expect_sound_split(input, result);
}

TEST(InterfaceSplit, PrismWithAnExposedSideIsSplitAboutItsCentre) {
  MixedMesh input = reference::single_cell(CellType::prism);
  reference::tag_boundary(input);
  const InterfaceResult result = split_interface(input, {{}, {{0, 1}, {0, 2}}});
  EXPECT_EQ(result.mesh.cell_count(CellType::prism), 0u);
  EXPECT_EQ(result.mesh.cell_count(CellType::pyramid), 2u);
  EXPECT_EQ(result.mesh.cell_count(CellType::tetrahedron), 2u + 2u);
  EXPECT_EQ(result.hull.size(), 3u);
  expect_sound_split(input, result);
}

TEST(InterfaceSplit, ThinWarpedCellThatCannotBeSplitIsCappedInstead) {
  // Two stacked hexahedra 0.02 thick whose shared quad is a saddle of ±0.012: a
  // pyramid on it with its apex at the lower cell's centre (0.01 away) is inverted.
  MixedMesh input =
      hexahedron_block(1, 1, 2, [](const Vector3& p) { return Vector3(p.x(), p.y(), 0.02 * p.z()); });
  for (Index node = 4; node < 8; ++node) {
    Vector3& point = input.points[static_cast<std::size_t>(node)];
    point.z() += point.x() == point.y() ? 0.012 : -0.012;
  }
  ASSERT_EQ(invalid_cells(input), 0);
  const OuterLayer side = {{{0, 2}}, {}};  // the lower cell's y = 0 side faces the far field
  InterfaceOptions strict;
  strict.cap_unsplittable_cells = false;
  EXPECT_THROW(split_interface(input, side, strict), Error);

  const InterfaceResult result = split_interface(input, side);
  EXPECT_EQ(result.capped_cells, 1u);
  EXPECT_EQ(result.mesh.cell_count(CellType::hexahedron), 2u);
  EXPECT_EQ(result.mesh.cell_count(CellType::pyramid), 1u);
  EXPECT_EQ(result.hull.size(), 4u);
  for (const auto& triangle : result.hull)
    EXPECT_LT(face_area_vector(result.mesh.points, triangle.data(), 3).y(), 0.0) << "caps point away (−y)";
  EXPECT_EQ(invalid_cells(result.mesh), 0);
  const FaceConnectivity faces = match_faces(result.mesh);
  EXPECT_TRUE(faces.conforming());
  EXPECT_TRUE(faces.untagged_boundary.empty());
  EXPECT_TRUE(faces.stray_boundary_faces.empty());
}

// The outermost cell at the trailing edge of a random wing's tip (mm: 64 long, 3-6
// thick, its inner quad warped by 5): the best split point leaves a pyramid under the
// floor of 1e-3 on a long side. Kept whole and capped, its cap's pyramid is far better.
TEST(InterfaceSplit, CellTwistedNearlyFlatIsCappedWhereItsSplitLeavesAFlatPyramid) {
  const Vector3 corners[8] = {{0.0, 0.0, 0.0},
                              {3.1921, -0.5391, -0.2108},
                              {-10.4461, 57.9886, -10.6562},
                              {-12.8170, 60.6100, -15.0573},
                              {0.1940, 1.9489, 5.4833},
                              {3.5097, 1.2712, 5.3140},
                              {-10.7576, 62.7255, -7.2847},
                              {-13.0130, 66.0634, -13.0266}};
  const MixedMesh input = hexahedron_block(1, 1, 1, [&](const Vector3& p) {
    const int i = static_cast<int>(p.x()), j = static_cast<int>(p.y()), k = static_cast<int>(p.z());
    return corners[4 * k + (j == 0 ? i : 3 - i)];
  });
  ASSERT_EQ(invalid_cells(input), 0);
  InterfaceOptions split_anyway;
  split_anyway.split_pyramid_floor = 1e-12;
  const InterfaceResult split = split_interface(input, top_layer(1, 1, 1), split_anyway);
  EXPECT_EQ(split.capped_cells, 0u);
  EXPECT_LT(worst_pyramid(split.mesh), InterfaceOptions().split_pyramid_floor);

  const InterfaceResult capped = split_interface(input, top_layer(1, 1, 1));
  EXPECT_EQ(capped.capped_cells, 1u);
  EXPECT_EQ(capped.mesh.cell_count(CellType::hexahedron), 1u);
  EXPECT_EQ(capped.mesh.cell_count(CellType::pyramid), 1u);
  EXPECT_EQ(capped.hull.size(), 4u);
  EXPECT_GE(worst_pyramid(capped.mesh), 1e-3);
  EXPECT_EQ(invalid_cells(capped.mesh), 0);
  EXPECT_TRUE(match_faces(capped.mesh).conforming());

  InterfaceOptions no_floor;
  no_floor.split_pyramid_floor = 0.0;
  EXPECT_THROW(split_interface(input, top_layer(1, 1, 1), no_floor), Error);
}

// Columns sheared along their long side, as at a blunt base's end at a tip (mm: faces
// 0.2 wide and 11 long, twelve layers 0.05 thick in all, each leaning 0.15 along the
// span): the best split, a stack, leaves a pyramid under the floor. The column is kept
// whole and capped instead, and its cap meets the floor; of two such columns side by
// side only one is (two low caps side by side leave a flat valley over their shared
// long edge).
TEST(InterfaceSplit, StacksShearedAlongTheirLengthAreCappedOneInTwo) {
  const auto sheared = [](const Vector3& p) {
    return Vector3(0.2 * p.x(), 11.0 * p.y() + 0.15 * p.z(), 0.004 * p.z());
  };
  const MixedMesh column = hexahedron_block(1, 1, 12, sheared);
  InterfaceOptions split_anyway;
  split_anyway.split_pyramid_floor = 1e-12;
  const InterfaceResult split = split_interface(column, top_layer(1, 1, 12), split_anyway);
  EXPECT_EQ(split.capped_cells, 0u);
  EXPECT_LT(worst_pyramid(split.mesh), InterfaceOptions().split_pyramid_floor);
  EXPECT_EQ(split.stacks, 1u);

  const InterfaceResult capped = split_interface(column, top_layer(1, 1, 12));
  EXPECT_EQ(capped.capped_cells, 1u);
  EXPECT_EQ(capped.mesh.cell_count(CellType::hexahedron), 12u) << "the stack's cells stay whole";
  EXPECT_EQ(capped.mesh.cell_count(CellType::pyramid), 1u);
  EXPECT_GE(worst_pyramid(capped.mesh), 1e-3);
  EXPECT_EQ(invalid_cells(capped.mesh), 0);
  EXPECT_TRUE(match_faces(capped.mesh).conforming());

  const MixedMesh pair = hexahedron_block(2, 1, 12, sheared);
  const InterfaceResult one_capped = split_interface(pair, top_layer(2, 1, 12));
  EXPECT_EQ(one_capped.capped_cells, 1u);
  EXPECT_EQ(invalid_cells(one_capped.mesh), 0);
  EXPECT_TRUE(match_faces(one_capped.mesh).conforming());
}

TEST(InterfaceSplit, TwistedTopIsCutAlongTheDiagonalThatLetsTheSplitStayValid) {
  // A rhombus cell (top quad 4-5-7-6 in the block's numbering; short diagonal 4-7 along
  // y, long 5-6 along x) whose top and bottom are twisted alike into saddles (5, 6 and
  // 1, 2 raised, the others lowered by 0.9 of the cell height), like a cell beside a
  // convex corner of the layers. The shorter diagonal of the top is the valley 4-7: no
  // split point makes both its tetrahedra and the pyramid on the twisted bottom valid.
  // Cut along the ridge 5-6, the split is valid.
  MixedMesh input = hexahedron_block(1, 1, 1, [](const Vector3& p) {
    const double along = p.x() - p.y(), across = p.x() + p.y() - 1.0;
    return Vector3(1.5 * along, 0.5 * across, 0.4 * p.z());
  });
  for (Index node : {1, 2, 5, 6}) input.points[static_cast<std::size_t>(node)].z() += 0.36;
  for (Index node : {0, 3, 4, 7}) input.points[static_cast<std::size_t>(node)].z() -= 0.36;
  ASSERT_EQ(invalid_cells(input), 0);
  const double ridge = (input.points[6] - input.points[5]).norm();
  const double valley = (input.points[7] - input.points[4]).norm();
  ASSERT_LT(valley, ridge) << "the rule alone would take the valley";

  const InterfaceResult result = split_interface(input, top_layer(1, 1, 1));
  EXPECT_EQ(result.capped_cells, 0u);
  ASSERT_EQ(result.hull.size(), 2u);
  for (const auto& triangle : result.hull)
    EXPECT_EQ(
        std::count(triangle.begin(), triangle.end(), 5) + std::count(triangle.begin(), triangle.end(), 6), 2)
        << "both hull triangles share the ridge 5-6";
  EXPECT_EQ(invalid_cells(result.mesh), 0);
  const FaceConnectivity faces = match_faces(result.mesh);
  EXPECT_TRUE(faces.conforming());
  EXPECT_TRUE(faces.untagged_boundary.empty());
}

TEST(InterfaceSplit, CapOnATwistedQuadIsRaisedUntilValid) {
  // A trailing-edge cell at a wing tip (marched layers of a taper 0.3 wing, metres): a
  // top 0.6 mm by 11 mm twisted by 0.15 mm on a cell 0.26 mm thick. No split point
  // gives valid pieces, and a cap a quarter of the short edge high is inverted.
  MixedMesh input = reference::single_cell(CellType::hexahedron);
  input.points = {{0.3019396, 2.4900778, -0.0207519}, {0.3013277, 2.4901052, -0.0207548},
                  {0.2985206, 2.5010016, -0.0198548}, {0.2990872, 2.5006164, -0.0204153},
                  {0.3019331, 2.4901146, -0.0210112}, {0.3013185, 2.4901526, -0.0210122},
                  {0.2984818, 2.5012589, -0.0198846}, {0.2990432, 2.5008094, -0.0205867}};
  reference::tag_boundary(input);
  ASSERT_EQ(invalid_cells(input), 0);
  const OuterLayer top = {{{0, 1}}, {}};
  InterfaceOptions low_cap;
  low_cap.cap_height_limit = 0.0;
  EXPECT_THROW(split_interface(input, top, low_cap), Error);

  const InterfaceResult result = split_interface(input, top);
  EXPECT_EQ(result.capped_cells, 1u);
  EXPECT_EQ(result.mesh.cell_count(CellType::hexahedron), 1u);
  EXPECT_EQ(result.mesh.cell_count(CellType::pyramid), 1u);
  EXPECT_EQ(result.hull.size(), 4u);
  EXPECT_EQ(invalid_cells(result.mesh), 0);
  const FaceConnectivity faces = match_faces(result.mesh);
  EXPECT_TRUE(faces.conforming());
  EXPECT_TRUE(faces.untagged_boundary.empty());
}

// The split points are searched side by side; the mesh must not depend on how many
// threads search. A thin, curved 24 × 24 block: many outer cells (more than one chunk
// of 64), each so thin that its centre split is not good enough and the search runs.
TEST(InterfaceSplit, SplitIsTheSameOnOneThreadAndOnMany) {
  const MixedMesh input = hexahedron_block(24, 24, 2, [](const Vector3& point) {
    return Vector3(point.x(), point.y(),
                   0.002 * point.z() * (1.0 + 0.3 * std::sin(1.3 * point.x() + 0.7 * point.y())) +
                       0.01 * std::sin(0.4 * point.x()) * std::cos(0.3 * point.y()));
  });
  const OuterLayer layer = top_layer(24, 24, 2);
  InterfaceResult serial;
  {
    const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    serial = split_interface(input, layer);
  }
  const InterfaceResult parallel = split_interface(input, layer);
  // (Not expect_sound_split: the warped top quads are cut along a diagonal, which
  // changes the volume by their warp.)
  EXPECT_EQ(invalid_cells(parallel.mesh), 0);
  EXPECT_TRUE(match_faces(parallel.mesh).conforming());
  EXPECT_EQ(parallel.capped_cells, 0u);
  EXPECT_EQ(parallel.mesh.points, serial.mesh.points);
  for (CellType type : all_cell_types)
    EXPECT_EQ(parallel.mesh.block(type).nodes, serial.mesh.block(type).nodes);
  EXPECT_EQ(parallel.hull, serial.hull);
  EXPECT_GT(parallel.mesh.points.size(), input.points.size() + 24 * 24 - 1);
}

// Cells whose outer quad carries capped_marker keep their shape and get a cap; a
// hexahedron that also touches an outer face without it is split as usual, and so is
// one whose marked quad has an edge on the footprint (the outline of the hull). A 5 × 3
// block with the tops of cells x 2–4 marked: cell 2 of each row shares nodes with cell
// 1's plain top, cell 4 and the outer rows reach the outline, so only the middle of the
// middle row is capped. The hull stays closed round the footprint.
TEST(InterfaceSplit, CellsOfMarkedOuterQuadsAreCappedNotSplit) {
  MixedMesh input = hexahedron_block(5, 3, 1, [](const Vector3& point) { return point; });
  const int marked = input.marker("hull_side");
  for (std::size_t face = 0; face < input.face_count(FaceType::quad); ++face) {
    const Index* nodes = input.face(FaceType::quad, face);
    bool top = true;
    double x = 0.0;
    for (int corner = 0; corner < 4; ++corner) {
      top = top && input.points[static_cast<std::size_t>(nodes[corner])].z() == 1.0;
      x += 0.25 * input.points[static_cast<std::size_t>(nodes[corner])].x();
    }
    if (top && x > 2.0) input.faces(FaceType::quad).markers[face] = marked;
  }
  const OuterLayer layer = top_layer(5, 3, 1);
  const InterfaceResult result = split_interface(input, layer);
  EXPECT_EQ(result.capped_cells, 1u);
  EXPECT_EQ(result.centres.size(), 14u);  // every other cell split about its centre
  EXPECT_EQ(result.mesh.cell_count(CellType::hexahedron), 1u);
  EXPECT_EQ(invalid_cells(result.mesh), 0);
  EXPECT_TRUE(match_faces(result.mesh).conforming());
  // 14 split tops of 2 triangles, 1 cap of 4; open only along the footprint's 16 edges.
  EXPECT_EQ(result.hull.size(), 32u);
  EXPECT_EQ(triangle_free_edges(result.hull).size(), 16u);
  // Without the marker every cell is split.
  InterfaceOptions plain;
  plain.capped_marker.clear();
  EXPECT_EQ(split_interface(input, layer, plain).capped_cells, 0u);
  // Cap heights must be positive.
  InterfaceOptions flat;
  flat.marked_cap_height = 0.0;
  EXPECT_THROW(split_interface(input, layer, flat), Error);
}

// Calls visit(middle of its quad, apex) for every pyramid of the split whose apex is a
// new point (a cap's, or a split cell's centre).
template <typename Visit>
void for_each_new_apex(const InterfaceResult& result, std::size_t input_points, Visit visit) {
  for (std::size_t cell = 0; cell < result.mesh.cell_count(CellType::pyramid); ++cell) {
    const Index* nodes = result.mesh.cell(CellType::pyramid, cell);
    if (static_cast<std::size_t>(nodes[4]) < input_points) continue;
    Vector3 middle = Vector3::Zero();
    for (int corner = 0; corner < 4; ++corner)
      middle += 0.25 * result.mesh.points[static_cast<std::size_t>(nodes[corner])];
    visit(middle, result.mesh.points[static_cast<std::size_t>(nodes[4])]);
  }
}

// A block of 8 × 5 × 1 cells of `size` (x, y, 1), each node moved `shear` x along y,
// whose tops are raised by `slope` times the distance from x = 4 size.x (a valley
// there), the tops of cells 2–5 in x marked, so the cells 3 and 4 of rows 1–3 are capped (rows 0 and 4 reach the footprint). Returns each cap's
// height over its quad's middle, by that middle.
std::vector<std::pair<Vector3, double>> cap_heights(const Vector3& size, double slope,
                                                    InterfaceResult& result, double shear = 0.0) {
  // The tops' rise at x: slope times the distance from x = 4 size.x.
  const auto rise = [&](double x) {
    const double from_middle = x - 4.0 * size.x();
    return slope * std::abs(from_middle);
  };
  MixedMesh input = hexahedron_block(8, 5, 1, [&](const Vector3& point) {
    return Vector3(size.x() * point.x(), size.y() * point.y() + shear * size.x() * point.x(),
                   point.z() + rise(size.x() * point.x()));
  });
  const int marked = input.marker("hull_side");
  for (std::size_t face = 0; face < input.face_count(FaceType::quad); ++face) {
    const Index* nodes = input.face(FaceType::quad, face);
    Vector3 middle = Vector3::Zero();
    for (int corner = 0; corner < 4; ++corner)
      middle += 0.25 * input.points[static_cast<std::size_t>(nodes[corner])];
    const double top = 1.0 + rise(middle.x());
    if (std::abs(middle.z() - top) < 1e-12 && middle.x() > 2.0 * size.x() && middle.x() < 6.0 * size.x())
      input.faces(FaceType::quad).markers[face] = marked;
  }
  result = split_interface(input, top_layer(8, 5, 1));
  std::vector<std::pair<Vector3, double>> heights;
  for_each_new_apex(result, input.points.size(), [&](const Vector3& middle, const Vector3& apex) {
    // Caps stand on the tops over x 3–5 size.x; the split cells' pyramids have their
    // centre as apex, inside the cell, below its top.
    const double top = 1.0 + rise(middle.x());
    if (std::abs(middle.z() - top) > 1e-9 || middle.x() < 3.0 * size.x() || middle.x() > 5.0 * size.x())
      return;
    heights.push_back({middle, (apex - middle).norm()});
  });
  return heights;
}

// Marked caps stand 0.2 of their quad's longest edge high (quads 1 × 10: apex 2 out),
// and come down where that crosses the hull: at a valley slope of 0.5 the caps on
// either side lean into each other and come down to twice the shortest edge times 0.5,
// which clears them; on the flat block they stay tall.
TEST(InterfaceSplit, TallCapsComeDownOnlyWhereTheyCrossTheHull) {
  for (const double slope : {0.0, 0.5}) {
    InterfaceResult result;
    const auto heights = cap_heights(Vector3(1, 10, 1), slope, result);
    ASSERT_EQ(result.capped_cells, 6u);
    ASSERT_EQ(heights.size(), 6u);
    EXPECT_EQ(result.lowered_caps, slope > 0.0 ? 6u : 0u);
    EXPECT_EQ(invalid_cells(result.mesh), 0);
    const double shortest = std::sqrt(1.0 + slope * slope);
    for (const auto& [middle, height] : heights)
      EXPECT_NEAR(height, slope == 0.0 ? 2.0 : shortest, 1e-9)
          << "cap over (" << middle.x() << ", " << middle.y() << ")";
  }
}

// The same on quads sheared along their length (each node moved 4 x along y), as a
// wake's are where its lines' nodes are staggered: the quads are still 1 wide, but
// their short edges are 4.1 long, and with the lowest cap taken from those a cap could
// not come down at all, so the caps either side of the valley were never tested against
// the hull and crossed each other. The lowest comes from the quad's width (its area over
// its longest edge), so they come down as on the unsheared block.
TEST(InterfaceSplit, TallCapsOnShearedQuadsComeDownWhereTheyCrossTheHull) {
  for (const double slope : {0.0, 0.5}) {
    InterfaceResult result;
    const auto heights = cap_heights(Vector3(1, 10, 1), slope, result, 4.0);
    ASSERT_EQ(result.capped_cells, 6u);
    ASSERT_EQ(heights.size(), 6u);
    EXPECT_EQ(result.lowered_caps, slope > 0.0 ? 6u : 0u);
    EXPECT_EQ(invalid_cells(result.mesh), 0);
    const double short_edge = std::sqrt(1.0 + 16.0 + slope * slope);
    const double width = std::sqrt(1.0 + slope * slope);  // area over the long edge
    for (const auto& [middle, height] : heights)
      EXPECT_NEAR(height, slope == 0.0 ? 0.5 * short_edge : width, 1e-9)
          << "cap over (" << middle.x() << ", " << middle.y() << ")";
  }
}

// On sheared quads over a gentle fold (as above, 5.7 degrees) the caps stand on their
// short edges (4.1, apexes 2.06 out) and are tall only because their quads are 1 wide:
// they keep their own normals, as such caps did before they could come down. Turned
// with their neighbours, caps like these over a rounded tip's trailing edge left a hull
// TetGen could not recover (random wing 6 of seed 93).
TEST(InterfaceSplit, StandardCapsOnShearedQuadsStandOnTheirOwnNormals) {
  InterfaceResult result;
  const auto heights = cap_heights(Vector3(1, 10, 1), 0.05, result, 4.0);
  ASSERT_EQ(heights.size(), 6u);
  EXPECT_EQ(invalid_cells(result.mesh), 0);
  int caps = 0;
  for_each_new_apex(result, 0, [&](const Vector3& middle, const Vector3& apex) {
    const Vector3 rise = apex - middle;
    if (rise.z() < 1.0) return;  // not a cap on the tops (split cells' apexes are inside)
    // The tops fall towards x = 4 and rise after it, 0.05 per unit.
    const Vector3 normal = Vector3(middle.x() < 4.0 ? 0.05 : -0.05, 0.0, 1.0).normalized();
    EXPECT_NEAR(rise.normalized().dot(normal), 1.0, 1e-12) << "cap over (" << middle.x() << ", " << middle.y() << ")";
    ++caps;
  });
  EXPECT_EQ(caps, 6);
}

// Over a gentle fold (tops rising 0.05 per unit either side of x = 4: 5.7 degrees between
// the quads' normals) the tall caps either side (quads 1 x 10, apexes 2 out) stand along
// their neighbourhood's mean normal: along their own normals their apexes would lean
// together to 0.8 apart, and the far field's tetrahedron of the shared edge and the two
// apexes would be the flatter.
TEST(InterfaceSplit, CapsOverAGentleFoldStandAlongTheirMeanNormal) {
  InterfaceResult result;
  const auto heights = cap_heights(Vector3(1, 10, 1), 0.05, result);
  ASSERT_EQ(heights.size(), 6u);
  EXPECT_EQ(invalid_cells(result.mesh), 0);
  std::vector<Vector3> apexes;
  for (std::size_t cell = 0; cell < result.mesh.cell_count(CellType::pyramid); ++cell) {
    const Index* nodes = result.mesh.cell(CellType::pyramid, cell);
    const Vector3& apex = result.mesh.points[static_cast<std::size_t>(nodes[4])];
    if (apex.z() > 1.5) apexes.push_back(apex);  // the caps' apexes, 2 over tops near 1.05
  }
  ASSERT_EQ(apexes.size(), 6u);
  for (const Vector3& left : apexes)
    for (const Vector3& right : apexes)
      if (left.x() < 4.0 && right.x() > 4.0 && std::abs(left.y() - right.y()) < 1.0) {
        EXPECT_GT((right - left).norm(), 0.95);
      }
  EXPECT_EQ(result.lowered_caps, 0u);
  for (const auto& [middle, height] : heights) EXPECT_NEAR(height, 2.0, 1e-9);
}

// Two caps on coplanar quads side by side along x (edges at xs, y from 0 to `length`),
// sharing the edge at xs[1], each apex at heights[k] along directions[k] over its quad's
// middle and allowed down to `lowest`; the caps' sides are the hull.
struct TwoCaps {
  MixedMesh mesh;
  std::vector<interface_detail::TallCap> caps;
  std::vector<std::array<Index, 3>> hull;
};

TwoCaps two_caps(const std::array<double, 3>& xs, double length, const std::array<Vector3, 2>& directions,
                 const std::array<double, 2>& heights, double lowest) {
  TwoCaps result;
  for (double x : xs)
    for (double y : {0.0, length}) result.mesh.points.push_back(Vector3(x, y, 0.0));
  // Corners 0 (x0,0) 1 (x0,L) 2 (x1,0) 3 (x1,L) 4 (x2,0) 5 (x2,L); quads wound upwards.
  const std::array<std::array<Index, 4>, 2> quads{{{0, 2, 3, 1}, {2, 4, 5, 3}}};
  for (std::size_t k = 0; k < 2; ++k) {
    const Vector3 middle(0.5 * (xs[k] + xs[k + 1]), 0.5 * length, 0.0);
    const Index apex = static_cast<Index>(result.mesh.points.size());
    result.mesh.points.push_back(middle + heights[k] * directions[k]);
    const auto& quad = quads[k];
    result.caps.push_back({apex,
                           middle,
                           Vector3::UnitZ(),
                           directions[k],
                           heights[k],
                           lowest,
                           {quad[0], quad[1], quad[2], quad[3], apex},
                           result.hull.size()});
    for (std::size_t corner = 0; corner < 4; ++corner)
      result.hull.push_back({quad[corner], quad[(corner + 1) % 4], apex});
  }
  return result;
}

// Two caps side by side on coplanar unit quads, one come down to 0.5 (as if it had
// crossed the hull) and the other still 2 high: the tall one comes down to stand no more
// above its neighbour than their middles are apart (1), so to 1.5; nothing crosses.
TEST(InterfaceSplit, NeighbouringCapsStandWithinFortyFiveDegrees) {
  TwoCaps setup = two_caps({0.0, 1.0, 2.0}, 1.0, {Vector3::UnitZ(), Vector3::UnitZ()}, {0.5, 2.0}, 0.25);
  MixedMesh& mesh = setup.mesh;
  std::vector<interface_detail::TallCap>& caps = setup.caps;
  std::vector<std::array<Index, 3>>& hull = setup.hull;
  // A flat frame round the two quads, out to 10 away, so that the footprint (the hull's
  // free edges) is too far to bound either cap.
  const Index frame = static_cast<Index>(mesh.points.size());
  for (const Vector3& corner :
       {Vector3(-10, -10, 0), Vector3(12, -10, 0), Vector3(12, 11, 0), Vector3(-10, 11, 0)})
    mesh.points.push_back(corner);
  const Index a = frame, b = frame + 1, c = frame + 2, d = frame + 3;
  for (const std::array<Index, 3>& triangle : std::vector<std::array<Index, 3>>{{a, b, 4},
                                                                                {a, 4, 2},
                                                                                {a, 2, 0},
                                                                                {b, c, 5},
                                                                                {b, 5, 4},
                                                                                {c, d, 1},
                                                                                {c, 1, 3},
                                                                                {c, 3, 5},
                                                                                {d, a, 0},
                                                                                {d, 0, 1}})
    hull.push_back(triangle);
  EXPECT_EQ(interface_detail::lower_crossing_caps(mesh, hull, caps, std::nullopt), 1u);
  EXPECT_NEAR(caps[0].height, 0.5, 1e-12);
  EXPECT_NEAR(caps[1].height, 1.5, 1e-9);
  EXPECT_NEAR(mesh.points[static_cast<std::size_t>(caps[1].apex)].z(), 1.5, 1e-9);
}

// A block of 8 × 5 × 1 cells 10 long in x and 1 wide in y (a wake's end rows), tops
// rising by `tilt` per unit of y (a sheet with dihedral, its normals leaning towards
// y = 0), the tops of cells 2–5 in x marked and the side at y = 0 tagged as the symmetry
// plane; with `row_on_plane_marked` false the tops of row 0 are plain. Cells 3 and 4 of
// rows 0 (if marked) to 3 are capped (cells 2 and 5 touch the plain tops, row 4 reaches
// the untagged side). Returns each cap's apex by row (y of its quad's middle).
std::map<int, std::vector<Vector3>> caps_next_to_the_plane(double tilt, bool row_on_plane_marked,
                                                          InterfaceResult& result) {
  MixedMesh input = hexahedron_block(
      8, 5, 1, [&](const Vector3& point) { return Vector3(10.0 * point.x(), point.y(), point.z() + tilt * point.y()); });
  const int marked = input.marker("hull_side");
  const int symmetry = input.marker("symmetry");
  for (std::size_t face = 0; face < input.face_count(FaceType::quad); ++face) {
    const Index* nodes = input.face(FaceType::quad, face);
    Vector3 middle = Vector3::Zero();
    bool on_plane = true;
    for (int corner = 0; corner < 4; ++corner) {
      const Vector3& point = input.points[static_cast<std::size_t>(nodes[corner])];
      middle += 0.25 * point;
      on_plane = on_plane && point.y() == 0.0;
    }
    if (on_plane) input.faces(FaceType::quad).markers[face] = symmetry;
    const bool top = std::abs(middle.z() - (1.0 + tilt * middle.y())) < 1e-12;
    if (top && middle.x() > 20.0 && middle.x() < 60.0 && (row_on_plane_marked || middle.y() > 1.0))
      input.faces(FaceType::quad).markers[face] = marked;
  }
  result = split_interface(input, top_layer(8, 5, 1));
  std::map<int, std::vector<Vector3>> apexes;
  for_each_new_apex(result, input.points.size(), [&](const Vector3& middle, const Vector3& apex) {
    if (std::abs(middle.z() - (1.0 + tilt * middle.y())) > 1e-9) return;  // a split cell's pyramid
    apexes[static_cast<int>(std::floor(middle.y()))].push_back(apex);
  });
  return apexes;
}

// Next to the symmetry plane a cap leans on it: on quads 10 × 1 (tall height 2) the caps
// of row 0 stand 2 over the middle of their edge on the plane, in the plane, and their
// face there is a symmetry triangle, not a hull triangle; the caps of the next rows stand
// 2 high as everywhere (a slot between the plane and a tall cap is filled by the leaning
// one). The mesh stays conforming with every boundary face tagged.
TEST(InterfaceSplit, CapsNextToTheSymmetryPlaneLeanOnIt) {
  InterfaceResult result;
  const auto apexes = caps_next_to_the_plane(0.0, true, result);
  ASSERT_EQ(result.capped_cells, 8u);
  EXPECT_EQ(result.lowered_caps, 0u);
  EXPECT_EQ(invalid_cells(result.mesh), 0);
  ASSERT_EQ(apexes.at(0).size(), 2u);
  for (const Vector3& apex : apexes.at(0)) {
    EXPECT_EQ(apex.y(), 0.0);
    EXPECT_NEAR(apex.z(), 3.0, 1e-12);
  }
  for (int row = 1; row <= 3; ++row)
    for (const Vector3& apex : apexes.at(row)) {
      EXPECT_NEAR(apex.y(), row + 0.5, 1e-12);
      EXPECT_NEAR(apex.z(), 3.0, 1e-12);
    }
  const FaceConnectivity faces = match_faces(result.mesh);
  EXPECT_TRUE(faces.conforming());
  EXPECT_TRUE(faces.untagged_boundary.empty());
  EXPECT_TRUE(faces.stray_boundary_faces.empty());
  const int symmetry = result.mesh.find_marker("symmetry");
  std::size_t plane_triangles = 0;
  for (std::size_t face = 0; face < result.mesh.face_count(FaceType::triangle); ++face)
    plane_triangles += result.mesh.faces(FaceType::triangle).markers[face] == symmetry;
  EXPECT_EQ(plane_triangles, 2u);
  // The hull's free edges (its footprint) now run up to each leaning apex and down again.
  std::size_t through_apexes = 0;
  for (const auto& edge : triangle_free_edges(result.hull))
    for (Index node : edge)
      through_apexes += result.mesh.points[static_cast<std::size_t>(node)].z() > 2.5;
  EXPECT_EQ(through_apexes, 4u);
}

// On a sheet whose normals lean towards the plane (tops rising 0.6 per unit of y, 31
// degrees), the caps turn parallel to the plane and keep their height: each apex stands
// 2 straight above its quad's middle in z, as far from the plane as the middle, so
// nothing leans across the plane and the caps stand parallel to the leaning ones on it.
// With row 0's tops plain, rows 0 and 1 are split (row 1 touches row 0's tops) and the
// caps of rows 2 and 3 turn the same.
TEST(InterfaceSplit, CapsLeaningTowardsTheSymmetryPlaneTurnParallelToIt) {
  for (const bool row_on_plane_marked : {false, true}) {
    InterfaceResult result;
    const auto apexes = caps_next_to_the_plane(0.6, row_on_plane_marked, result);
    ASSERT_EQ(result.capped_cells, row_on_plane_marked ? 8u : 4u);
    EXPECT_EQ(result.lowered_caps, 0u);
    EXPECT_EQ(invalid_cells(result.mesh), 0);
    EXPECT_TRUE(match_faces(result.mesh).conforming());
    for (int row = row_on_plane_marked ? 0 : 2; row <= 3; ++row)
      for (const Vector3& apex : apexes.at(row)) {
        EXPECT_NEAR(apex.y(), row == 0 ? 0.0 : row + 0.5, 1e-12) << "row " << row;
        EXPECT_NEAR(apex.z(), 1.0 + 0.6 * (row == 0 ? 0.0 : row + 0.5) + 2.0, 1e-12) << "row " << row;
      }
  }
}

// Two caps on coplanar quads 0.01 wide and 1 long sharing a long edge (a wake's first
// rows behind a swept trailing edge), one come down to 0.045 as if it had crossed the
// hull, the other 0.055 high: within the 45 degrees the levelling allows (their middles
// are 0.01 apart), but the line between the apexes then points at the shared edge, and
// the far field's tetrahedron of that edge and the two apexes has 171.9 degrees. The
// taller cap comes down towards its neighbour's height, to where that tetrahedron is
// least flat (169.65 degrees at 0.0461); the lower one stays.
TEST(InterfaceSplit, CapsOverNarrowQuadsComeDownWhereTheirValleyIsFlat) {
  TwoCaps setup =
      two_caps({-0.01, 0.0, 0.01}, 1.0, {Vector3::UnitZ(), Vector3::UnitZ()}, {0.045, 0.055}, 0.02);
  MixedMesh& mesh = setup.mesh;
  std::vector<interface_detail::TallCap>& caps = setup.caps;
  const std::vector<std::array<Index, 3>>& hull = setup.hull;
  auto valley = [&]() {
    return largest_dihedral_degrees(mesh.points[2], mesh.points[3],
                                    mesh.points[static_cast<std::size_t>(caps[0].apex)],
                                    mesh.points[static_cast<std::size_t>(caps[1].apex)]);
  };
  const double before = valley();
  ASSERT_GT(before, 171.0);
  EXPECT_EQ(interface_detail::lower_crossing_caps(mesh, hull, caps, std::nullopt), 1u);
  EXPECT_NEAR(caps[0].height, 0.045, 1e-12);
  EXPECT_LT(caps[1].height, 0.05);
  EXPECT_GE(caps[1].height, 0.045);
  std::printf("valley %.2f -> %.2f deg, taller cap 0.055 -> %.5f\n", before, valley(), caps[1].height);
  EXPECT_LT(valley(), 170.0);
}

// Two caps on coplanar quads 0.1 wide and 2 long sharing a long edge, their directions
// turned by 20 degrees towards each other (as over a concave fold, here steeper than
// the alignment's 20 degrees so that it leaves them alone), apexes 0.4 out: across the
// shared edge the apexes would be 0.1 - 2 x 0.4 sin 20 deg apart, crossed over. Both
// come down by the same factor until they are half the middles' distance apart.
TEST(InterfaceSplit, NeighbouringCapsKeepTheirApexesApartAcrossTheirSharedEdge) {
  MixedMesh mesh;
  for (double x : {-0.1, 0.0, 0.1})
    for (double y : {0.0, 2.0}) mesh.points.push_back(Vector3(x, y, 0.0));
  // Corners 0 (-0.1,0) 1 (-0.1,2) 2 (0,0) 3 (0,2) 4 (0.1,0) 5 (0.1,2); quads wound upwards.
  const std::array<std::array<Index, 4>, 2> quads{{{0, 2, 3, 1}, {2, 4, 5, 3}}};
  const double turn = 20.0 * M_PI / 180.0;
  std::vector<interface_detail::TallCap> caps;
  std::vector<std::array<Index, 3>> hull;
  for (std::size_t k = 0; k < 2; ++k) {
    const Vector3 middle(k == 0 ? -0.05 : 0.05, 1.0, 0.0);
    const Vector3 direction(k == 0 ? std::sin(turn) : -std::sin(turn), 0.0, std::cos(turn));
    const Index apex = static_cast<Index>(mesh.points.size());
    mesh.points.push_back(middle + 0.4 * direction);
    const auto& quad = quads[k];
    caps.push_back({apex,
                    middle,
                    direction,
                    direction,
                    0.4,
                    0.01,
                    {quad[0], quad[1], quad[2], quad[3], apex},
                    hull.size()});
    for (std::size_t corner = 0; corner < 4; ++corner)
      hull.push_back({quad[corner], quad[(corner + 1) % 4], apex});
  }
  EXPECT_EQ(interface_detail::lower_crossing_caps(mesh, hull, caps, std::nullopt), 2u);
  const double across = mesh.points[static_cast<std::size_t>(caps[1].apex)].x() -
                        mesh.points[static_cast<std::size_t>(caps[0].apex)].x();
  EXPECT_GE(across, 0.05 - 1e-9);
  EXPECT_NEAR(caps[0].height, caps[1].height, 1e-12);
  EXPECT_LT(caps[0].height, 0.4);
}
