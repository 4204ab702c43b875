// Round trips of the four-type reference mesh and a planar mesh through every
// format, compared independent of cell order: counts, volumes, regions and markers.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <tuple>

#include "mixmesh/core/error.hpp"
#include "mixmesh/io/mesh_io.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/mesh/face_connectivity.hpp"
#include "reference_cells.hpp"

using namespace mixmesh;

namespace {

struct Case {
  std::string name;
  std::string extension;
  WriteOptions options;
  bool keeps_regions;
};

void PrintTo(const Case& format, std::ostream* stream) {
  *stream << format.name;
}

std::filesystem::path scratch(const std::string& file, const std::string& folder = "mixmesh_io_test") {
  const std::filesystem::path directory = std::filesystem::temp_directory_path() / folder;
  std::filesystem::create_directories(directory);
  return directory / file;
}

// Cell volumes per type, sorted (order-independent comparison).
std::map<CellType, std::vector<double>> volumes(const MixedMesh& mesh) {
  std::map<CellType, std::vector<double>> result;
  for (CellType type : all_cell_types) {
    for (std::size_t cell = 0; cell < mesh.cell_count(type); ++cell)
      result[type].push_back(signed_volume(type, mesh.points, mesh.cell(type, cell)));
    std::sort(result[type].begin(), result[type].end());
  }
  return result;
}

// Per marker name: triangle count, quad count, summed area.
std::map<std::string, std::tuple<int, int, double>> markers(const MixedMesh& mesh) {
  std::map<std::string, std::tuple<int, int, double>> result;
  for (FaceType type : all_face_types)
    for (std::size_t face = 0; face < mesh.face_count(type); ++face) {
      auto& entry = result[mesh.marker_names.at(static_cast<std::size_t>(mesh.faces(type).markers[face]))];
      (type == FaceType::triangle ? std::get<0>(entry) : std::get<1>(entry)) += 1;
      std::get<2>(entry) += face_area_vector(mesh.points, mesh.face(type, face), node_count(type)).norm();
    }
  return result;
}

std::map<std::pair<CellType, int>, int> regions(const MixedMesh& mesh) {
  std::map<std::pair<CellType, int>, int> result;
  for (CellType type : all_cell_types)
    for (int region : mesh.block(type).regions) ++result[{type, region}];
  return result;
}

class EveryFormat : public ::testing::TestWithParam<Case> {};

std::vector<Case> all_cases() {
  auto with = [](MshVersion version, Encoding encoding) {
    WriteOptions options;
    options.msh_version = version;
    options.encoding = encoding;
    return options;
  };
  WriteOptions compressed;
  compressed.compress = true;
  return {{"vtu_binary", ".vtu", {}, true},
          {"vtu_ascii", ".vtu", with(MshVersion::v41, Encoding::ascii), true},
          {"vtu_compressed", ".vtu", compressed, true},
          {"msh41_ascii", ".msh", with(MshVersion::v41, Encoding::ascii), true},
          {"msh41_binary", ".msh", with(MshVersion::v41, Encoding::binary), true},
          {"msh22_ascii", ".msh", with(MshVersion::v22, Encoding::ascii), true},
          {"msh22_binary", ".msh", with(MshVersion::v22, Encoding::binary), true},
          {"su2", ".su2", {}, false},
          {"cgns", ".cgns", {}, true}};
}

INSTANTIATE_TEST_SUITE_P(Io, EveryFormat, ::testing::ValuesIn(all_cases()),
                         [](const auto& info) { return info.param.name; });

TEST_P(EveryFormat, FourTypeMeshRoundTripsWithVolumesMarkersAndRegions) {
  const MixedMesh original = reference::four_type_mesh();
  const std::filesystem::path path = scratch("four_types_" + GetParam().name + GetParam().extension);
  write_mesh(original, path, GetParam().options);
  const MixedMesh copy = read_mesh(path);

  EXPECT_EQ(copy.points.size(), original.points.size());
  for (CellType type : all_cell_types) EXPECT_EQ(copy.cell_count(type), 1u) << name(type);
  const auto expected = volumes(original);
  const auto found = volumes(copy);
  for (CellType type : all_cell_types) {
    ASSERT_EQ(found.at(type).size(), expected.at(type).size());
    for (std::size_t cell = 0; cell < expected.at(type).size(); ++cell) {
      EXPECT_GT(found.at(type)[cell], 0.0) << name(type) << " turned inside out";
      EXPECT_NEAR(found.at(type)[cell], expected.at(type)[cell], 1e-12) << name(type);
    }
  }
  const auto original_markers = markers(original);
  const auto copied_markers = markers(copy);
  ASSERT_EQ(copied_markers.size(), original_markers.size());
  for (const auto& [marker, entry] : original_markers) {
    ASSERT_EQ(copied_markers.count(marker), 1u) << marker;
    EXPECT_EQ(std::get<0>(copied_markers.at(marker)), std::get<0>(entry)) << marker;
    EXPECT_EQ(std::get<1>(copied_markers.at(marker)), std::get<1>(entry)) << marker;
    EXPECT_NEAR(std::get<2>(copied_markers.at(marker)), std::get<2>(entry), 1e-12) << marker;
  }
  if (GetParam().keeps_regions) {
    EXPECT_EQ(regions(copy), regions(original));
  }

  // The faces still close the cells: every boundary face of the cells is tagged.
  const FaceConnectivity faces = match_faces(copy);
  EXPECT_TRUE(faces.conforming());
  EXPECT_TRUE(faces.untagged_boundary.empty());
  EXPECT_TRUE(faces.stray_boundary_faces.empty());
}

TEST_P(EveryFormat, WritingTwiceGivesTheSameMesh) {
  const MixedMesh original = reference::four_type_mesh();
  // A folder of its own: tests run in parallel and others' temporaries must not count.
  const std::string folder = "mixmesh_io_twice_" + GetParam().name;
  const std::filesystem::path first = scratch("first" + GetParam().extension, folder);
  const std::filesystem::path second = scratch("second" + GetParam().extension, folder);
  write_mesh(original, first, GetParam().options);
  write_mesh(read_mesh(first), second, GetParam().options);
  const MixedMesh again = read_mesh(second);
  EXPECT_EQ(volumes(again), volumes(original));
  EXPECT_EQ(markers(again).size(), markers(original).size());
  for (const auto& file : std::filesystem::directory_iterator(first.parent_path()))
    EXPECT_EQ(file.path().filename().string().rfind(".tmp-", 0), std::string::npos)
        << "temporary left behind";
}

// Two triangles and a quad in z = 0 with edges tagged "inlet" and "wall".
MixedMesh planar_mesh() {
  MixedMesh mesh;
  mesh.points = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 1, 0}};
  auto& triangles = mesh.planar_cells[static_cast<std::size_t>(index(FaceType::triangle))];
  triangles.nodes = {0, 1, 4, 0, 4, 3};
  triangles.markers = {1, 1};
  auto& quads = mesh.planar_cells[static_cast<std::size_t>(index(FaceType::quad))];
  quads.nodes = {1, 2, 5, 4};
  quads.markers = {2};
  const int inlet = mesh.marker("inlet");
  const int wall = mesh.marker("wall");
  mesh.boundary_edges.nodes = {3, 0, 0, 1, 1, 2, 2, 5, 5, 4, 4, 3};
  mesh.boundary_edges.markers = {inlet, wall, wall, wall, wall, wall};
  return mesh;
}

TEST_P(EveryFormat, PlanarMeshRoundTripsWhereTheFormatHasOne) {
  const MixedMesh original = planar_mesh();
  const std::filesystem::path path = scratch("planar_" + GetParam().name + GetParam().extension);
  if (GetParam().extension == ".cgns") {
    EXPECT_THROW(write_mesh(original, path, GetParam().options), Error);
    return;
  }
  write_mesh(original, path, GetParam().options);
  const MixedMesh copy = read_mesh(path);
  ASSERT_TRUE(copy.planar());
  EXPECT_EQ(copy.points.size(), original.points.size());
  for (std::size_t type = 0; type < 2; ++type) {
    EXPECT_EQ(copy.planar_cells[type].nodes.size(), original.planar_cells[type].nodes.size());
    if (GetParam().keeps_regions) {
      EXPECT_EQ(copy.planar_cells[type].markers, original.planar_cells[type].markers);
    }
  }
  // Orientation survives: every planar cell keeps its counter-clockwise winding.
  for (std::size_t type = 0; type < 2; ++type) {
    const int stride = type == 0 ? 3 : 4;
    const auto& block = copy.planar_cells[type];
    for (std::size_t cell = 0; cell < block.markers.size(); ++cell)
      EXPECT_GT(
          face_area_vector(copy.points, &block.nodes[cell * static_cast<std::size_t>(stride)], stride).z(),
          0.0);
  }
  std::map<std::string, int> edges;
  for (int marker : copy.boundary_edges.markers)
    ++edges[copy.marker_names.at(static_cast<std::size_t>(marker))];
  EXPECT_EQ(edges, (std::map<std::string, int>{{"inlet", 1}, {"wall", 5}}));
}

TEST_P(EveryFormat, SurfaceMeshKeepsItsBoundaryFaces) {
  if (GetParam().extension == ".cgns") GTEST_SKIP() << "CGNS files of mixmesh hold volume meshes";
  MixedMesh surface = reference::four_type_mesh();
  for (CellBlock& block : surface.cells) block = CellBlock{};
  const std::filesystem::path path = scratch("surface_" + GetParam().name + GetParam().extension);
  write_mesh(surface, path, GetParam().options);
  const MixedMesh copy = read_mesh(path);
  EXPECT_FALSE(copy.planar());
  EXPECT_EQ(copy.cell_count(), 0u);
  const auto expected = markers(surface);
  const auto found = markers(copy);
  ASSERT_EQ(found.size(), expected.size());
  for (const auto& [marker, entry] : expected) {
    EXPECT_EQ(std::get<0>(found.at(marker)), std::get<0>(entry)) << marker;
    EXPECT_EQ(std::get<1>(found.at(marker)), std::get<1>(entry)) << marker;
  }
}

TEST(MeshFormat, ExtensionChoosesTheFormatCaseInsensitively) {
  EXPECT_EQ(format_from_extension("a/b.VTU"), MeshFormat::vtu);
  EXPECT_EQ(format_from_extension("b.msh"), MeshFormat::msh);
  EXPECT_EQ(format_from_extension("b.su2"), MeshFormat::su2);
  EXPECT_EQ(format_from_extension("b.cgns"), MeshFormat::cgns);
  EXPECT_THROW(format_from_extension("b.stl"), Error);
  EXPECT_THROW(read_mesh("mesh_without_extension"), Error);
}

}  // namespace
