// IDW deformation timings on a synthetic case: a wing-like ellipsoid (length 1, 50 k
// surface nodes) pitched by 5° inside a fixed sphere, 1 M volume points in 50 layers
// growing geometrically from 0.001 to 10 body lengths off the surface.
//
//   BM_IdwSimpleTree       eq. (1) with the tree code, all 1 M points (threads: TBB); counters
//                          compare it with the exact sum on 20 k of the points, whose CPU
//                          time is scaled linearly to 1 M (speedup) and whose results give
//                          the largest difference relative to the body length
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
  std::vector<std::size_t> sample_indices;  // 20 k volume points drawn from input.volume_points
  std::vector<Vector3> sample;
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
    for (int k = 0; k < 20000; ++k) {
      result.sample_indices.push_back(pick(generator));
      result.sample.push_back(result.input.volume_points[result.sample_indices.back()]);
    }
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

IdwInput sample_input() {
  IdwInput input = synthetic_case().input;
  input.volume_points = synthetic_case().sample;
  return input;
}

// The exact sum on the 20 k sample, and its process CPU time scaled to all 1 M points (the
// exact sum costs the same for every point); computed once.
struct ExactReference {
  IdwResult result;
  double scaled_cpu_seconds = 0.0;
};

const ExactReference& exact_reference() {
  static const ExactReference reference = [] {
    ExactReference computed;
    const std::clock_t start = std::clock();
    computed.result = idw_deform(sample_input(), simple_options(true));
    computed.scaled_cpu_seconds = process_seconds(start) *
                                  static_cast<double>(synthetic_case().input.volume_points.size()) /
                                  static_cast<double>(synthetic_case().sample.size());
    return computed;
  }();
  return reference;
}

// The tree code on all 1 M points; against the exact sum on the sample (time scaled).
void BM_IdwSimpleTree(benchmark::State& state) {
  const SyntheticCase& data = synthetic_case();
  const ExactReference& exact = exact_reference();
  IdwResult result;
  double cpu = 0.0;
  for (auto _ : state) {
    const std::clock_t start = std::clock();
    result = idw_deform(data.input, simple_options(false));
    cpu = process_seconds(start);
    benchmark::DoNotOptimize(result.displacements.data());
  }
  double largest = 0.0;
  for (std::size_t k = 0; k < data.sample_indices.size(); ++k)
    largest = std::max(largest,
                       (result.displacements[data.sample_indices[k]] - exact.result.displacements[k]).norm());
  state.counters["process_cpu_seconds"] = cpu;
  state.counters["exact_cpu_seconds_scaled"] = exact.scaled_cpu_seconds;
  state.counters["speedup"] = exact.scaled_cpu_seconds / cpu;
  state.counters["max_difference_per_length"] = largest / (2.0 * semi_axes.x());
  state.counters["terms_per_node"] =
      static_cast<double>(result.cluster_terms + result.node_terms) / data.input.volume_points.size();
  state.counters["error_bound"] = result.error_bound;
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
  // Speed-up in process CPU time (all threads), which other jobs on the machine disturb
  // less than wall-clock time; the reference is computed once, outside the timed loop.
  const IdwResult& exact = exact_reference().result;
  const double exact_seconds = exact_reference().scaled_cpu_seconds *
                               static_cast<double>(input.volume_points.size()) /
                               static_cast<double>(synthetic_case().input.volume_points.size());
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
// Argument: tree tolerance in units of 1e-6 (the default is 4).
BENCHMARK(BM_IdwSimpleTreeSample)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1)
    ->Arg(100)
    ->Arg(20)
    ->Arg(8)
    ->Arg(4)
    ->Arg(2)
    ->Arg(1);
BENCHMARK(BM_IdwSimpleExactSample)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_IdwRotationForm)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

}  // namespace
}  // namespace mixmesh::deform

BENCHMARK_MAIN();
