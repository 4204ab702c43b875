#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "mixmesh/core/error.hpp"
#include "mixmesh/march/spacing.hpp"

namespace mixmesh {
namespace {

TEST(MarchSpacing, YPlusEstimateForTheOneraM6) {
  // Cf = 0.026 / (11.72e6)^(1/7) = 2.541e-3; sqrt(Cf / 2) = 3.565e-2;
  // spacing = 0.646 / (11.72e6 * 3.565e-2) = 1.546e-6 m.
  EXPECT_NEAR(first_spacing_from_y_plus(1.0, 11.72e6, 0.646), 1.546e-6, 0.005e-6);
  // Linear in y+ and in the length at fixed Reynolds number.
  EXPECT_NEAR(first_spacing_from_y_plus(2.0, 11.72e6, 0.646),
              2.0 * first_spacing_from_y_plus(1.0, 11.72e6, 0.646), 1e-18);
  EXPECT_NEAR(first_spacing_from_y_plus(1.0, 11.72e6, 1.292),
              2.0 * first_spacing_from_y_plus(1.0, 11.72e6, 0.646), 1e-18);
  // The defaults are the M6 test point.
  SpacingOptions defaults;
  EXPECT_EQ(defaults.layer_count, 32);
  EXPECT_NEAR(layer_steps(defaults).front(), 1.546e-6, 0.005e-6);
}

TEST(MarchSpacing, GeometricGrowth) {
  SpacingOptions options;
  options.first_spacing = 1e-3;
  options.layer_count = 5;
  options.growth_rate = 1.5;
  const std::vector<double> steps = layer_steps(options);
  ASSERT_EQ(steps.size(), 5u);
  for (std::size_t k = 0; k < steps.size(); ++k) EXPECT_NEAR(steps[k], 1e-3 * std::pow(1.5, k), 1e-15);
}

TEST(MarchSpacing, TanhGrowthMeetsFirstSpacingAndThickness) {
  SpacingOptions options;
  options.growth_law = GrowthLaw::tanh;
  options.first_spacing = 1e-5;
  options.layer_count = 32;
  options.total_thickness = 0.01;
  const std::vector<double> steps = layer_steps(options);
  ASSERT_EQ(steps.size(), 32u);
  EXPECT_NEAR(steps.front(), 1e-5, 1e-9);
  EXPECT_NEAR(std::accumulate(steps.begin(), steps.end(), 0.0), 0.01, 1e-12);
  for (std::size_t k = 1; k < steps.size(); ++k) EXPECT_GT(steps[k], steps[k - 1]);
}

TEST(MarchSpacing, RejectsInconsistentOptions) {
  EXPECT_THROW(first_spacing_from_y_plus(0.0, 1e6, 1.0), Error);
  EXPECT_THROW(first_spacing_from_y_plus(1.0, -1.0, 1.0), Error);
  EXPECT_THROW(first_spacing_from_y_plus(1.0, 1e6, 0.0), Error);
  SpacingOptions options;
  options.layer_count = 0;
  EXPECT_THROW(layer_steps(options), Error);
  options.layer_count = 10;
  options.growth_rate = 0.9;
  EXPECT_THROW(layer_steps(options), Error);
  options.growth_rate = 1.2;
  options.growth_law = GrowthLaw::tanh;
  options.first_spacing = 1e-3;
  options.total_thickness = 5e-3;  // thinner than 10 uniform first steps
  EXPECT_THROW(layer_steps(options), Error);
  options.total_thickness.reset();  // tanh without a thickness
  EXPECT_THROW(layer_steps(options), Error);
  options.growth_law = GrowthLaw::geometric;
  options.first_spacing = 0.0;  // given, but not positive: no silent y+ estimate
  EXPECT_THROW(layer_steps(options), Error);
  options.first_spacing.reset();  // absent: from y+
  EXPECT_DOUBLE_EQ(layer_steps(options).front(), first_spacing_from_y_plus(options.target_y_plus,
                                                                           options.reynolds_number,
                                                                           options.reference_length));
}

// A stack thinned near a concave corner keeps its first step (the wall's y+) and stays
// geometric with a smaller growth; only a limit below N first steps makes it uniform.
TEST(MarchSpacing, StepsWithinAThicknessKeepTheFirstStep) {
  SpacingOptions options;  // the ONERA M6 stack: 32 layers from 1.546 um, growth 1.25
  const std::vector<double> steps = layer_steps(options);
  double total = 0.0;
  for (double step : steps) total += step;
  EXPECT_EQ(steps_within_thickness(steps, total * 1.5), steps);
  for (double fraction : {0.5, 0.1, 0.02}) {
    const std::vector<double> thinner = steps_within_thickness(steps, fraction * total);
    ASSERT_EQ(thinner.size(), steps.size());
    double sum = 0.0;
    for (double step : thinner) sum += step;
    EXPECT_NEAR(sum, fraction * total, 1e-9 * total) << fraction;
    EXPECT_DOUBLE_EQ(thinner.front(), steps.front());
    const double growth = thinner[1] / thinner[0];
    EXPECT_GT(growth, 1.0);
    EXPECT_LT(growth, 1.25);
    for (std::size_t k = 2; k < thinner.size(); ++k) EXPECT_NEAR(thinner[k] / thinner[k - 1], growth, 1e-9);
  }
  const double tiny = 0.5 * steps.front() * static_cast<double>(steps.size());
  for (double step : steps_within_thickness(steps, tiny))
    EXPECT_DOUBLE_EQ(step, tiny / static_cast<double>(steps.size()));
  EXPECT_THROW(steps_within_thickness(steps, 0.0), Error);
  EXPECT_THROW(steps_within_thickness({1e-6, -1e-6}, 1.0), Error);
}

}  // namespace
}  // namespace mixmesh
