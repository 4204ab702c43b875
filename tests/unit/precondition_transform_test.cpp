#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "mixmesh/core/error.hpp"
#include "mixmesh/precondition/precondition.hpp"

using namespace mixmesh;

namespace {

// Triangles stretched `ratio` : 1 in x, in the planes z = const and y = const
// alternately, so their mean affine invariant has full rank.
struct Surface {
  std::vector<Vector3> points;
  std::vector<std::array<Index, 3>> triangles;
};

Surface stretched_triangles(double ratio) {
  Surface surface;
  for (int copy = 0; copy < 6; ++copy) {
    const Vector3 origin(0.0, 0.3 * copy, 0.1 * copy);
    const Vector3 across = copy % 2 ? Vector3(0, 1, 0) : Vector3(0, 0, 1);
    const Index first = static_cast<Index>(surface.points.size());
    surface.points.push_back(origin);
    surface.points.push_back(origin + Vector3(ratio, 0, 0));
    surface.points.push_back(origin + 0.5 * Vector3(ratio, 0, 0) + across);
    surface.triangles.push_back({first, first + 1, first + 2});
  }
  return surface;
}

Vector3 sorted_eigenvalues(const Eigen::Matrix3d& matrix) {
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(matrix).eigenvalues();
}

}  // namespace

TEST(Precondition, ShearIsTheSweepMatrixAndForwardHasUnitDeterminant) {
  const Surface surface = stretched_triangles(10.0);
  PreconditionOptions options;
  options.sweep_degrees = 30.0;
  const Preconditioning map = precondition(surface.points, surface.triangles, options);
  EXPECT_NEAR(map.shear(0, 1), 0.5, 1e-15);  // Wild eq. (14): sin 30°
  EXPECT_NEAR(map.forward.determinant(), 1.0, 1e-12);
  EXPECT_TRUE((map.forward * map.backward).isApprox(Eigen::Matrix3d::Identity(), 1e-12));
  EXPECT_NEAR(map.mean_affine.trace(), 1.0, 1e-12) << "the mean of unit-trace covariances";
}

TEST(Precondition, SweepIsEstimatedFromTheLeadingEdge) {
  std::vector<Vector3> wing;
  for (int station = 0; station <= 20; ++station)
    for (int chordwise = 0; chordwise <= 10; ++chordwise) {
      const double y = 0.2 * station;
      wing.emplace_back(std::sin(25.0 * M_PI / 180.0) * y + 0.1 * chordwise, y, 0.0);
    }
  EXPECT_NEAR(estimate_sweep_degrees(wing), 25.0, 1e-9);
  // The estimated shear takes the sweep out: every leading-edge point maps to x = 0.
  PreconditionOptions options;
  options.affine = AffineMap::none;
  const Surface surface = stretched_triangles(3.0);
  Preconditioning map = precondition(wing, surface.triangles, options);
  EXPECT_NEAR(map.sweep_degrees, 25.0, 1e-9);
  const Eigen::Matrix3d unshear = map.shear.inverse();
  for (int station = 0; station <= 20; ++station)
    EXPECT_NEAR((unshear * wing[static_cast<std::size_t>(station * 11)]).x(), 0.0, 1e-12);
  EXPECT_EQ(estimate_sweep_degrees({{1, 0, 0}, {2, 0, 0}}), 0.0);
}

TEST(Precondition, WhiteningMakesTheMeanTriangleIsotropicAndTheInverseOvershoots) {
  const Surface surface = stretched_triangles(20.0);
  PreconditionOptions options;
  options.shear = false;
  const Vector3 before =
      sorted_eigenvalues(precondition(surface.points, surface.triangles, options).mean_affine);
  ASSERT_GT(before(2) / before(0), 10.0);

  options.affine = AffineMap::whitening;
  const Preconditioning whitening = precondition(surface.points, surface.triangles, options);
  options.affine = AffineMap::none;
  const Vector3 whitened = sorted_eigenvalues(
      precondition(transform_points(whitening.forward, surface.points), surface.triangles, options)
          .mean_affine);
  // Ā itself is a sum of unit-trace pieces, not an affine covariant, so whitening makes
  // the mapped mean much rounder rather than exactly round.
  EXPECT_LT(whitened(2) / whitened(0), 0.25 * before(2) / before(0));

  options.affine = AffineMap::inverse;
  const Preconditioning inverse = precondition(surface.points, surface.triangles, options);
  options.affine = AffineMap::none;
  const Eigen::Matrix3d inverted =
      precondition(transform_points(inverse.forward, surface.points), surface.triangles, options).mean_affine;
  // Ā⁻¹ scales the long axis by 1/λ rather than 1/√λ: x, long before, becomes the short axis.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(inverted);
  EXPECT_GT(std::abs(solver.eigenvectors().col(0).x()), 0.9);
}

TEST(Precondition, PlanarOrEmptySurfacesAreRejected) {
  const std::vector<Vector3> flat = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  EXPECT_THROW(precondition(flat, {{0, 1, 2}, {1, 3, 2}}), Error);
  EXPECT_THROW(precondition(flat, {}), Error);
  EXPECT_THROW(precondition(flat, {{0, 0, 0}}), Error);
}

TEST(Precondition, DumpWritesALegacyVtkSurface) {
  const Surface surface = stretched_triangles(2.0);
  const std::filesystem::path path = std::filesystem::path(::testing::TempDir()) / "precondition_dump.vtk";
  dump_surface(path, surface.points, surface.triangles);
  std::ifstream in(path);
  std::string line, text;
  while (std::getline(in, line)) text += line + "\n";
  EXPECT_EQ(text.rfind("# vtk DataFile Version 3.0", 0), 0u);
  EXPECT_NE(text.find("POINTS 18 double"), std::string::npos);
  EXPECT_NE(text.find("POLYGONS 6 24"), std::string::npos);
  std::filesystem::remove(path);
}
