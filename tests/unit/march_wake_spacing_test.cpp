#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "march_surfaces.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/march/march_layers.hpp"
#include "mixmesh/march/spacing.hpp"

namespace mixmesh {
namespace {

double sum(const std::vector<double>& steps) {
  return std::accumulate(steps.begin(), steps.end(), 0.0);
}

// The ONERA M6 wall stack: 32 layers from 1.546 µm, growth 1.25 (7.8 mm).
std::vector<double> wall_stack() {
  SpacingOptions options;
  return layer_steps(options);
}

TEST(MarchWakeSpacing, TrailingEdgeAndNoSpreadKeepTheWallSteps) {
  const std::vector<double> wall = wall_stack();
  EXPECT_EQ(wake_layer_steps(wall, 0.0, 6.0), wall);
  EXPECT_EQ(wake_layer_steps(wall, 8.4, 0.0), wall);
}

TEST(MarchWakeSpacing, ThicknessGrowsAsAWedge) {
  const std::vector<double> wall = wall_stack();
  const double thickness = sum(wall);
  // s = x^2 / (x + 1) wall thicknesses, x = d tan(spread) / T0.
  auto wedge = [&](double distance, double spread) {
    const double x = distance * std::tan(spread * M_PI / 180.0) / thickness;
    return x * x / (x + 1.0);
  };
  for (double distance : {0.002, 0.1, 1.0, 8.4})
    for (double spread : {1.0, 6.0, 20.0})
      EXPECT_NEAR(sum(wake_layer_steps(wall, distance, spread)), thickness * (1.0 + wedge(distance, spread)),
                  1e-12 * (1.0 + distance))
          << distance << " m, " << spread << " deg";
}

TEST(MarchWakeSpacing, GeometricStackStaysGeometricWithRelaxedGrowth) {
  const std::vector<double> wall = wall_stack();
  // x = d tan(6 deg) / T0, s = x^2 / (x + 1), b = s / (s + 16): the growth becomes
  // 1.25^(1 - b).
  const double distance = 2.0;
  const double x = distance * std::tan(6.0 * M_PI / 180.0) / sum(wall);
  const double s = x * x / (x + 1.0);
  const double growth = std::pow(1.25, 1.0 - s / (s + 16.0));
  const std::vector<double> steps = wake_layer_steps(wall, distance, 6.0);
  ASSERT_EQ(steps.size(), wall.size());
  for (std::size_t k = 1; k < steps.size(); ++k) EXPECT_NEAR(steps[k] / steps[k - 1], growth, 1e-12);
}

TEST(MarchWakeSpacing, FirstStepRelaxesDownstreamSmoothly) {
  // Along a wake line of cells growing by 1.2 from 2 mm (the M6 wake), every step grows
  // monotonically downstream, by at most 1.56 from one cell to the next; at the wake's
  // end (8.4 m) the first step is millimetres, not the wall's micrometres, and stays
  // below the mean step.
  const std::vector<double> wall = wall_stack();
  std::vector<double> before = wall;
  double distance = 0.0, cell = 0.002;
  while (distance < 8.4) {
    distance += cell;
    cell *= 1.2;
    const std::vector<double> steps = wake_layer_steps(wall, distance, 6.0);
    for (std::size_t k = 0; k < steps.size(); ++k) {
      EXPECT_GE(steps[k], before[k]) << "layer " << k << " at " << distance << " m";
      EXPECT_LE(steps[k], 1.56 * before[k]) << "layer " << k << " at " << distance << " m";
    }
    before = steps;
  }
  EXPECT_GT(before.front(), 1e-2);
  EXPECT_LT(before.front(), sum(before) / static_cast<double>(before.size()));
  EXPECT_GT(before.back(), before.front());
}

TEST(MarchWakeSpacing, WorksForTanhStacks) {
  SpacingOptions options;
  options.growth_law = GrowthLaw::tanh;
  options.first_spacing = 1e-5;
  options.layer_count = 20;
  options.total_thickness = 0.01;
  const std::vector<double> wall = layer_steps(options);
  const std::vector<double> steps = wake_layer_steps(wall, 1.0, 3.0);
  const double x = std::tan(3.0 * M_PI / 180.0) / 0.01;
  EXPECT_NEAR(sum(steps), 0.01 * (1.0 + x * x / (x + 1.0)), 1e-12);
  for (std::size_t k = 1; k < steps.size(); ++k) EXPECT_GT(steps[k], steps[k - 1]);
  EXPECT_GT(steps.front(), wall.front());
}

TEST(MarchWakeSpacing, RejectsBadInput) {
  const std::vector<double> wall = wall_stack();
  EXPECT_THROW(wake_layer_steps(wall, -1.0, 6.0), Error);
  EXPECT_THROW(wake_layer_steps(wall, std::nan(""), 6.0), Error);
  EXPECT_THROW(wake_layer_steps(wall, 1.0, -1.0), Error);
  EXPECT_THROW(wake_layer_steps(wall, 1.0, 45.0), Error);
  EXPECT_THROW(wake_layer_steps({1e-3, 0.0}, 1.0, 6.0), Error);
  try {
    wake_layer_steps(wall, 1.0, 50.0);
    FAIL() << "a spread of 50 degrees was accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("50"), std::string::npos) << error.what();
  }
}

// Segment lengths of every marching line of a wing with a 2-chord wake: wall lines keep
// the wall's steps (the wing's layers do not change), wake lines thicken downstream with
// the spread and keep the wall's steps without it.
TEST(MarchWakeSpacing, WakeLinesThickenAndWallLinesKeepTheirSteps) {
  march_surfaces::TestWing test;
  test.chordwise_cells = 32;
  test.spanwise_cells = 8;
  const SurfaceMesh surface = march_surfaces::wing(test);
  MarchOptions options;
  options.spacing.layer_count = 12;
  options.spacing.first_spacing = 1e-4;
  options.spacing.growth_rate = 1.25;
  // The growth laws alone: the outermost layer keeps its law's step.
  options.outer_layer_height = 0.0;
  const std::vector<double> wall = layer_steps(options.spacing);
  for (double spread : {0.0, 6.0}) {
    options.wake_spread_degrees = spread;
    const BoundaryLayer layer = march_layers(surface, options);
    EXPECT_EQ(layer.report.stopped_faces, 0);
    EXPECT_EQ(march_surfaces::invalid_cell_count(layer.mesh), 0);
    double largest_first = 0.0;
    int wall_lines = 0, wake_lines = 0;
    for (std::size_t c = 0; c < layer.column_points.size(); ++c) {
      const std::vector<Index>& line = layer.column_points[c];
      ASSERT_EQ(line.size(), wall.size() + 1);
      auto segment = [&](std::size_t k) {
        return (layer.mesh.points[static_cast<std::size_t>(line[k + 1])] -
                layer.mesh.points[static_cast<std::size_t>(line[k])])
            .norm();
      };
      if (layer.column_side[c] == 0 || spread == 0.0) {
        // Wall lines (and every line without the spread): the wall's steps. Lines that
        // start on the wall and on the sheet (the trailing edge) count as wall lines.
        const bool wall_line = layer.column_side[c] == 0;
        wall_lines += wall_line ? 1 : 0;
        wake_lines += wall_line ? 0 : 1;
        for (std::size_t k = 0; k < wall.size(); ++k) EXPECT_NEAR(segment(k), wall[k], 1e-9 * wall[k]);
      } else {
        ++wake_lines;
        largest_first = std::max(largest_first, segment(0));
        EXPECT_GE(segment(0), wall.front() * (1.0 - 1e-9));
      }
    }
    EXPECT_GT(wall_lines, 0);
    EXPECT_GT(wake_lines, 0);
    // 2 chords downstream at 6 degrees the wedge adds about 0.2 m to the 5.4 mm of the
    // wall stack: the first step there is about a hundred times the wall's.
    if (spread > 0.0) {
      EXPECT_GT(largest_first, 10.0 * wall.front());
    }
  }
  options.wake_spread_degrees = 50.0;
  EXPECT_THROW(march_layers(surface, options), Error);
}

}  // namespace
}  // namespace mixmesh
