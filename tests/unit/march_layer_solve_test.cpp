// The two solvers of the layer corrector (Jacobi sweeps, sparse solve of the whole
// layer) solve the same equations: converged, they give the same layers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "march_surfaces.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/march/march_metrics.hpp"

namespace mixmesh {
namespace {

MarchOptions options_for(LayerSolve solve, int iterations, int layers) {
  MarchOptions options;
  options.spacing.layer_count = layers;
  options.spacing.first_spacing = 1e-4;
  options.spacing.growth_rate = 1.25;
  options.layer_solve = solve;
  options.sweeps = iterations;
  options.layer_tolerance = 1e-10;
  return options;
}

// Largest distance between the same points of two marches of one surface.
double largest_difference(const BoundaryLayer& a, const BoundaryLayer& b) {
  EXPECT_EQ(a.mesh.points.size(), b.mesh.points.size());
  double largest = 0.0;
  for (std::size_t p = 0; p < std::min(a.mesh.points.size(), b.mesh.points.size()); ++p)
    largest = std::max(largest, (a.mesh.points[p] - b.mesh.points[p]).norm());
  return largest;
}

void expect_valid(const BoundaryLayer& layer, const SurfaceMesh& surface) {
  EXPECT_EQ(march_surfaces::invalid_cell_count(layer.mesh), 0);
  EXPECT_EQ(layer.report.stopped_faces, 0);
  EXPECT_TRUE(match_faces(layer.mesh).conforming());
  // Lines starting in the symmetry plane stay exactly in it.
  for (std::size_t c = 0; c < layer.column_points.size(); ++c)
    if (surface.symmetry_tolerance >= 0.0 &&
        std::abs(surface.points[static_cast<std::size_t>(layer.column_node[c])].y() - surface.symmetry_y) <=
            surface.symmetry_tolerance)
      for (Index point : layer.column_points[c]) {
        EXPECT_EQ(layer.mesh.points[static_cast<std::size_t>(point)].y(), surface.symmetry_y);
      }
}

// The triangle patch of march_surfaces bent round a unit cylinder (axis along y),
// convex side out: prism rings whose layers grow as thick as the cells are wide.
SurfaceMesh bent_triangle_patch() {
  SurfaceMesh surface = march_surfaces::triangle_patch(4, 0.1);
  for (Vector3& point : surface.points)
    point = Vector3(std::sin(point.x()), point.y(), std::cos(point.x()) - 1.0);
  return surface;
}

void expect_same_converged_layers(const SurfaceMesh& surface, double first_spacing, int layers) {
  MarchOptions options = options_for(LayerSolve::sparse, 50, layers);
  options.spacing.first_spacing = first_spacing;
  const BoundaryLayer sparse = march_layers(surface, options);
  options.layer_solve = LayerSolve::sweeps;
  options.sweeps = 3000;
  const BoundaryLayer sweeps = march_layers(surface, options);
  expect_valid(sparse, surface);
  expect_valid(sweeps, surface);
  // The sparse solve converged, in far fewer outer iterations than sweeps.
  EXPECT_LT(sparse.report.corrector_change, options.layer_tolerance);
  EXPECT_LT(sparse.report.corrector_iterations, layers * 50);
  const double thickness = sparse.report.total_thickness;
  const double difference = largest_difference(sparse, sweeps);
  std::printf("thickness %.4g m, largest node difference %.3g m, sweeps' last change %.3g\n", thickness,
              difference, sweeps.report.corrector_change);
  EXPECT_LT(difference, 1e-9 * thickness);
  // And the corrector did move the nodes: without it the layers differ.
  options.sweeps = 0;
  const BoundaryLayer uncorrected = march_layers(surface, options);
  EXPECT_GT(largest_difference(sparse, uncorrected), 1e-3 * thickness);
}

// Structured stencils, free edges, and rings closed by their mirror image in the
// symmetry plane (the row y = 0).
TEST(MarchLayerSolve, SparseSolveAndConvergedSweepsGiveTheSameCylinderLayers) {
  expect_same_converged_layers(march_surfaces::cylinder_patch(17, 9), 0.005, 16);
}

// Prism rings (Wild eq. (6)).
TEST(MarchLayerSolve, SparseSolveAndConvergedSweepsGiveTheSameTriangleLayers) {
  expect_same_converged_layers(bent_triangle_patch(), 0.005, 12);
}

// With the default options on a wing with a wake and a tip cap, both are valid and
// close; the sweeps stop short of convergence (docs/march.md).
TEST(MarchLayerSolve, BothSolversGiveValidWingLayers) {
  const SurfaceMesh surface = march_surfaces::wing(march_surfaces::TestWing{});
  MarchOptions options;
  options.spacing.target_y_plus = 1.0;
  options.spacing.reynolds_number = 1e7;
  options.spacing.reference_length = 1.0;
  const BoundaryLayer sweeps = march_layers(surface, options);
  options.layer_solve = LayerSolve::sparse;
  const BoundaryLayer sparse = march_layers(surface, options);
  expect_valid(sweeps, surface);
  expect_valid(sparse, surface);
  EXPECT_LT(sparse.report.corrector_change, options.layer_tolerance);
  const double difference = largest_difference(sparse, sweeps);
  std::printf("wing: thickness %.4g m, largest node difference %.3g m, sweeps' last change %.3g\n",
              sparse.report.total_thickness, difference, sweeps.report.corrector_change);
  EXPECT_LT(difference, 1e-3 * sparse.report.total_thickness);
}

TEST(MarchLayerSolve, RejectsInvalidSolverOptions) {
  const SurfaceMesh plate = march_surfaces::flat_plate(4, 4);
  MarchOptions negative;
  negative.layer_solve = LayerSolve::sparse;
  negative.layer_tolerance = -1e-4;
  EXPECT_THROW(march_layers(plate, negative), Error);
  MarchOptions not_a_number;
  not_a_number.layer_tolerance = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(march_layers(plate, not_a_number), Error);
  MarchOptions unknown;
  unknown.layer_solve = static_cast<LayerSolve>(7);
  try {
    march_layers(plate, unknown);
    ADD_FAILURE() << "an unknown layer solve was accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("layer solve"), std::string::npos);
  }
}

}  // namespace
}  // namespace mixmesh
