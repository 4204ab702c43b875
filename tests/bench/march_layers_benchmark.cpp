// 32 layers on the paper-scale ONERA M6 surface of cases/onera_m6.toml (200 x 40 wing
// faces, the wake and the tip cap), marched by the smoothed method (layer corrector by
// Jacobi sweeps or by a sparse solve per layer) and by the plain-normal baseline.
// Times are wall-clock (the march runs on all cores).
#include <benchmark/benchmark.h>

#include <filesystem>

#include "mixmesh/config/config.hpp"
#include "mixmesh/march/march_layers.hpp"
#include "mixmesh/pipeline/surface_options.hpp"

namespace {

// The surface of the case file itself ([wing] and [surface]), so the benchmark follows
// the case when it changes.
const mixmesh::SurfaceMesh& onera_m6_surface() {
  static const mixmesh::SurfaceMesh surface = [] {
    const auto case_file =
        std::filesystem::path(__FILE__).parent_path() / ".." / ".." / "cases" / "onera_m6.toml";
    mixmesh::config::Document document = mixmesh::config::Document::load(case_file);
    mixmesh::config::Section root = document.root();
    return mixmesh::build_surface(mixmesh::read_surface_setup(root));
  }();
  return surface;
}

void march(benchmark::State& state, mixmesh::MarchMethod method, bool intersection_check = true,
           mixmesh::LayerSolve layer_solve = mixmesh::LayerSolve::sweeps, int sweeps = 12) {
  const mixmesh::SurfaceMesh& surface = onera_m6_surface();
  mixmesh::MarchOptions options;  // 32 layers, y+ = 1 at Re 11.72e6 on the MAC
  options.method = method;
  options.check_self_intersection = intersection_check;
  options.layer_solve = layer_solve;
  options.sweeps = sweeps;
  std::size_t cells = 0;
  mixmesh::MarchReport report;
  for (auto _ : state) {
    const mixmesh::BoundaryLayer layer = mixmesh::march_layers(surface, options);
    cells = layer.mesh.cell_count();
    report = layer.report;
    benchmark::DoNotOptimize(cells);
  }
  state.counters["cells"] = static_cast<double>(cells);
  state.counters["stopped_faces"] = report.stopped_faces;
  state.counters["corrector_iterations"] = report.corrector_iterations;
  state.counters["corrector_change"] = report.corrector_change;
}

void smoothed_march(benchmark::State& state) {
  march(state, mixmesh::MarchMethod::smoothed);
}
void smoothed_march_sparse_layer_solve(benchmark::State& state) {
  march(state, mixmesh::MarchMethod::smoothed, true, mixmesh::LayerSolve::sparse);
}
// The sweeps run until they reach about the sparse solve's convergence (docs/march.md).
void smoothed_march_100_sweeps(benchmark::State& state) {
  march(state, mixmesh::MarchMethod::smoothed, true, mixmesh::LayerSolve::sweeps, 100);
}
void normal_extrusion(benchmark::State& state) {
  march(state, mixmesh::MarchMethod::normal);
}
void smoothed_march_without_intersection_check(benchmark::State& state) {
  march(state, mixmesh::MarchMethod::smoothed, false);
}

}  // namespace

BENCHMARK(smoothed_march)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime()
    ->Repetitions(5)
    ->ReportAggregatesOnly(true);
BENCHMARK(smoothed_march_sparse_layer_solve)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime()
    ->Repetitions(3)
    ->ReportAggregatesOnly(true);
BENCHMARK(smoothed_march_100_sweeps)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime()
    ->Repetitions(3)
    ->ReportAggregatesOnly(true);
BENCHMARK(smoothed_march_without_intersection_check)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime()
    ->Repetitions(3)
    ->ReportAggregatesOnly(true);
BENCHMARK(normal_extrusion)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime()
    ->Repetitions(3)
    ->ReportAggregatesOnly(true);
BENCHMARK_MAIN();
