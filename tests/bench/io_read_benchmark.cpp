// Read and write times of every format for a generated mixed mesh of about one
// million cells (64 x 64 x 64 blocks: a quarter hexahedra, a quarter split into two
// prisms, a quarter into six pyramids around a centre node, a quarter into six
// tetrahedra). Run: build/tests/bench/io_read_benchmark [--benchmark_filter=vtu]
#include <benchmark/benchmark.h>

#include <array>
#include <filesystem>
#include <utility>

#include "mixmesh/io/mesh_io.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "reference_cells.hpp"

using namespace mixmesh;

namespace {

constexpr int blocks = 64;

MixedMesh million_cell_mesh() {
  MixedMesh mesh;
  const int side = blocks + 1;
  auto node = [&](int i, int j, int k) { return static_cast<Index>((k * side + j) * side + i); };
  for (int k = 0; k < side; ++k)
    for (int j = 0; j < side; ++j)
      for (int i = 0; i < side; ++i) mesh.points.emplace_back(i, j, k);
  const int wall = mesh.marker("wall");
  for (int k = 0; k < blocks; ++k) {
    for (int j = 0; j < blocks; ++j) {
      for (int i = 0; i < blocks; ++i) {
        const std::array<Index, 8> corner = {
            node(i, j, k),     node(i + 1, j, k),     node(i + 1, j + 1, k),     node(i, j + 1, k),
            node(i, j, k + 1), node(i + 1, j, k + 1), node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)};
        const int quarter = 4 * k / blocks;
        if (quarter == 0) {
          Index hexahedron[8];
          std::copy(corner.begin(), corner.end(), hexahedron);
          mesh.add_cell(CellType::hexahedron, hexahedron, 1);
          if (k == 0) {
            const Index floor[4] = {corner[0], corner[3], corner[2], corner[1]};
            mesh.add_face(FaceType::quad, floor, wall);
          }
        } else if (quarter == 1) {
          for (const std::array<int, 6>& half :
               {std::array<int, 6>{0, 1, 2, 4, 5, 6}, std::array<int, 6>{0, 2, 3, 4, 6, 7}}) {
            Index prism[6];
            for (int n = 0; n < 6; ++n)
              prism[n] = corner[static_cast<std::size_t>(half[static_cast<std::size_t>(n)])];
            mesh.add_cell(CellType::prism, prism, 2);
          }
        } else if (quarter == 2) {
          const auto centre = static_cast<Index>(mesh.points.size());
          mesh.points.emplace_back(i + 0.5, j + 0.5, k + 0.5);
          constexpr std::array<std::array<int, 4>, 6> sides = {
              {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}}};
          for (const auto& side_nodes : sides) {
            Index pyramid[5] = {corner[static_cast<std::size_t>(side_nodes[0])],
                                corner[static_cast<std::size_t>(side_nodes[1])],
                                corner[static_cast<std::size_t>(side_nodes[2])],
                                corner[static_cast<std::size_t>(side_nodes[3])], centre};
            mesh.add_cell(CellType::pyramid, pyramid, 3);
          }
        } else {
          // Kuhn split: six tetrahedra along the diagonal 0-6.
          constexpr std::array<std::array<int, 2>, 6> paths = {
              {{1, 2}, {1, 5}, {3, 2}, {3, 7}, {4, 5}, {4, 7}}};
          for (const auto& path : paths) {
            Index tetrahedron[4] = {corner[0], corner[static_cast<std::size_t>(path[0])],
                                    corner[static_cast<std::size_t>(path[1])], corner[6]};
            mesh.add_cell(CellType::tetrahedron, tetrahedron, 4);
          }
        }
      }
    }
  }
  reference::orient_positively(mesh);
  return mesh;
}

const MixedMesh& shared_mesh() {
  static const MixedMesh mesh = million_cell_mesh();
  return mesh;
}

std::filesystem::path file(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("mixmesh_io_benchmark_" + name);
}

void write_benchmark(benchmark::State& state, const std::string& name, WriteOptions options) {
  const MixedMesh& mesh = shared_mesh();
  for (auto _ : state) write_mesh(mesh, file(name), options);
  state.counters["cells"] = static_cast<double>(mesh.cell_count());
  state.counters["MB"] = static_cast<double>(std::filesystem::file_size(file(name))) / 1e6;
}

void read_benchmark(benchmark::State& state, const std::string& name, WriteOptions options) {
  const MixedMesh& mesh = shared_mesh();
  write_mesh(mesh, file(name), options);
  std::size_t cells = 0;
  for (auto _ : state) cells = read_mesh(file(name)).cell_count();
  if (cells != mesh.cell_count()) state.SkipWithError("the mesh read back has a different cell count");
  state.counters["cells"] = static_cast<double>(cells);
}

WriteOptions binary() {
  WriteOptions options;
  options.encoding = Encoding::binary;
  return options;
}

}  // namespace

BENCHMARK_CAPTURE(write_benchmark, vtu, "mesh.vtu", WriteOptions{})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(read_benchmark, vtu, "mesh.vtu", WriteOptions{})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(write_benchmark, msh41_ascii, "ascii.msh", WriteOptions{})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(read_benchmark, msh41_ascii, "ascii.msh", WriteOptions{})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(write_benchmark, msh41_binary, "binary.msh", binary())
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(read_benchmark, msh41_binary, "binary.msh", binary())
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(write_benchmark, su2, "mesh.su2", WriteOptions{})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(read_benchmark, su2, "mesh.su2", WriteOptions{})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(write_benchmark, cgns, "mesh.cgns", WriteOptions{})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(read_benchmark, cgns, "mesh.cgns", WriteOptions{})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

BENCHMARK_MAIN();
