// ARA deformation of a 1 M-node hexahedral O-grid around an ellipse (200 × 100 × 50
// nodes), the body pitched 5° about its quarter chord: the first deformation (nearest
// faces searched) and a repeat with the cached nearest faces.
//   deform_ara_benchmark --benchmark_repetitions=3
#include <benchmark/benchmark.h>

#include "../support/deform_meshes.hpp"
#include "mixmesh/deform/ara.hpp"

namespace {

using namespace mixmesh;

const MixedMesh& million_node_mesh() {
  static const MixedMesh mesh = [] {
    testing::OGrid grid;
    grid.around = 200;
    grid.outward = 100;
    grid.layers_z = 49;
    grid.first_spacing = 0.001;
    grid.outer_radius = 20.0;
    grid.height = 2.0;
    return testing::volume_o_grid(grid, testing::VolumeKind::hexahedron);
  }();
  return mesh;
}

deform::Motion pitch() {
  deform::Body body;
  body.markers = {"wall"};
  body.centre = Vector3(-0.5, 0.0, 0.0);
  body.angle = 5.0;
  deform::Motion motion;
  motion.bodies = {body};
  motion.symmetry = {"bottom", "top"};
  return motion;
}

void first_deformation(benchmark::State& state) {
  const MixedMesh& mesh = million_node_mesh();
  const deform::BoundaryMotion boundary = deform::boundary_motion(mesh, mesh, pitch(), 1);
  const Log log;
  for (auto _ : state) {
    deform::AraMethod method;
    benchmark::DoNotOptimize(method.move(mesh, boundary, log));
    state.counters["inverted"] = static_cast<double>(method.last_report().inverted_after_repair);
    state.counters["iterations"] = method.last_report().smoothing_iterations;
    state.counters["distance_s"] = method.last_report().distance_seconds;
  }
  state.counters["nodes"] = static_cast<double>(mesh.points.size());
}

void cached_deformation(benchmark::State& state) {
  const MixedMesh& mesh = million_node_mesh();
  const deform::BoundaryMotion boundary = deform::boundary_motion(mesh, mesh, pitch(), 1);
  const Log log;
  deform::AraMethod method;
  method.move(mesh, boundary, log);  // fills the cache
  for (auto _ : state) {
    benchmark::DoNotOptimize(method.move(mesh, boundary, log));
    state.counters["cache_used"] = method.last_report().cache_used;
    state.counters["distance_s"] = method.last_report().distance_seconds;
  }
}

// The whole step as the command runs it: boundary motion, ARA, validation, quality.
void checked_step(benchmark::State& state) {
  const MixedMesh& mesh = million_node_mesh();
  const Log log;
  for (auto _ : state) {
    deform::AraMethod method;
    const deform::DeformResult result = deform::deform_step(mesh, mesh, pitch(), 1, method, log);
    state.counters["valid"] = result.valid;
  }
}

BENCHMARK(first_deformation)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK(cached_deformation)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK(checked_step)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
