// Far field on a swept, thin, high-aspect-ratio hull with the preconditioning
// variants of method.md §5: none, shear only, shear + whitening Ā^{-1/2}, shear +
// the paper's Ā⁻¹. Counters: tetrahedra, TetGen's Steiner points and the smallest
// dihedral angle (degrees) of the tetrahedra.
#include <benchmark/benchmark.h>

#include <cmath>

#include "../support/farfield_hulls.hpp"
#include "mixmesh/farfield/farfield.hpp"

using namespace mixmesh;

namespace {

// A swept slab: chord 1 (x), span 4 (y, from the symmetry plane), thickness 0.04 (z),
// leading edge swept by 30°; 12 × 12 cells on each large face, open at y = 0.
FarFieldInput swept_slab() {
  return farfield_hulls::slab({0.0, 0.0, -0.02}, {1.0, 4.0, 0.04}, {12, 12, 1}, true, 30.0);
}

double minimum_dihedral_degrees(const MixedMesh& mesh) {
  double smallest = 180.0;
  for (std::size_t cell = 0; cell < mesh.cell_count(CellType::tetrahedron); ++cell) {
    const Index* nodes = mesh.cell(CellType::tetrahedron, cell);
    auto at = [&](int local) -> const Vector3& {
      return mesh.points[static_cast<std::size_t>(nodes[local])];
    };
    for (const auto& edge : {std::array<int, 4>{0, 1, 2, 3},
                             {0, 2, 1, 3},
                             {0, 3, 1, 2},
                             {1, 2, 0, 3},
                             {1, 3, 0, 2},
                             {2, 3, 0, 1}}) {
      const Vector3 axis = (at(edge[1]) - at(edge[0])).normalized();
      Vector3 first = at(edge[2]) - at(edge[0]), second = at(edge[3]) - at(edge[0]);
      first -= first.dot(axis) * axis;
      second -= second.dot(axis) * axis;
      smallest =
          std::min(smallest, std::acos(std::clamp(first.normalized().dot(second.normalized()), -1.0, 1.0)) *
                                 180.0 / M_PI);
    }
  }
  return smallest;
}

void run(benchmark::State& state, bool precondition, bool shear, AffineMap affine) {
  const FarFieldInput input = swept_slab();
  FarFieldOptions options;
  options.radius_in_chords = 10.0;
  options.farfield_size_in_chords = 2.0;
  options.precondition = precondition;
  options.preconditioning.shear = shear;
  options.preconditioning.affine = affine;
  FarFieldResult result;
  for (auto _ : state) result = farfield(input, options);
  state.counters["tetrahedra"] = static_cast<double>(result.mesh.cell_count(CellType::tetrahedron));
  state.counters["steiner"] = static_cast<double>(result.steiner_points);
  state.counters["min_dihedral"] = minimum_dihedral_degrees(result.mesh);
}

}  // namespace

BENCHMARK_CAPTURE(run, none, false, false, AffineMap::none)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(run, shear, true, true, AffineMap::none)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(run, shear_whitening, true, true, AffineMap::whitening)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(run, shear_inverse, true, true, AffineMap::inverse)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(run, whitening, true, false, AffineMap::whitening)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
