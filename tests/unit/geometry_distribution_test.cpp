#include <gtest/gtest.h>

#include <cmath>

#include "mixmesh/core/error.hpp"
#include "mixmesh/geometry/cubic_spline.hpp"
#include "mixmesh/geometry/distribution.hpp"

using namespace mixmesh;

namespace {

void expect_increasing_from_zero_to_one(const std::vector<double>& positions) {
  ASSERT_GE(positions.size(), 2u);
  EXPECT_EQ(positions.front(), 0.0);
  EXPECT_EQ(positions.back(), 1.0);
  for (std::size_t k = 1; k < positions.size(); ++k)
    EXPECT_GT(positions[k], positions[k - 1]) << "node " << k;
}

}  // namespace

TEST(UniformDistribution, HasEqualSpacing) {
  const auto positions = uniform_distribution(4);
  ASSERT_EQ(positions.size(), 5u);
  for (std::size_t k = 0; k < positions.size(); ++k) EXPECT_DOUBLE_EQ(positions[k], 0.25 * k);
}

struct SpacingCase {
  int cells;
  double first;
  double last;
};

class VinokurSpacings : public ::testing::TestWithParam<SpacingCase> {};

INSTANTIATE_TEST_SUITE_P(Distribution, VinokurSpacings,
                         ::testing::Values(SpacingCase{100, 0.001, 0.002}, SpacingCase{100, 0.0005, 0.05},
                                           SpacingCase{40, 0.03, 0.03}, SpacingCase{40, 0.04, 0.02},
                                           SpacingCase{80, 0.01, 0.0}, SpacingCase{80, 0.0, 0.002},
                                           SpacingCase{20, 0.1, 0.0}, SpacingCase{10, 0.02, 0.3}));

TEST_P(VinokurSpacings, HitsTheRequestedEndSpacingsAndIncreases) {
  const SpacingCase& spacing = GetParam();
  const auto positions = vinokur_distribution(spacing.cells, spacing.first, spacing.last);
  ASSERT_EQ(positions.size(), static_cast<std::size_t>(spacing.cells) + 1);
  expect_increasing_from_zero_to_one(positions);
  if (spacing.first > 0.0) {
    EXPECT_NEAR(positions[1] / spacing.first, 1.0, 1e-9);
  }
  if (spacing.last > 0.0) {
    EXPECT_NEAR((1.0 - positions[spacing.cells - 1]) / spacing.last, 1.0, 1e-9);
  }
}

TEST(VinokurDistribution, IsSmoothWithBoundedNeighbourRatio) {
  const auto positions = vinokur_distribution(100, 0.001, 0.002);
  for (std::size_t k = 2; k < positions.size(); ++k) {
    const double ratio = (positions[k] - positions[k - 1]) / (positions[k - 1] - positions[k - 2]);
    EXPECT_LT(ratio, 1.2);
    EXPECT_GT(ratio, 1.0 / 1.2);
  }
}

TEST(VinokurDistribution, RejectsSpacingsThatDoNotFit) {
  EXPECT_THROW(vinokur_distribution(10, 0.6, 0.5), Error);
  EXPECT_THROW(vinokur_distribution(0, 0.1, 0.1), Error);
  EXPECT_THROW(vinokur_distribution(1, 0.1, 0.1), Error);
}

TEST(GeometricDistribution, GrowsByTheRatioAndEndsAtOne) {
  const auto positions = geometric_distribution(0.01, 1.2);
  expect_increasing_from_zero_to_one(positions);
  const double scale = positions[1] / 0.01;
  for (std::size_t k = 2; k < positions.size(); ++k) {
    EXPECT_NEAR((positions[k] - positions[k - 1]) / (positions[k - 1] - positions[k - 2]), 1.2, 1e-12);
  }
  EXPECT_NEAR(scale, 1.0, 0.15);
  EXPECT_THROW(geometric_distribution(0.0, 1.2), Error);
  EXPECT_THROW(geometric_distribution(0.1, 0.9), Error);
}

TEST(CubicSpline, ReproducesACubicInsideAndInterpolatesKnots) {
  // A natural spline is exact for linear data and interpolates any data at its knots.
  std::vector<double> knots, values;
  for (int k = 0; k <= 10; ++k) {
    knots.push_back(0.1 * k * k);
    values.push_back(3.0 - 2.0 * knots.back());
  }
  const CubicSpline line(knots, values);
  for (double t = 0.0; t <= 10.0; t += 0.37) {
    EXPECT_NEAR(line.value(t), 3.0 - 2.0 * t, 1e-12);
    EXPECT_NEAR(line.derivative(t), -2.0, 1e-12);
  }
  std::vector<double> sines;
  for (double knot : knots) sines.push_back(std::sin(knot));
  const CubicSpline curve(knots, sines);
  for (std::size_t k = 0; k < knots.size(); ++k) EXPECT_NEAR(curve.value(knots[k]), sines[k], 1e-14);
}

TEST(CubicSpline, RejectsKnotsThatDoNotIncrease) {
  EXPECT_THROW(CubicSpline({0.0, 1.0, 1.0}, {0.0, 1.0, 2.0}), Error);
  EXPECT_THROW(CubicSpline({0.0}, {0.0}), Error);
}
