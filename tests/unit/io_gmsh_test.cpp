// Reading meshes that Gmsh itself wrote, and the node-order conventions of the
// formats checked against hand-made files in each format's own numbering.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include "mixmesh/io/mesh_io.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/mesh/face_connectivity.hpp"

using namespace mixmesh;

namespace {

double smallest_volume(const MixedMesh& mesh, CellType type) {
  double smallest = 1e300;
  for (std::size_t cell = 0; cell < mesh.cell_count(type); ++cell)
    smallest = std::min(smallest, signed_volume(type, mesh.points, mesh.cell(type, cell)));
  return smallest;
}

TEST(GmshMesh, MixedBlockMadeByGmshReadsWithPositiveVolumesAndNamedMarkers) {
  const MixedMesh mesh =
      read_mesh(std::filesystem::path(MIXMESH_SOURCE_DIR) / "cases/meshes/mixed_block.msh");
  // Counts as Gmsh 4.8 meshed cases/meshes/mixed_block.geo (also seen by meshio).
  EXPECT_EQ(mesh.cell_count(CellType::hexahedron), 48u);
  EXPECT_EQ(mesh.cell_count(CellType::prism), 132u);
  EXPECT_EQ(mesh.cell_count(CellType::pyramid), 16u);
  EXPECT_EQ(mesh.cell_count(CellType::tetrahedron), 708u);
  EXPECT_EQ(mesh.points.size(), 385u);
  double total = 0;
  for (CellType type : all_cell_types) {
    EXPECT_GT(smallest_volume(mesh, type), 0.0) << name(type);
    for (std::size_t cell = 0; cell < mesh.cell_count(type); ++cell)
      total += signed_volume(type, mesh.points, mesh.cell(type, cell));
  }
  EXPECT_NEAR(total, 2.0, 1e-12);  // the 2 x 1 x 1 block
  EXPECT_EQ(std::set<std::string>(mesh.marker_names.begin(), mesh.marker_names.end()),
            (std::set<std::string>{"wall", "top", "sides"}));
  const FaceConnectivity faces = match_faces(mesh);
  EXPECT_TRUE(faces.conforming());
  EXPECT_TRUE(faces.untagged_boundary.empty());
  EXPECT_TRUE(faces.stray_boundary_faces.empty());
  // Physical volumes 1 ("layer": hexahedra and prisms) and 2 ("outer": the rest).
  for (int region : mesh.block(CellType::hexahedron).regions) EXPECT_EQ(region, 1);
  for (int region : mesh.block(CellType::prism).regions) EXPECT_EQ(region, 1);
  for (int region : mesh.block(CellType::tetrahedron).regions) EXPECT_EQ(region, 2);
}

// The unit prism with its bottom triangle counter-clockwise seen from the top (the
// Gmsh/CGNS convention) in each format's own numbering.
TEST(NodeOrder, GmshPrismIsPermutedToAPositiveVtkWedge) {
  const std::string gmsh_prism =
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n6\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 1 0 1\n6 0 1 "
      "1\n"
      "$EndNodes\n$Elements\n1\n1 6 2 1 1 1 2 3 4 5 6\n$EndElements\n";
  const MixedMesh mesh = parse_msh(gmsh_prism, "prism.msh");
  ASSERT_EQ(mesh.cell_count(CellType::prism), 1u);
  EXPECT_NEAR(signed_volume(CellType::prism, mesh.points, mesh.cell(CellType::prism, 0)), 0.5, 1e-15);
}

TEST(NodeOrder, Su2PrismUsesVtkNumberingUnchanged) {
  // SU2 numbers like VTK: bottom 0-1-2 clockwise seen from the top.
  const std::string su2_prism =
      "NDIME= 3\nNELEM= 1\n13 0 1 2 3 4 5 0\nNPOIN= 6\n0 0 0\n0 1 0\n1 0 0\n0 0 1\n0 1 1\n1 0 1\nNMARK= 0\n";
  const MixedMesh mesh = parse_su2(su2_prism, "prism.su2");
  ASSERT_EQ(mesh.cell_count(CellType::prism), 1u);
  EXPECT_NEAR(signed_volume(CellType::prism, mesh.points, mesh.cell(CellType::prism, 0)), 0.5, 1e-15);
}

TEST(NodeOrder, GmshTetrahedronPyramidAndHexahedronKeepTheirOrder) {
  const std::string cells =
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n9\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n5 0 0 1\n6 1 0 "
      "1\n"
      "7 1 1 1\n8 0 1 1\n9 0.5 0.5 2\n$EndNodes\n$Elements\n3\n1 5 2 1 1 1 2 3 4 5 6 7 8\n"
      "2 7 2 1 1 5 6 7 8 9\n3 4 2 1 1 1 2 4 5\n$EndElements\n";
  const MixedMesh mesh = parse_msh(cells, "cells.msh");
  EXPECT_NEAR(smallest_volume(mesh, CellType::hexahedron), 1.0, 1e-15);
  EXPECT_NEAR(smallest_volume(mesh, CellType::pyramid), 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(smallest_volume(mesh, CellType::tetrahedron), 1.0 / 6.0, 1e-15);
}

TEST(GmshMesh, SparseNodeTagsAndUnnamedGroupsAreAccepted) {
  const std::string sparse =
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n10 0 0 0\n20000000 1 0 0\n30 0 1 0\n7 0 0 "
      "1\n$EndNodes\n"
      "$Elements\n2\n1 4 2 5 3 10 20000000 30 7\n2 2 2 9 4 10 30 20000000\n$EndElements\n";
  const MixedMesh mesh = parse_msh(sparse, "sparse.msh");
  EXPECT_NEAR(smallest_volume(mesh, CellType::tetrahedron), 1.0 / 6.0, 1e-15);
  EXPECT_EQ(mesh.block(CellType::tetrahedron).regions.front(), 5);
  ASSERT_EQ(mesh.face_count(FaceType::triangle), 1u);
  EXPECT_EQ(mesh.marker_names.at(static_cast<std::size_t>(mesh.faces(FaceType::triangle).markers.front())),
            "group_9");
}

}  // namespace
