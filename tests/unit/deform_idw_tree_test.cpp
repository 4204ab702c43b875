// The IDW tree code against the exact sum of eq. (1): within its certified bound, within
// the tolerance, exact at tolerance 0; invalid construction.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <random>

#include "mixmesh/core/error.hpp"
#include "mixmesh/deform/idw.hpp"
#include "mixmesh/deform/idw_tree.hpp"

namespace mixmesh::deform {
namespace {

struct Case {
  std::vector<Vector3> positions, displacements, volume;
  std::vector<Eigen::Matrix3d> rotations;
};

// A wavy displacement field on a unit sphere of boundary nodes, volume points around it.
Case sphere_case(int boundary_count, int volume_count, bool with_rotations) {
  std::mt19937 generator(42);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> radius(1.02, 6.0);
  Case result;
  for (int k = 0; k < boundary_count; ++k) {
    const Vector3 x = Vector3(normal(generator), normal(generator), normal(generator)).normalized();
    result.positions.push_back(x);
    result.displacements.push_back(0.05 * Vector3(std::sin(3 * x.y()), std::cos(2 * x.z()), x.x() * x.y()));
    if (with_rotations)
      result.rotations.push_back(
          Eigen::AngleAxisd(0.1 * x.z(), Vector3(x.y(), 1, 0).normalized()).toRotationMatrix());
  }
  for (int k = 0; k < volume_count; ++k) {
    const Vector3 direction = Vector3(normal(generator), normal(generator), normal(generator)).normalized();
    result.volume.push_back(radius(generator) * direction);
  }
  return result;
}

// Largest difference from the exact sum over the volume points; every point's difference
// must lie within the certified bound the evaluation reports.
double largest_error_within_bound(const Case& data, double tolerance, double exponent = 3.0) {
  const IdwTree tree(data.positions, data.displacements, data.rotations, exponent, 8);
  std::size_t clusters = 0;
  double largest_error = 0.0;
  for (const Vector3& point : data.volume) {
    const IdwTree::Evaluation exact = tree.evaluate_exact(point);
    const IdwTree::Evaluation approximate = tree.evaluate(point, tolerance);
    const double error = (approximate.displacement - exact.displacement).norm();
    // The certified bound holds (with room for round-off of the sums themselves).
    EXPECT_LE(error, approximate.error_bound + 1e-14) << "at " << point.transpose() << ", p = " << exponent;
    EXPECT_TRUE(std::isfinite(approximate.error_bound));
    largest_error = std::max(largest_error, error);
    clusters += approximate.cluster_terms;
  }
  EXPECT_GT(clusters, data.volume.size());  // far clusters were aggregated
  return largest_error;
}

double largest_displacement(const Case& data) {
  double largest = 0.0;
  for (const Vector3& u : data.displacements) largest = std::max(largest, u.norm());
  return largest;
}

void expect_tree_matches_exact(const Case& data) {
  // The tolerance controls the error: ten times tighter gives a much smaller error, and at
  // 1e-6 the error is a small fraction of the boundary motion. The tolerance budgets each
  // accepted cluster's error (relative to the largest displacement times the weight sum),
  // not the total, so at 1e-4 the total here is 3.4 times 1e-4 of the largest
  // displacement; the guarantee is the certified bound each evaluation is checked against.
  const double loose = largest_error_within_bound(data, 1e-4);
  const double tight = largest_error_within_bound(data, 1e-5);
  const double tighter = largest_error_within_bound(data, 1e-6);
  EXPECT_LT(tight, 0.5 * loose);
  EXPECT_LT(tighter, 0.5 * tight);
  EXPECT_LT(tighter, 1e-4 * largest_displacement(data));
}

TEST(IdwTree, MatchesExactSumWithinBound) {
  expect_tree_matches_exact(sphere_case(4000, 300, false));
}

TEST(IdwTree, MatchesExactSumWithRotations) {
  expect_tree_matches_exact(sphere_case(4000, 300, true));
}

// A tolerance so loose that every cluster under the largest opening angle is aggregated: the
// remainder bound is then taxed hardest (θ up to 0.75), for whole exponents (closed form of
// the tail) and others (Lagrange form), with a fixed body around the moving one.
TEST(IdwTree, BoundHoldsAtLargestOpeningAngle) {
  Case data = sphere_case(3000, 200, false);
  const std::size_t moving = data.positions.size();
  for (std::size_t k = 0; k < moving; k += 3) {
    data.positions.push_back(8.0 * data.positions[k]);
    data.displacements.push_back(Vector3::Zero());
  }
  for (const double exponent : {1.0, 2.0, 2.5, 3.0, 5.0}) {
    const double error = largest_error_within_bound(data, 1.0, exponent);
    EXPECT_GT(error, 0.0);  // the aggregates really were approximations
  }
  Case rotating = sphere_case(3000, 200, true);
  largest_error_within_bound(rotating, 1.0, 3.0);
}

// Groups of nearby points share the far clusters through one expansion about the group's
// centre: every point stays within its certified bound, the expansion is really used, and
// the error stays within a small multiple of the single-point evaluation's.
TEST(IdwTree, GroupEvaluationWithinBound) {
  const Case data = sphere_case(4000, 0, false);
  const IdwTree tree(data.positions, data.displacements, data.rotations, 3.0, 8);
  std::mt19937 generator(3);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (const double spread : {0.01, 0.1, 0.5}) {
    for (const double tolerance : {1e-6, 1e-4, 1.0}) {
      std::size_t shared = 0;
      double group_error = 0.0, single_error = 0.0;
      for (int trial = 0; trial < 10; ++trial) {
        const Vector3 centre = Vector3(normal(generator), normal(generator), normal(generator)).normalized() *
                               (1.5 + 3.0 * std::abs(normal(generator)));
        std::vector<Vector3> points;
        for (std::size_t k = 0; k < IdwTree::max_group_size; ++k)
          points.push_back(centre +
                           0.5 * spread * Vector3(normal(generator), normal(generator), normal(generator)));
        std::vector<IdwTree::Evaluation> evaluations(points.size());
        tree.evaluate_group(points.data(), points.size(), tolerance, evaluations.data());
        for (std::size_t k = 0; k < points.size(); ++k) {
          const Vector3 exact = tree.evaluate_exact(points[k]).displacement;
          const double error = (evaluations[k].displacement - exact).norm();
          EXPECT_LE(error, evaluations[k].error_bound + 1e-14)
              << "spread " << spread << " tolerance " << tolerance;
          group_error = std::max(group_error, error);
          single_error =
              std::max(single_error, (tree.evaluate(points[k], tolerance).displacement - exact).norm());
          shared += evaluations[k].cluster_terms;
        }
      }
      EXPECT_GT(shared, 0u);
      EXPECT_LT(group_error, 4.0 * single_error + 1e-12) << "spread " << spread << " tolerance " << tolerance;
    }
  }
}

// With rotations, and for a single point, the group call is the single-point evaluation.
TEST(IdwTree, GroupEvaluationFallsBackToSinglePoints) {
  const Case data = sphere_case(2000, 16, true);
  const IdwTree tree(data.positions, data.displacements, data.rotations, 3.0, 8);
  std::vector<IdwTree::Evaluation> evaluations(data.volume.size());
  tree.evaluate_group(data.volume.data(), data.volume.size(), 1e-5, evaluations.data());
  for (std::size_t k = 0; k < data.volume.size(); ++k)
    EXPECT_EQ(evaluations[k].displacement, tree.evaluate(data.volume[k], 1e-5).displacement);
  tree.evaluate_group(data.volume.data(), 0, 1e-5, evaluations.data());  // nothing to do
}

TEST(IdwTree, ZeroToleranceIsExact) {
  const Case data = sphere_case(1000, 50, false);
  const IdwTree tree(data.positions, data.displacements, data.rotations, 3.0, 8);
  for (const Vector3& point : data.volume) {
    const IdwTree::Evaluation exact = tree.evaluate_exact(point);
    const IdwTree::Evaluation approximate = tree.evaluate(point, 0.0);
    EXPECT_EQ(approximate.cluster_terms, 0u);
    EXPECT_LT((approximate.displacement - exact.displacement).norm(), 1e-15);
  }
}

TEST(IdwTree, LooserToleranceUsesFewerTerms) {
  const Case data = sphere_case(4000, 100, false);
  const IdwTree tree(data.positions, data.displacements, data.rotations, 3.0, 8);
  std::size_t tight = 0, loose = 0;
  for (const Vector3& point : data.volume) {
    const IdwTree::Evaluation a = tree.evaluate(point, 1e-6), b = tree.evaluate(point, 1e-2);
    tight += a.cluster_terms + a.node_terms;
    loose += b.cluster_terms + b.node_terms;
  }
  EXPECT_LT(loose, tight);
}

TEST(IdwTree, DeformSimpleFormTreeAgreesWithExactMode) {
  const Case data = sphere_case(3000, 400, false);
  IdwInput input;
  input.volume_points = data.volume;
  IdwBody body;
  body.positions = data.positions;
  body.displacements = data.displacements;
  input.bodies.push_back(body);
  IdwOptions options;
  options.form = IdwForm::simple;
  options.exact = true;
  const IdwResult exact = idw_deform(input, options);
  options.exact = false;
  const IdwResult tree = idw_deform(input, options);
  EXPECT_GT(tree.cluster_terms, 0u);
  EXPECT_EQ(exact.cluster_terms, 0u);
  for (std::size_t i = 0; i < data.volume.size(); ++i)
    EXPECT_LE((tree.displacements[i] - exact.displacements[i]).norm(), tree.error_bound + 1e-14);
}

TEST(IdwTree, RejectsInvalidConstruction) {
  const std::vector<Vector3> positions = {Vector3(0, 0, 0), Vector3(1, 0, 0)};
  const std::vector<Vector3> displacements = {Vector3(0, 0, 1), Vector3(0, 0, 1)};
  EXPECT_THROW(IdwTree({}, {}, {}, 3.0, 8), Error);
  EXPECT_THROW(IdwTree(positions, {Vector3::Zero()}, {}, 3.0, 8), Error);
  EXPECT_THROW(IdwTree(positions, displacements, {Eigen::Matrix3d::Identity()}, 3.0, 8), Error);
  EXPECT_THROW(IdwTree(positions, displacements, {}, -1.0, 8), Error);
  EXPECT_THROW(IdwTree(positions, displacements, {}, 3.0, 0), Error);
}

}  // namespace
}  // namespace mixmesh::deform
