// Boundary layers → interface split → metrics → far field → one mesh: the stages
// connect by plain data and the assembled mesh is conforming and fully tagged.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>

#include "mixmesh/farfield/farfield.hpp"
#include "mixmesh/interface/interface_split.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/mesh/face_connectivity.hpp"
#include "mixmesh/metric/metric.hpp"

using namespace mixmesh;

namespace {

// Two layers of cells on a hemisphere of radius 0.5 (pole at +y, rim on y = 0):
// hexahedra between latitude rings, prisms around the pole; the top of the second
// layer is the outer face. Boundary: wall (inner), symmetry (y = 0), outer.
struct Layers {
  MixedMesh mesh;
  OuterLayer outer;
};

Layers hemisphere_layers(int rings, int sectors, double thickness) {
  Layers layers;
  MixedMesh& mesh = layers.mesh;
  const std::array<double, 3> radii = {0.5 - 2 * thickness, 0.5 - thickness, 0.5};
  auto point = [&](int ring, int sector, int level) {
    if (ring == 0) return static_cast<Index>(level);
    return static_cast<Index>(3 + (level * rings + ring - 1) * sectors + sector % sectors);
  };
  for (int level = 0; level < 3; ++level) mesh.points.emplace_back(0.0, radii[level], 0.0);
  for (int level = 0; level < 3; ++level)
    for (int ring = 1; ring <= rings; ++ring)
      for (int sector = 0; sector < sectors; ++sector) {
        const double polar = M_PI / 2 * ring / rings, azimuth = 2 * M_PI * sector / sectors;
        mesh.points.emplace_back(radii[level] * std::sin(polar) * std::cos(azimuth),
                                 ring == rings ? 0.0 : radii[level] * std::cos(polar),
                                 radii[level] * std::sin(polar) * std::sin(azimuth));
      }
  for (int level = 0; level < 2; ++level)
    for (int sector = 0; sector < sectors; ++sector) {
      Index prism[6] = {point(0, 0, level),     point(1, sector + 1, level),     point(1, sector, level),
                        point(0, 0, level + 1), point(1, sector + 1, level + 1), point(1, sector, level + 1)};
      if (signed_volume(CellType::prism, mesh.points, prism) < 0) {
        std::swap(prism[1], prism[2]);
        std::swap(prism[4], prism[5]);
      }
      if (level == 1) layers.outer.prisms.push_back({mesh.cell_count(CellType::prism), 1});
      mesh.add_cell(CellType::prism, prism);
      for (int ring = 1; ring < rings; ++ring) {
        Index hexahedron[8] = {point(ring, sector, level),
                               point(ring + 1, sector, level),
                               point(ring + 1, sector + 1, level),
                               point(ring, sector + 1, level),
                               point(ring, sector, level + 1),
                               point(ring + 1, sector, level + 1),
                               point(ring + 1, sector + 1, level + 1),
                               point(ring, sector + 1, level + 1)};
        if (signed_volume(CellType::hexahedron, mesh.points, hexahedron) < 0) {
          std::swap(hexahedron[1], hexahedron[3]);
          std::swap(hexahedron[5], hexahedron[7]);
        }
        if (level == 1) layers.outer.hexahedra.push_back({mesh.cell_count(CellType::hexahedron), 1});
        mesh.add_cell(CellType::hexahedron, hexahedron);
      }
    }
  const int wall = mesh.marker("wall"), symmetry = mesh.marker("symmetry"), outer = mesh.marker("outer");
  for (const CellFace& face : match_faces(mesh).boundary) {
    Index nodes[4];
    const int count = face_nodes(mesh, face, nodes);
    bool on_plane = true, inner = true;
    for (int corner = 0; corner < count; ++corner) {
      const Vector3& at = mesh.points[static_cast<std::size_t>(nodes[corner])];
      on_plane = on_plane && at.y() == 0.0;
      inner = inner && std::abs(at.norm() - radii[0]) < 1e-12;
    }
    mesh.add_face(count == 3 ? FaceType::triangle : FaceType::quad, nodes,
                  on_plane ? symmetry
                  : inner  ? wall
                           : outer);
  }
  return layers;
}

// The split layers without their hull tags, plus the far field's cells and faces.
MixedMesh assemble(const InterfaceResult& split, const FarFieldResult& far) {
  MixedMesh mesh;
  mesh.points = far.mesh.points;
  mesh.cells = split.mesh.cells;
  const int hull_marker = split.mesh.find_marker("interface");
  for (FaceType type : all_face_types)
    for (std::size_t face = 0; face < split.mesh.face_count(type); ++face) {
      const int marker = split.mesh.faces(type).markers[face];
      if (marker != hull_marker)
        mesh.add_face(type, split.mesh.face(type, face),
                      mesh.marker(split.mesh.marker_names[static_cast<std::size_t>(marker)]));
    }
  for (std::size_t cell = 0; cell < far.mesh.cell_count(CellType::tetrahedron); ++cell)
    mesh.add_cell(CellType::tetrahedron, far.mesh.cell(CellType::tetrahedron, cell), 9);
  for (std::size_t face = 0; face < far.mesh.face_count(FaceType::triangle); ++face)
    mesh.add_face(FaceType::triangle, far.mesh.face(FaceType::triangle, face),
                  mesh.marker(far.mesh.marker_names[static_cast<std::size_t>(
                      far.mesh.faces(FaceType::triangle).markers[face])]));
  return mesh;
}

// Volume cells as a legacy VTK unstructured grid, for the independent checker.
void write_vtk(const MixedMesh& mesh, const std::filesystem::path& path) {
  std::ofstream out(path);
  out << std::setprecision(17) << "# vtk DataFile Version 3.0\nmixmesh\nASCII\nDATASET UNSTRUCTURED_GRID\n";
  out << "POINTS " << mesh.points.size() << " double\n";
  for (const Vector3& point : mesh.points) out << point.x() << ' ' << point.y() << ' ' << point.z() << '\n';
  std::size_t entries = 0;
  for (CellType type : all_cell_types)
    entries += mesh.cell_count(type) * static_cast<std::size_t>(node_count(type) + 1);
  out << "CELLS " << mesh.cell_count() << ' ' << entries << '\n';
  for (CellType type : all_cell_types)
    for (std::size_t cell = 0; cell < mesh.cell_count(type); ++cell) {
      out << node_count(type);
      for (int corner = 0; corner < node_count(type); ++corner) out << ' ' << mesh.cell(type, cell)[corner];
      out << '\n';
    }
  out << "CELL_TYPES " << mesh.cell_count() << '\n';
  for (CellType type : all_cell_types)
    for (std::size_t cell = 0; cell < mesh.cell_count(type); ++cell) out << vtk_cell_number(type) << '\n';
}

}  // namespace

TEST(FarFieldAssembly, LayersSplitMetricsAndTetrahedraFormOneConformingMesh) {
  const Layers layers = hemisphere_layers(5, 20, 0.02);
  ASSERT_TRUE(match_faces(layers.mesh).conforming());
  const InterfaceResult split = split_interface(layers.mesh, layers.outer);
  EXPECT_EQ(split.hull.size(), 20u * (2 * 4) + 20u);  // two triangles per outer hexahedron, one per prism

  FarFieldInput input;
  input.points = split.mesh.points;
  input.hull = split.hull;
  for (const auto& triangle : split.hull)
    for (Index node : triangle)
      if (std::find(input.metric_nodes.begin(), input.metric_nodes.end(), node) == input.metric_nodes.end())
        input.metric_nodes.push_back(node);
  input.metrics = node_metrics(layers.mesh, input.metric_nodes);  // from the cells before the split
  FarFieldOptions options;
  options.sizing = FarFieldSizing::anisotropic;
  options.radius_in_chords = 5.0;
  options.farfield_size_in_chords = 1.5;
  options.size_gradient = 0.4;
  const FarFieldResult far = farfield(input, options);
  EXPECT_GT(far.hull_lengths.within_range, 0.6);

  const MixedMesh mesh = assemble(split, far);
  int invalid = 0;
  for (CellType type : all_cell_types)
    for (std::size_t cell = 0; cell < mesh.cell_count(type); ++cell)
      invalid += !cell_shape(type, mesh.points, mesh.cell(type, cell)).valid();
  EXPECT_EQ(invalid, 0);
  const FaceConnectivity faces = match_faces(mesh);
  EXPECT_TRUE(faces.conforming());
  EXPECT_TRUE(faces.untagged_boundary.empty());
  EXPECT_TRUE(faces.stray_boundary_faces.empty());
  EXPECT_EQ(mesh.find_marker("outer"), -1) << "the old outer tags went with the split";
  // Symmetry faces from both parts lie on y = 0.
  const int symmetry = mesh.find_marker("symmetry");
  for (FaceType type : all_face_types)
    for (std::size_t face = 0; face < mesh.face_count(type); ++face)
      if (mesh.faces(type).markers[face] == symmetry) {
        for (int corner = 0; corner < node_count(type); ++corner)
          EXPECT_EQ(mesh.points[static_cast<std::size_t>(mesh.face(type, face)[corner])].y(), 0.0);
      }

  // The independent checker agrees (exit 0: valid).
  const std::filesystem::path path = std::filesystem::path(::testing::TempDir()) / "farfield_assembly.vtk";
  write_vtk(mesh, path);
  const std::string command =
      "/usr/bin/python3 " MIXMESH_SHARED_DIR "/tools/check_mesh.py --no-foam -q " + path.string();
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  std::filesystem::remove(path);
}
