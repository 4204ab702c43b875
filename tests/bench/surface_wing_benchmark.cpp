// The ONERA M6 surface mesh at the paper's resolution (200 x 80 wing faces, C-type
// wake, triangulated tip), from the case file to the SurfaceMesh.
#include <benchmark/benchmark.h>

#include <filesystem>

#include "mixmesh/config/config.hpp"
#include "mixmesh/pipeline/surface_options.hpp"
#include "mixmesh/pipeline/wing_options.hpp"
#include "mixmesh/surface/wing_surface.hpp"

namespace {

void onera_m6_surface(benchmark::State& state) {
  mixmesh::config::Document document = mixmesh::config::Document::load(
      std::filesystem::path(__FILE__).parent_path() / "../../cases/onera_m6.toml");
  mixmesh::config::Section root = document.root();
  mixmesh::config::Section wing_table = root.section("wing");
  mixmesh::config::Section surface_table = root.section("surface");
  const mixmesh::WingDefinition wing = mixmesh::read_wing_definition(wing_table);
  const mixmesh::SurfaceOptions options = mixmesh::read_surface_options(surface_table);
  std::size_t faces = 0;
  for (auto _ : state) {
    const mixmesh::SurfaceMesh surface = mixmesh::generate_wing_surface(wing, options);
    benchmark::DoNotOptimize(surface.points.data());
    faces = surface.unstructured[0].triangles.size() / 3;
    for (const auto& patch : surface.structured)
      faces += static_cast<std::size_t>((patch.ni - 1) * (patch.nj - 1));
  }
  state.counters["surface_faces"] = static_cast<double>(faces);
}
BENCHMARK(onera_m6_surface)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);

}  // namespace

BENCHMARK_MAIN();
