// ARA deformation of a 1 M-node hexahedral O-grid around an ellipse (200 × 100 × 50
// nodes), the body pitched 5° about its quarter chord: the first deformation (nearest
// faces searched, geometry prepared) and a repeat with both cached, each with the
// conjugate-gradient smoothing (argument 0), the Gauss–Seidel one (argument 1) and the
// conjugate-gradient one converged to a 100 times tighter tolerance (argument 2), where
// the smoothing does many iterations in both runs; and
// the whole checked step as the command runs it. Counters: seconds per stage.
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

void report_stages(benchmark::State& state, const deform::AraReport& report) {
  state.counters["setup_s"] = report.setup_seconds;
  state.counters["distance_s"] = report.distance_seconds;
  state.counters["predictor_s"] = report.predictor_seconds;
  state.counters["smoothing_s"] = report.smoothing_seconds;
  state.counters["interpolation_s"] = report.interpolation_seconds;
  state.counters["repair_s"] = report.repair_seconds;
  state.counters["spin_iterations"] = report.spin_iterations;
  state.counters["iterations"] = report.smoothing_iterations;
  state.counters["total_s"] = report.total_seconds;
}

deform::AraOptions solver_options(const benchmark::State& state) {
  deform::AraOptions options;
  options.solver = state.range(0) == 1 ? deform::Solver::gauss_seidel : deform::Solver::conjugate_gradient;
  if (state.range(0) == 2) options.tolerance *= 0.01;
  return options;
}

void first_deformation(benchmark::State& state) {
  const MixedMesh& mesh = million_node_mesh();
  const deform::BoundaryMotion boundary = deform::boundary_motion(mesh, mesh, pitch(), 1);
  const Log log;
  for (auto _ : state) {
    deform::AraMethod method(solver_options(state));
    benchmark::DoNotOptimize(method.move(mesh, boundary, log));
    state.counters["inverted"] = static_cast<double>(method.last_report().inverted_after_repair);
    report_stages(state, method.last_report());
  }
  state.counters["nodes"] = static_cast<double>(mesh.points.size());
}

void cached_deformation(benchmark::State& state) {
  const MixedMesh& mesh = million_node_mesh();
  const deform::BoundaryMotion boundary = deform::boundary_motion(mesh, mesh, pitch(), 1);
  const Log log;
  deform::AraMethod method(solver_options(state));
  method.move(mesh, boundary, log);  // fills the caches
  for (auto _ : state) {
    benchmark::DoNotOptimize(method.move(mesh, boundary, log));
    state.counters["cache_used"] = method.last_report().cache_used;
    state.counters["geometry_cached"] = method.last_report().geometry_cached;
    report_stages(state, method.last_report());
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
    state.counters["ara_s"] = method.last_report().total_seconds;
    state.counters["step_s"] = result.seconds;
  }
}

BENCHMARK(first_deformation)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK(cached_deformation)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK(checked_step)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
