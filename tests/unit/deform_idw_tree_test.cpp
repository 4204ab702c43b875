// The IDW tree code against the exact sum of eq. (1): within its certified bound, within
// the tolerance, exact at tolerance 0; invalid construction.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

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

void expect_tree_matches_exact(const Case& data, double tolerance) {
  const IdwTree tree(data.positions, data.displacements, data.rotations, 3.0, 8);
  std::size_t clusters = 0;
  double largest_error = 0.0, largest_displacement = 0.0;
  for (const Vector3& point : data.volume) {
    const IdwTree::Evaluation exact = tree.evaluate_exact(point);
    const IdwTree::Evaluation approximate = tree.evaluate(point, tolerance);
    const double error = (approximate.displacement - exact.displacement).norm();
    // The certified bound holds (with room for round-off of the sums themselves).
    EXPECT_LE(error, approximate.error_bound + 1e-14) << "at " << point.transpose();
    largest_error = std::max(largest_error, error);
    largest_displacement = std::max(largest_displacement, exact.displacement.norm());
    clusters += approximate.cluster_terms;
  }
  // The tolerance is a relative budget per cluster; the achieved error is far smaller
  // than the tolerance times the displacements.
  EXPECT_LT(largest_error, tolerance * largest_displacement);
  EXPECT_GT(clusters, data.volume.size());  // far clusters were aggregated
}

TEST(IdwTree, MatchesExactSumWithinBound) {
  expect_tree_matches_exact(sphere_case(4000, 300, false), 1e-4);
}

TEST(IdwTree, MatchesExactSumWithRotations) {
  expect_tree_matches_exact(sphere_case(4000, 300, true), 1e-4);
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
