#include <gtest/gtest.h>

#include <cmath>

#include "mixmesh/march/laplace_operators.hpp"

namespace mixmesh {
namespace {

const double pi = std::acos(-1.0);

// The regular ring of radius `radius` around the origin in the plane z = height.
std::vector<Vector3> regular_ring(int count, double radius, double height, double phase = 0.0) {
  std::vector<Vector3> ring;
  for (int n = 0; n < count; ++n) {
    const double angle = phase + 2.0 * pi * n / count;
    ring.emplace_back(radius * std::cos(angle), radius * std::sin(angle), height);
  }
  return ring;
}

TEST(MarchOperators, PrismOperatorEqualsStructuredOperatorOnARegularRing) {
  const double spacing = 0.3, step = 0.05;
  const std::vector<Vector3> ring = regular_ring(4, spacing, step);  // east, north, west, south
  StructuredStencil stencil{ring[0],
                            ring[2],
                            ring[1],
                            ring[3],
                            Vector3(spacing, spacing, step),
                            Vector3(-spacing, spacing, step),
                            Vector3(spacing, -spacing, step),
                            Vector3(-spacing, -spacing, step)};
  const Vector3 below(0, 0, 0);
  // A target off the line, so the two weights (in-layer against marching) matter.
  for (const Vector3& target :
       {Vector3(0.02, -0.01, step), Vector3(0.0, 0.0, step), Vector3(-0.04, 0.03, 0.8 * step)}) {
    const Vector3 structured = structured_laplace_update(stencil, target, below);
    const Vector3 prism = prism_laplace_update(ring, target, target, below);
    EXPECT_NEAR((structured - prism).norm(), 0.0, 1e-12) << target.transpose();
    // Strictly between the target and the ring centre (a weighted average).
    EXPECT_LT((structured - Vector3(0, 0, step)).norm(), (target - Vector3(0, 0, step)).norm() + 1e-15);
  }
}

TEST(MarchOperators, RegularRingsOfAnyValenceKeepTheCentre) {
  for (int count = 3; count <= 8; ++count) {
    const std::vector<Vector3> ring = regular_ring(count, 0.2, 0.01, 0.3);
    const Vector3 centre(0, 0, 0.01);
    const Vector3 result = prism_laplace_update(ring, centre, centre, Vector3::Zero());
    EXPECT_NEAR((result - centre).norm(), 0.0, 1e-12) << count;
  }
}

TEST(MarchOperators, StretchedRingsKeepTheirCentre) {
  // Affine images of regular rings (a stretched, sheared surface mesh): the centre of
  // the image is the solution, since a linear field is harmonic.
  Eigen::Matrix3d stretch;
  stretch << 3.0, 0.8, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 1.0;
  for (int count = 3; count <= 8; ++count) {
    std::vector<Vector3> ring = regular_ring(count, 0.2, 0.0, 0.4);
    for (Vector3& x : ring) x = stretch * x + Vector3(0, 0, 0.01);
    const Vector3 centre(0, 0, 0.01);
    const Vector3 result = prism_laplace_update(ring, centre, centre, Vector3::Zero());
    EXPECT_NEAR((result - centre).norm(), 0.0, 1e-9) << count;
  }
  StructuredStencil stencil;
  auto at = [&](double i, double j) {
    return Vector3(stretch * Vector3(0.2 * i, 0.2 * j, 0.0) + Vector3(0, 0, 0.01));
  };
  stencil = {at(1, 0), at(-1, 0), at(0, 1), at(0, -1), at(1, 1), at(-1, 1), at(1, -1), at(-1, -1)};
  const Vector3 centre(0, 0, 0.01);
  EXPECT_NEAR((structured_laplace_update(stencil, centre, Vector3::Zero()) - centre).norm(), 0.0, 1e-12);
}

TEST(MarchOperators, ThinLayersFollowTheMarchingLine) {
  // Near the wall (step << spacing) the marching term dominates: the result stays
  // close to the target even when the ring is displaced sideways.
  std::vector<Vector3> ring = regular_ring(6, 0.5, 1e-4);
  for (Vector3& x : ring) x.x() += 0.05;
  const Vector3 target(0, 0, 1e-4);
  const Vector3 result = prism_laplace_update(ring, target, target, Vector3::Zero());
  EXPECT_LT((result - target).norm(), 1e-6);
}

TEST(MarchOperators, DegenerateInputReturnsTheTarget) {
  const Vector3 target(1, 2, 3);
  EXPECT_EQ(prism_laplace_update({Vector3::Zero(), Vector3::UnitX()}, target, target, target), target);
  const StructuredStencil flat{};
  EXPECT_EQ(structured_laplace_update(flat, target, target), target);
}

}  // namespace
}  // namespace mixmesh
