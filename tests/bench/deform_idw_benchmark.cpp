// IDW deformation timings on a synthetic case: a wing-like ellipsoid (length 1, 50 k
// surface nodes) pitched by 5° inside a fixed sphere, 1 M volume points in 50 layers
// growing geometrically from 0.001 to 10 body lengths off the surface.
//
//   BM_IdwSimpleTree       eq. (1) with the tree code, all 1 M points (threads: TBB)
//   BM_IdwSimpleTreeSample/T the tree code (tolerance T·1e-6) on 20 k points drawn from the
//                          1 M; counters give the largest difference from the exact sum
//                          (relative to the body length) and the speed-up over the exact
//                          sum in process CPU time
//   BM_IdwSimpleExactSample the exact sum on the same 20 k points
//   BM_IdwRotationForm     eq. (2–4), all 1 M points
//
// Run: deform_idw_benchmark --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>

#include <cmath>
#include <ctime>
#include <random>

#include "mixmesh/deform/idw.hpp"

namespace mixmesh::deform {
namespace {

constexpr double pi = 3.14159265358979323846;
const Vector3 semi_axes(0.5, 0.1, 0.05);

Vector3 ellipsoid_point(double u, double v, const Vector3& axes) {
  return Vector3(axes.x() * std::cos(u) * std::sin(v), axes.y() * std::sin(u) * std::sin(v),
                 axes.z() * std::cos(v));
}

struct SyntheticCase {
  IdwInput input;
  std::vector<Vector3> sample;  // 20 k volume points drawn from input.volume_points
};

const SyntheticCase& synthetic_case() {
  static const SyntheticCase data = [] {
    SyntheticCase result;
    IdwBody wing;
    wing.name = "wing";
    const Eigen::Matrix3d pitch = Eigen::AngleAxisd(-5.0 * pi / 180.0, Vector3::UnitZ()).toRotationMatrix();
    const Vector3 centre(0.125, 0.0, 0.0);  // quarter chord
    const int around = 400, across = 125;   // 50 000 surface nodes
    for (int i = 0; i < around; ++i)
      for (int j = 0; j < across; ++j) {
        const Vector3 x = ellipsoid_point(2.0 * pi * i / around, pi * (j + 0.5) / across, semi_axes);
        wing.positions.push_back(x);
        wing.displacements.push_back(pitch * (x - centre) + centre - x);
      }
    IdwBody farfield;
    farfield.name = "farfield";
    farfield.moving = false;
    for (int i = 0; i < 80; ++i)
      for (int j = 0; j < 40; ++j)
        farfield.positions.push_back(
            ellipsoid_point(2.0 * pi * i / 80, pi * (j + 0.5) / 40, Vector3::Constant(20.0)));
    result.input.bodies = {wing, farfield};

    // 1 000 000 volume points: 200 × 100 directions × 50 layers.
    for (int layer = 0; layer < 50; ++layer) {
      const double offset = 0.001 * std::pow(1e4, layer / 49.0);
      for (int i = 0; i < 200; ++i)
        for (int j = 0; j < 100; ++j)
          result.input.volume_points.push_back(ellipsoid_point(
              2.0 * pi * (i + 0.3) / 200, pi * (j + 0.7) / 100, semi_axes + Vector3::Constant(offset)));
    }
    std::mt19937 generator(7);
    std::uniform_int_distribution<std::size_t> pick(0, result.input.volume_points.size() - 1);
    for (int k = 0; k < 20000; ++k) result.sample.push_back(result.input.volume_points[pick(generator)]);
    return result;
  }();
  return data;
}

IdwOptions simple_options(bool exact, double tolerance = IdwOptions{}.tree_tolerance) {
  IdwOptions options;
  options.form = IdwForm::simple;
  options.exact = exact;
  options.tree_tolerance = tolerance;
  return options;
}

// Process CPU time of all threads: wall-clock time on an idle machine is about this
// divided by the core count; other jobs on a shared machine inflate the wall clock.
double process_seconds(std::clock_t start) {
  return static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
}

void BM_IdwSimpleTree(benchmark::State& state) {
  const SyntheticCase& data = synthetic_case();
  IdwResult result;
  double cpu = 0.0;
  for (auto _ : state) {
    const std::clock_t start = std::clock();
    result = idw_deform(data.input, simple_options(false));
    cpu = process_seconds(start);
    benchmark::DoNotOptimize(result.displacements.data());
  }
  state.counters["process_cpu_seconds"] = cpu;
  state.counters["nodes"] = static_cast<double>(data.input.volume_points.size());
  state.counters["terms_per_node"] =
      static_cast<double>(result.cluster_terms + result.node_terms) / data.input.volume_points.size();
  state.counters["error_bound"] = result.error_bound;
}

IdwInput sample_input() {
  IdwInput input = synthetic_case().input;
  input.volume_points = synthetic_case().sample;
  return input;
}

void BM_IdwSimpleExactSample(benchmark::State& state) {
  const IdwInput input = sample_input();
  for (auto _ : state) {
    const IdwResult result = idw_deform(input, simple_options(true));
    benchmark::DoNotOptimize(result.displacements.data());
  }
}

void BM_IdwSimpleTreeSample(benchmark::State& state) {
  const IdwInput input = sample_input();
  // Reference once, outside the timed loop.
  // Speed-up in process CPU time (all threads), which other jobs on the machine disturb
  // less than wall-clock time.
  const std::clock_t exact_start = std::clock();
  const IdwResult exact = idw_deform(input, simple_options(true));
  const double exact_seconds = process_seconds(exact_start);
  IdwResult tree;
  double tree_seconds = 0.0;
  for (auto _ : state) {
    const std::clock_t start = std::clock();
    tree = idw_deform(input, simple_options(false, 1e-6 * static_cast<double>(state.range(0))));
    tree_seconds = process_seconds(start);
    benchmark::DoNotOptimize(tree.displacements.data());
  }
  double largest = 0.0;
  for (std::size_t i = 0; i < exact.displacements.size(); ++i)
    largest = std::max(largest, (tree.displacements[i] - exact.displacements[i]).norm());
  state.counters["max_difference_per_length"] = largest / (2.0 * semi_axes.x());
  state.counters["speedup"] = exact_seconds / tree_seconds;
  state.counters["clusters_per_node"] = static_cast<double>(tree.cluster_terms) / input.volume_points.size();
  state.counters["nodes_per_node"] = static_cast<double>(tree.node_terms) / input.volume_points.size();
}

void BM_IdwRotationForm(benchmark::State& state) {
  const SyntheticCase& data = synthetic_case();
  double cpu = 0.0;
  for (auto _ : state) {
    const std::clock_t start = std::clock();
    const IdwResult result = idw_deform(data.input, IdwOptions{});
    cpu = process_seconds(start);
    benchmark::DoNotOptimize(result.displacements.data());
  }
  state.counters["process_cpu_seconds"] = cpu;
  state.counters["nodes"] = static_cast<double>(data.input.volume_points.size());
}

BENCHMARK(BM_IdwSimpleTree)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);
// Argument: tree tolerance in units of 1e-6 (the default is 30).
BENCHMARK(BM_IdwSimpleTreeSample)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1)
    ->Arg(1000)
    ->Arg(100)
    ->Arg(30)
    ->Arg(10);
BENCHMARK(BM_IdwSimpleExactSample)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_IdwRotationForm)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

}  // namespace
}  // namespace mixmesh::deform

BENCHMARK_MAIN();
