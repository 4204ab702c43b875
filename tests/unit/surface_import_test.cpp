// Imported surfaces: Plot3D blocks and STL/OBJ/OFF triangles combined into one
// SurfaceMesh whose patches share nodes where they meet.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <map>
#include <sstream>

#include "error_message.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/surface/imported_surface.hpp"

using namespace mixmesh;

namespace {

std::filesystem::path write_file(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::path(::testing::TempDir()) / name;
  std::ofstream(path) << text;
  return path;
}

// The six faces of the unit cube as 3 x 3 Plot3D blocks, i x j pointing outward.
std::string cube_plot3d() {
  // Each face: origin, i direction, j direction (outward normal = i x j).
  const std::vector<std::array<Vector3, 3>> faces = {{Vector3(0, 0, 0), Vector3(0, 1, 0), Vector3(1, 0, 0)},
                                                     {Vector3(0, 0, 1), Vector3(1, 0, 0), Vector3(0, 1, 0)},
                                                     {Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(0, 0, 1)},
                                                     {Vector3(0, 1, 0), Vector3(0, 0, 1), Vector3(1, 0, 0)},
                                                     {Vector3(0, 0, 0), Vector3(0, 0, 1), Vector3(0, 1, 0)},
                                                     {Vector3(1, 0, 0), Vector3(0, 1, 0), Vector3(0, 0, 1)}};
  std::ostringstream text;
  text << std::setprecision(17) << faces.size() << "\n";
  for (std::size_t f = 0; f < faces.size(); ++f) text << "3 3 1\n";
  for (const auto& face : faces) {
    for (int axis = 0; axis < 3; ++axis) {
      for (int j = 0; j < 3; ++j) {
        for (int i = 0; i < 3; ++i) text << (face[0] + 0.5 * i * face[1] + 0.5 * j * face[2])[axis] << " ";
        text << "\n";
      }
    }
  }
  return text.str();
}

// Each edge twice in opposite directions; returns the enclosed volume.
double closed_volume(const SurfaceMesh& surface) {
  std::map<std::pair<Index, Index>, int> directed;
  double volume = 0.0;
  const auto add = [&](const std::vector<Index>& face) {
    for (std::size_t k = 0; k < face.size(); ++k) ++directed[{face[k], face[(k + 1) % face.size()]}];
    const Vector3& a = surface.points[face[0]];
    for (std::size_t k = 1; k + 1 < face.size(); ++k) {
      volume += a.dot(surface.points[face[k]].cross(surface.points[face[k + 1]])) / 6.0;
    }
  };
  for (const auto& patch : surface.structured) {
    for (int j = 0; j + 1 < patch.nj; ++j) {
      for (int i = 0; i + 1 < patch.ni; ++i)
        add({patch.node(i, j), patch.node(i + 1, j), patch.node(i + 1, j + 1), patch.node(i, j + 1)});
    }
  }
  for (const auto& patch : surface.unstructured) {
    for (std::size_t t = 0; t < patch.triangles.size(); t += 3) {
      add({patch.triangles[t], patch.triangles[t + 1], patch.triangles[t + 2]});
    }
  }
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(directed.count({edge.second, edge.first}), 1u)
        << "free edge " << edge.first << "-" << edge.second;
  }
  return volume;
}

}  // namespace

TEST(ImportedSurface, Plot3DCubeBlocksShareTheirEdgeNodes) {
  const auto path = write_file("cube.p3d", cube_plot3d());
  const SurfaceMesh surface = import_surfaces({{path, "box", PatchRole::wall, false}}, ImportOptions{});
  ASSERT_EQ(surface.structured.size(), 6u);
  EXPECT_EQ(surface.structured[0].name, "box_1");
  EXPECT_EQ(surface.structured[5].name, "box_6");
  EXPECT_EQ(surface.points.size(), 26u);  // 6 * 9 nodes, edges and corners merged
  EXPECT_NEAR(closed_volume(surface), 1.0, 1e-12);
  const SurfaceMesh flipped = import_surfaces({{path, "box", PatchRole::wall, true}}, ImportOptions{});
  EXPECT_NEAR(closed_volume(flipped), -1.0, 1e-12);
}

TEST(ImportedSurface, StlTrianglesAndOffTrianglesMergeIntoOneClosedSurface) {
  // A tetrahedron: three faces in an ASCII STL (each vertex repeated), the fourth in OFF.
  const std::string stl =
      "solid tet\n"
      "facet normal 0 0 -1\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 1 0 0\nendloop\nendfacet\n"
      "facet normal 0 -1 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 0 1\nendloop\nendfacet\n"
      "facet normal -1 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 1\nvertex 0 1 0\nendloop\nendfacet\n"
      "endsolid tet\n";
  const std::string off = "OFF\n3 1 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n";
  const SurfaceMesh surface = import_surfaces({{write_file("tet.stl", stl), "", PatchRole::wall, false},
                                               {write_file("lid.off", off), "lid", PatchRole::wall, false}},
                                              ImportOptions{});
  ASSERT_EQ(surface.unstructured.size(), 2u);
  EXPECT_EQ(surface.unstructured[0].name, "tet");
  EXPECT_EQ(surface.unstructured[1].name, "lid");
  EXPECT_EQ(surface.points.size(), 4u);
  EXPECT_NEAR(closed_volume(surface), 1.0 / 6.0, 1e-7);  // STL stores floats
}

TEST(ImportedSurface, NodesWithinTheToleranceMergeAndCollapsedFacesAreErrors) {
  SurfaceMesh surface;
  surface.points = {Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(1, 1, 0), Vector3(1e-10, 0, 0),
                    Vector3(0, 1, 0)};
  TrianglePatch patch;
  patch.name = "pair";
  patch.triangles = {0, 1, 2, 3, 2, 4};
  surface.unstructured.push_back(patch);
  merge_coincident_nodes(surface, 1e-8);
  EXPECT_EQ(surface.points.size(), 4u);
  EXPECT_EQ(surface.unstructured[0].triangles[3], 0);
  SurfaceMesh collapsing = surface;
  EXPECT_NE(error_message([&] { merge_coincident_nodes(collapsing, 2.0); }).find("patch pair"),
            std::string::npos);
}

TEST(ImportedSurface, BadFilesNameTheFileAndLine) {
  const auto short_file = write_file("short.p3d", "1\n2 2 1\n0 1 0 1\n0 0 1 1\n0 0\n");
  EXPECT_NE(error_message([&] {
              import_surfaces({{short_file, "", PatchRole::wall, false}}, {});
            }).find("short.p3d:5:"),
            std::string::npos);
  const auto word = write_file("word.p3d", "1\n2 2 1\n0 1 0 one\n");
  EXPECT_NE(error_message([&] {
              import_surfaces({{word, "", PatchRole::wall, false}}, {});
            }).find("word.p3d:3:"),
            std::string::npos);
  const auto volume = write_file("volume.p3d", "1\n2 2 2\n");
  EXPECT_NE(error_message([&] {
              import_surfaces({{volume, "", PatchRole::wall, false}}, {});
            }).find("volume block"),
            std::string::npos);
  EXPECT_NE(error_message([] {
              import_surfaces({{"/nonexistent/wing.stl", "", PatchRole::wall, false}}, {});
            }).find("/nonexistent/wing.stl"),
            std::string::npos);
  const auto unknown = write_file("wing.igs", "");
  EXPECT_NE(error_message([&] {
              import_surfaces({{unknown, "", PatchRole::wall, false}}, {});
            }).find("unknown surface format"),
            std::string::npos);
}
