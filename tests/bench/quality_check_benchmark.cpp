// Validity and quality of a ~1 M-cell mixed mesh built in memory:
//   lower part  hexahedra (x < half) beside prisms (x ≥ half, two per column cell),
//               layers growing by 2 % upwards, like a boundary layer
//   transition  one layer of cubes over the hexahedra, each a pyramid on its bottom
//               quad plus ten tetrahedra to its centre
//   upper part  cubes cut into six tetrahedra (Kuhn), over everything
// Every quad face that meets triangles is cut along the diagonal through its
// lowest-numbered corner, so the parts conform. Boundary faces: "wall" at z = 0,
// "farfield" elsewhere.
//
//   quality_check_benchmark [benchmark options]
//   quality_check_benchmark --write-mesh=FILE [--size=N]   writes the mesh (any io
//                                                           format) and exits
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <cstring>
#include <iostream>
#include <string>

#include "mixmesh/io/mesh_io.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/quality/quality.hpp"

namespace {

using mixmesh::CellType;
using mixmesh::Index;
using mixmesh::MixedMesh;

// n × n columns, `layers` boundary-layer layers and `tetrahedron_layers` above.
MixedMesh build_mixed_block(int n, int layers, int tetrahedron_layers) {
  MixedMesh mesh;
  const int levels = layers + 1 + tetrahedron_layers;  // cube layers
  std::vector<double> height(static_cast<std::size_t>(levels) + 1, 0.0);
  double spacing = 1e-3;
  for (int level = 1; level <= levels; ++level) {
    height[static_cast<std::size_t>(level)] = height[static_cast<std::size_t>(level) - 1] + spacing;
    if (level < layers) spacing *= 1.02;
  }
  auto point = [&](int i, int j, int k) { return static_cast<Index>((k * (n + 1) + j) * (n + 1) + i); };
  for (int k = 0; k <= levels; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i)
        mesh.points.push_back(
            {static_cast<double>(i) / n, static_cast<double>(j) / n, height[static_cast<std::size_t>(k)]});

  // Corners of cube (i, j, k) in hex order.
  auto corners = [&](int i, int j, int k) {
    return std::array<Index, 8>{
        point(i, j, k),     point(i + 1, j, k),     point(i + 1, j + 1, k),     point(i, j + 1, k),
        point(i, j, k + 1), point(i + 1, j, k + 1), point(i + 1, j + 1, k + 1), point(i, j + 1, k + 1)};
  };
  // Kuhn's six tetrahedra along the diagonal 0-6; node sequences through the cube.
  constexpr std::array<std::array<int, 4>, 6> kuhn = {
      {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6}, {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}}};
  auto add_positive = [&](CellType type, Index* nodes) {
    if (mixmesh::signed_volume(type, mesh.points, nodes) < 0) {
      if (type == CellType::tetrahedron) std::swap(nodes[1], nodes[2]);
      if (type == CellType::pyramid) std::swap(nodes[1], nodes[3]);
    }
    mesh.add_cell(type, nodes);
  };
  const int half = n / 2;
  for (int k = 0; k < levels; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const auto c = corners(i, j, k);
        if (k < layers && i < half) {
          mesh.add_cell(CellType::hexahedron, c.data());
        } else if (k < layers) {
          // Diagonal 0-2 of the column cell: prisms (0, 1, 2) and (0, 2, 3), VTK wedge
          // order (bottom clockwise seen from the top).
          Index first[6] = {c[0], c[2], c[1], c[4], c[6], c[5]};
          Index second[6] = {c[0], c[3], c[2], c[4], c[7], c[6]};
          mesh.add_cell(CellType::prism, first);
          mesh.add_cell(CellType::prism, second);
        } else if (k == layers && i < half) {
          // Pyramid on the bottom quad to the cube centre, tetrahedra on the five
          // other faces cut along the diagonal through the corner of smallest index.
          const Index centre = static_cast<Index>(mesh.points.size());
          mesh.points.push_back(0.5 * (mesh.points[static_cast<std::size_t>(c[0])] +
                                       mesh.points[static_cast<std::size_t>(c[6])]));
          Index pyramid[5] = {c[0], c[1], c[2], c[3], centre};
          add_positive(CellType::pyramid, pyramid);
          constexpr std::array<std::array<int, 4>, 5> faces = {
              {{4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {3, 2, 6, 7}, {0, 3, 7, 4}}};
          for (const auto& face : faces) {
            // Each face's corner of smallest index is its first listed one, and the
            // Kuhn diagonals of the neighbours run through it too.
            const Index a = c[static_cast<std::size_t>(face[0])];
            const Index b = c[static_cast<std::size_t>(face[1])];
            const Index d = c[static_cast<std::size_t>(face[2])];
            const Index e = c[static_cast<std::size_t>(face[3])];
            Index first[4] = {a, b, d, centre};
            Index second[4] = {a, d, e, centre};
            add_positive(CellType::tetrahedron, first);
            add_positive(CellType::tetrahedron, second);
          }
        } else {
          for (const auto& tetrahedron : kuhn) {
            Index nodes[4];
            for (int local = 0; local < 4; ++local)
              nodes[local] = c[static_cast<std::size_t>(tetrahedron[static_cast<std::size_t>(local)])];
            add_positive(CellType::tetrahedron, nodes);
          }
        }
      }

  const mixmesh::FaceConnectivity faces = mixmesh::match_faces(mesh);
  const int wall = mesh.marker("wall");
  const int farfield = mesh.marker("farfield");
  for (const mixmesh::CellFace& face : faces.boundary) {
    Index nodes[4];
    const int count = mixmesh::face_nodes(mesh, face, nodes);
    bool on_wall = true;
    for (int corner = 0; corner < count; ++corner)
      on_wall = on_wall && mesh.points[static_cast<std::size_t>(nodes[corner])].z() == 0.0;
    mesh.add_face(count == 3 ? mixmesh::FaceType::triangle : mixmesh::FaceType::quad, nodes,
                  on_wall ? wall : farfield);
  }
  return mesh;
}

// size 63: 63 × 63 columns, 126 layers, 10 tetrahedron layers: 1 025 829 cells.
MixedMesh build_benchmark_mesh(int size) {
  return build_mixed_block(size, 2 * size, size / 6);
}

const MixedMesh& benchmark_mesh() {
  static const MixedMesh mesh = build_benchmark_mesh(63);
  return mesh;
}

void BM_CheckMesh(benchmark::State& state) {
  const MixedMesh& mesh = benchmark_mesh();
  bool valid = false;
  for (auto _ : state) {
    const mixmesh::CheckReport report = mixmesh::check_mesh(mesh);
    valid = report.validity.valid();
    benchmark::DoNotOptimize(report.quality.entries.data());
  }
  if (!valid) state.SkipWithError("the benchmark mesh is not valid");
  state.counters["cells"] = static_cast<double>(mesh.cell_count());
}
BENCHMARK(BM_CheckMesh)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Validate(benchmark::State& state) {
  const MixedMesh& mesh = benchmark_mesh();
  for (auto _ : state) benchmark::DoNotOptimize(mixmesh::validate(mesh).findings.data());
}
BENCHMARK(BM_Validate)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_MatchFaces(benchmark::State& state) {
  const MixedMesh& mesh = benchmark_mesh();
  for (auto _ : state) benchmark::DoNotOptimize(mixmesh::match_faces(mesh).interior.data());
}
BENCHMARK(BM_MatchFaces)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_MeasureQuality(benchmark::State& state) {
  const MixedMesh& mesh = benchmark_mesh();
  for (auto _ : state) benchmark::DoNotOptimize(mixmesh::measure_quality(mesh).entries.data());
}
BENCHMARK(BM_MeasureQuality)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

int main(int argument_count, char** arguments) {
  std::string output;
  int size = 63;
  for (int argument = 1; argument < argument_count; ++argument) {
    if (std::strncmp(arguments[argument], "--write-mesh=", 13) == 0) output = arguments[argument] + 13;
    if (std::strncmp(arguments[argument], "--size=", 7) == 0) size = std::stoi(arguments[argument] + 7);
  }
  if (!output.empty()) {
    try {
      const MixedMesh mesh = build_benchmark_mesh(size);
      mixmesh::write_mesh(mesh, output);
      std::cout << "wrote " << output << ": " << mesh.points.size() << " points, " << mesh.cell_count()
                << " cells\n";
      return 0;
    } catch (const std::exception& error) {
      std::cerr << "error: " << error.what() << '\n';
      return 1;
    }
  }
  benchmark::Initialize(&argument_count, arguments);
  if (benchmark::ReportUnrecognizedArguments(argument_count, arguments)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
