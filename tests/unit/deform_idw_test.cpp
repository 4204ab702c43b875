// IDW deformation on plain data: rigid-motion reproduction, ψ blending, several bodies,
// automatic exponents, symmetry planes, invalid input.
#include <gtest/gtest.h>

#include <tbb/global_control.h>
#include <Eigen/Geometry>

#include <cmath>
#include <random>

#include "mixmesh/core/error.hpp"
#include "mixmesh/deform/idw.hpp"
#include "mixmesh/deform/idw_rigid_fit.hpp"

namespace mixmesh::deform {
namespace {

constexpr double pi = 3.14159265358979323846;

// Nodes on an ellipsoid with semi-axes (2, 1, 0.5): a closed body surface.
std::vector<Vector3> ellipsoid_nodes(int count, unsigned seed) {
  std::mt19937 generator(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<Vector3> nodes;
  for (int k = 0; k < count; ++k) {
    const Vector3 direction = Vector3(normal(generator), normal(generator), normal(generator)).normalized();
    nodes.push_back(direction.cwiseProduct(Vector3(2.0, 1.0, 0.5)));
  }
  return nodes;
}

std::vector<Vector3> cloud(int count, double radius, unsigned seed) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> uniform(-radius, radius);
  std::vector<Vector3> points;
  for (int k = 0; k < count; ++k)
    points.emplace_back(uniform(generator), uniform(generator), uniform(generator));
  return points;
}

IdwBody rigid_body(const std::vector<Vector3>& nodes, const Eigen::Matrix3d& rotation, const Vector3& centre,
                   const Vector3& translation) {
  IdwBody body;
  body.name = "wing";
  body.positions = nodes;
  for (const Vector3& x : nodes)
    body.displacements.push_back(rotation * (x - centre) + centre + translation - x);
  return body;
}

Vector3 rigid_displacement(const Vector3& x, const Eigen::Matrix3d& rotation, const Vector3& centre,
                           const Vector3& translation) {
  return rotation * (x - centre) + centre + translation - x;
}

TEST(IdwRotationForm, ReproducesRigidTranslationExactly) {
  IdwInput input;
  input.volume_points = cloud(200, 5.0, 1);
  const Vector3 translation(0.3, -0.2, 0.7);
  input.bodies.push_back(
      rigid_body(ellipsoid_nodes(300, 2), Eigen::Matrix3d::Identity(), Vector3::Zero(), translation));
  const IdwResult result = idw_deform(input);
  for (const Vector3& u : result.displacements) EXPECT_LT((u - translation).norm(), 1e-12);
}

TEST(IdwRotationForm, ReproducesRigidRotationExactly) {
  IdwInput input;
  input.volume_points = cloud(200, 5.0, 3);
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.6, Vector3(1.0, 2.0, -0.5).normalized()).toRotationMatrix();
  const Vector3 centre(0.25, 0.1, -0.3), translation(0.1, 0.2, 0.0);
  input.bodies.push_back(rigid_body(ellipsoid_nodes(300, 4), rotation, centre, translation));
  IdwOptions options;
  options.translation_exponent = 1.5;
  options.rotation_exponent = 2.0;
  // Fitted rotations (Kabsch), then the given per-node rotations averaged.
  for (const bool given : {false, true}) {
    if (given) input.bodies[0].rotations.assign(input.bodies[0].positions.size(), rotation);
    const IdwResult result = idw_deform(input, options);
    for (std::size_t i = 0; i < input.volume_points.size(); ++i)
      EXPECT_LT((result.displacements[i] -
                 rigid_displacement(input.volume_points[i], rotation, centre, translation))
                    .norm(),
                1e-10)
          << (given ? "given" : "fitted") << " rotations, volume point " << i;
  }
}

TEST(IdwRotationForm, ReproducesPlanarRotationOfStraightWalls) {
  // A square in z = 0: the reference nodes of points near a side are collinear, which a
  // spatial fit could not resolve; planar data are fitted about z.
  IdwBody body;
  for (int k = 0; k < 40; ++k) {
    const double s = -1.0 + 2.0 * k / 40.0;
    for (const Vector3& x : {Vector3(s, -1, 0), Vector3(1, s, 0), Vector3(-s, 1, 0), Vector3(-1, -s, 0)})
      body.positions.push_back(x);
  }
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(-5.0 * pi / 180.0, Vector3::UnitZ()).toRotationMatrix();
  for (const Vector3& x : body.positions)
    body.displacements.push_back(rigid_displacement(x, rotation, Vector3::Zero(), Vector3::Zero()));
  IdwInput input;
  input.bodies.push_back(body);
  for (int k = 0; k < 50; ++k) input.volume_points.emplace_back(1.0 + 0.1 * k, 0.03 * k, 0.0);
  const IdwResult result = idw_deform(input);
  for (std::size_t i = 0; i < input.volume_points.size(); ++i) {
    const Vector3 expected =
        rigid_displacement(input.volume_points[i], rotation, Vector3::Zero(), Vector3::Zero());
    EXPECT_LT((result.displacements[i] - expected).norm(), 1e-12) << "volume point " << i;
  }
}

TEST(IdwRotationForm, FadesToZeroAtFixedBoundary) {
  IdwInput input;
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(0.2, Vector3::UnitZ()).toRotationMatrix();
  input.bodies.push_back(rigid_body(ellipsoid_nodes(400, 5), rotation, Vector3::Zero(), Vector3(0.1, 0, 0)));
  IdwBody farfield;
  farfield.name = "farfield";
  farfield.moving = false;
  farfield.positions = ellipsoid_nodes(400, 6);
  for (Vector3& x : farfield.positions) x *= 10.0;
  input.bodies.push_back(farfield);
  // Points on the fixed boundary, next to the body, and between.
  input.volume_points = {farfield.positions[0], farfield.positions[7], input.bodies[0].positions[3] * 1.01,
                         input.bodies[0].positions[3] * 3.0};
  const IdwResult result = idw_deform(input);
  EXPECT_EQ(result.displacements[0].norm(), 0.0);
  EXPECT_EQ(result.displacements[1].norm(), 0.0);
  const Vector3 near =
      rigid_displacement(input.volume_points[2], rotation, Vector3::Zero(), Vector3(0.1, 0, 0));
  EXPECT_LT((result.displacements[2] - near).norm(), 0.02 * near.norm());
  // Half way out the motion has decayed but not vanished, and stays below the body's.
  const Vector3 middle =
      rigid_displacement(input.volume_points[3], rotation, Vector3::Zero(), Vector3(0.1, 0, 0));
  EXPECT_GT(result.displacements[3].norm(), 0.1 * middle.norm());
  EXPECT_LT(result.displacements[3].norm(), middle.norm());
}

// A body turned by `rotation` about `centre` inside a fixed spherical far field of
// radius `radius`, and `volume_count` points within `cloud_radius`; seeds from `seed` on.
IdwInput turning_body_in_far_field(const Eigen::Matrix3d& rotation, const Vector3& centre, int body_count,
                                   int far_count, double radius, int volume_count, double cloud_radius,
                                   unsigned seed) {
  IdwInput input;
  input.bodies.push_back(rigid_body(ellipsoid_nodes(body_count, seed), rotation, centre, Vector3::Zero()));
  IdwBody farfield;
  farfield.moving = false;
  farfield.positions = ellipsoid_nodes(far_count, seed + 1);
  for (Vector3& x : farfield.positions) x = radius * x.normalized();
  input.bodies.push_back(farfield);
  input.volume_points = cloud(volume_count, cloud_radius, seed + 2);
  return input;
}

TEST(IdwRotationForm, SameResultOnAnyThreadCountAndCloseToExactDistances) {
  const IdwInput input =
      turning_body_in_far_field(Eigen::AngleAxisd(0.2, Vector3::UnitX()).toRotationMatrix(), Vector3::Zero(),
                                500, 2000, 20.0, 5000, 6.0, 20);
  // The approximate distances to the other bodies (reused from the previous point of a
  // chunk) must not depend on the thread count either.
  IdwOptions approximate;
  approximate.distance_accuracy = 0.05;
  const IdwResult parallel = idw_deform(input, approximate);
  IdwResult serial;
  {
    const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    serial = idw_deform(input, approximate);
  }
  const IdwResult exact = idw_deform(input);  // the default: exact distances
  double largest = 0.0, difference = 0.0;
  for (std::size_t i = 0; i < input.volume_points.size(); ++i) {
    EXPECT_EQ(parallel.displacements[i], serial.displacements[i]) << "volume point " << i;
    largest = std::max(largest, exact.displacements[i].norm());
    difference = std::max(difference, (parallel.displacements[i] - exact.displacements[i]).norm());
  }
  // ψ moves by at most about the distance accuracy, and the decays (1 − ψ)^s with it.
  EXPECT_GT(difference, 0.0);
  EXPECT_LT(difference, 2.0 * approximate.distance_accuracy * largest);
}

// The exact distance search is seeded with the previous point's nearest node; it must
// give what a search from scratch gives (a volume point alone in its input), and the
// same on any thread count.
TEST(IdwRotationForm, SeededExactDistancesEqualASearchFromScratch) {
  const IdwInput input =
      turning_body_in_far_field(Eigen::AngleAxisd(0.3, Vector3::UnitY()).toRotationMatrix(),
                                Vector3(0.1, 0.0, 0.0), 400, 1500, 15.0, 3000, 5.0, 30);
  const IdwResult together = idw_deform(input);
  IdwResult serial;
  {
    const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    serial = idw_deform(input);
  }
  for (std::size_t i = 0; i < input.volume_points.size(); i += 7) {
    IdwInput alone = input;
    alone.volume_points = {input.volume_points[i]};
    EXPECT_EQ(idw_deform(alone).displacements[0], together.displacements[i]) << "volume point " << i;
  }
  for (std::size_t i = 0; i < input.volume_points.size(); ++i)
    EXPECT_EQ(serial.displacements[i], together.displacements[i]) << "volume point " << i;
}

TEST(IdwRotationForm, EachBodyCarriesItsOwnNeighbourhood) {
  IdwInput input;
  std::vector<Vector3> left = ellipsoid_nodes(200, 7), right = ellipsoid_nodes(200, 8);
  for (Vector3& x : left) x -= Vector3(4, 0, 0);
  for (Vector3& x : right) x += Vector3(4, 0, 0);
  input.bodies.push_back(rigid_body(left, Eigen::Matrix3d::Identity(), Vector3::Zero(), Vector3(0, 0.5, 0)));
  input.bodies.push_back(
      rigid_body(right, Eigen::Matrix3d::Identity(), Vector3::Zero(), Vector3(0, 0, -0.3)));
  input.volume_points = {left[5], right[9], Vector3(0, 0, 0)};
  const IdwResult result = idw_deform(input);
  EXPECT_LT((result.displacements[0] - Vector3(0, 0.5, 0)).norm(), 1e-12);
  EXPECT_LT((result.displacements[1] - Vector3(0, 0, -0.3)).norm(), 1e-12);
  // Midway each body contributes: both components present and smaller than either motion.
  EXPECT_GT(result.displacements[2].y(), 0.0);
  EXPECT_LT(result.displacements[2].y(), 0.5);
  EXPECT_LT(result.displacements[2].z(), 0.0);
  EXPECT_GT(result.displacements[2].z(), -0.3);
  ASSERT_EQ(result.bodies.size(), 2u);
}

TEST(IdwRotationForm, FaceDistancesMakePsiSmoothBetweenNodes) {
  // A plate of 1 × 1 quads in z = 0 translated in z, a fixed plate at z = 4. A point
  // above a node and one above the middle of a quad, both at height 0.3: with the
  // surface given as faces both are 0.3 from it and move alike; with nodes alone the
  // point over the quad's middle is 0.76 from the plate and moves less (the ripple that
  // folded flat pyramids over a plunging wing).
  IdwBody plate;
  plate.name = "plate";
  IdwBody lid;
  lid.name = "lid";
  lid.moving = false;
  const int n = 9;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      plate.positions.emplace_back(i - 4.0, j - 4.0, 0.0);
      plate.displacements.emplace_back(0.0, 0.0, 0.5);
      lid.positions.emplace_back(i - 4.0, j - 4.0, 4.0);
    }
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const Index corner = j * n + i;
      plate.faces.push_back({corner, corner + 1, corner + n + 1, corner + n});
      lid.faces.push_back({corner, corner + 1, corner + n + 1, -1});
      lid.faces.push_back({corner, corner + n + 1, corner + n, -1});
    }
  IdwInput input;
  input.volume_points = {Vector3(0.0, 0.0, 0.3), Vector3(0.5, 0.5, 0.3)};
  input.bodies = {plate, lid};
  const IdwResult with_faces = idw_deform(input);
  EXPECT_NEAR(with_faces.displacements[0].z(), 0.5 * (1.0 - 0.3 / 4.0), 1e-12);
  EXPECT_NEAR(with_faces.displacements[1].z(), with_faces.displacements[0].z(), 1e-12);
  for (IdwBody& body : input.bodies) body.faces.clear();
  const IdwResult nodes_only = idw_deform(input);
  EXPECT_GT(nodes_only.displacements[0].z() - nodes_only.displacements[1].z(), 0.01);

  input.bodies[0].faces = {{0, 1, 200, -1}};
  EXPECT_THROW(idw_deform(input), Error);  // a face naming a node the body does not have
}

TEST(IdwExponents, PureRotationPicksSrTwo) {
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(0.3, Vector3::UnitY()).toRotationMatrix();
  // About the centroid of the nodes: a rotation about another point also translates it.
  const std::vector<Vector3> nodes = ellipsoid_nodes(100, 9);
  Vector3 centroid = Vector3::Zero();
  for (const Vector3& x : nodes) centroid += x / 100.0;
  const IdwBody body = rigid_body(nodes, rotation, centroid, Vector3::Zero());
  const IdwBodyReport report = idw_exponents(body, IdwOptions{});
  EXPECT_NEAR(report.rotation_angle, 0.3, 1e-12);
  EXPECT_NEAR(report.rotation_share, 1.0, 1e-12);
  EXPECT_EQ(report.rotation_exponent, 2.0);
  EXPECT_EQ(report.translation_exponent, 1.0);
}

TEST(IdwExponents, PureTranslationPicksALargeSr) {
  const IdwBody body =
      rigid_body(ellipsoid_nodes(100, 10), Eigen::Matrix3d::Identity(), Vector3::Zero(), Vector3(1, 2, 3));
  const IdwBodyReport report = idw_exponents(body, IdwOptions{});
  EXPECT_NEAR(report.rotation_share, 0.0, 1e-12);
  EXPECT_EQ(report.rotation_exponent, IdwOptions{}.translation_rotation_exponent);
  EXPECT_GT(report.rotation_exponent, 2.0);
  EXPECT_EQ(report.translation_exponent, 1.0);
}

TEST(IdwExponents, ASmallButSteadyRotationKeepsSrTwo) {
  // The study's rectangle case a: 2° per step about the centroid with a translation of
  // 0.05 lengths, a rotation share of about 0.19, needs the rotation term at sr = 2.
  std::vector<Vector3> nodes;
  for (int k = 0; k <= 50; ++k) {
    const double x = -0.5 + k / 50.0;
    nodes.emplace_back(x, -0.1, 0.0);
    nodes.emplace_back(x, 0.1, 0.0);
  }
  Vector3 centroid = Vector3::Zero();
  for (const Vector3& x : nodes) centroid += x / static_cast<double>(nodes.size());
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(2.0 * M_PI / 180.0, Vector3::UnitZ()).toRotationMatrix();
  const IdwBody body = rigid_body(nodes, rotation, centroid, Vector3(0.0, 0.05, 0.0));
  const IdwBodyReport report = idw_exponents(body, IdwOptions{});
  EXPECT_GT(report.rotation_share, 0.1);
  EXPECT_LT(report.rotation_share, 0.3);
  EXPECT_EQ(report.rotation_exponent, 2.0);
}

TEST(IdwExponents, OptionsOverrideTheChoice) {
  const IdwBody body =
      rigid_body(ellipsoid_nodes(100, 11), Eigen::Matrix3d::Identity(), Vector3::Zero(), Vector3(1, 0, 0));
  IdwOptions options;
  options.translation_exponent = 2.0;
  options.rotation_exponent = 4.0;
  const IdwBodyReport report = idw_exponents(body, options);
  EXPECT_EQ(report.translation_exponent, 2.0);
  EXPECT_EQ(report.rotation_exponent, 4.0);
}

TEST(IdwSymmetry, NodesOnThePlaneKeepTheirCoordinate) {
  IdwInput input;
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(0.4, Vector3(1, 1, 0).normalized()).toRotationMatrix();
  input.bodies.push_back(rigid_body(ellipsoid_nodes(300, 12), rotation, Vector3::Zero(), Vector3(0, 0.2, 0)));
  input.symmetry_planes.push_back({Vector3(0, 2, 0), 0.0});  // y = 0, normal not unit
  input.volume_points = {Vector3(3, 0, 1), Vector3(-2, 0, -1.5), Vector3(3, 0.5, 1)};
  for (const IdwForm form : {IdwForm::rotation, IdwForm::simple}) {
    IdwOptions options;
    options.form = form;
    const IdwResult result = idw_deform(input, options);
    EXPECT_EQ(result.displacements[0].y(), 0.0);
    EXPECT_EQ(result.displacements[1].y(), 0.0);
    EXPECT_GT(result.displacements[0].norm(), 0.0);
    EXPECT_NE(result.displacements[2].y(), 0.0);  // off the plane: free
  }
}

TEST(IdwSimpleForm, WeightedAverageOfTwoNodes) {
  IdwInput input;
  IdwBody body;
  body.positions = {Vector3(-1, 0, 0), Vector3(1, 0, 0)};
  body.displacements = {Vector3(1, 0, 0), Vector3(0, 2, 0)};
  input.bodies.push_back(body);
  input.volume_points = {Vector3(0.5, 0, 0), Vector3(1, 0, 0)};
  IdwOptions options;
  options.form = IdwForm::simple;
  options.exact = true;
  options.exponent = 2.0;
  const IdwResult result = idw_deform(input, options);
  // Eq. (1), w = r^-2: w = 1/1.5², 1/0.5².
  const double w1 = 1.0 / 2.25, w2 = 4.0;
  EXPECT_NEAR(result.displacements[0].x(), w1 / (w1 + w2), 1e-15);
  EXPECT_NEAR(result.displacements[0].y(), 2.0 * w2 / (w1 + w2), 1e-15);
  EXPECT_EQ(result.displacements[1], Vector3(0, 2, 0));  // on a boundary node
}

TEST(IdwSimpleForm, PerNodeRotationsReproduceRigidMotion) {
  IdwInput input;
  input.volume_points = cloud(100, 4.0, 13);
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(0.5, Vector3(0, 1, 1).normalized()).toRotationMatrix();
  IdwBody body = rigid_body(ellipsoid_nodes(500, 14), rotation, Vector3(0.5, 0, 0), Vector3(0, 0, 0.1));
  body.rotations.assign(body.positions.size(), rotation);
  input.bodies.push_back(body);
  for (const bool exact : {true, false}) {
    IdwOptions options;
    options.form = IdwForm::simple;
    options.exact = exact;
    const IdwResult result = idw_deform(input, options);
    for (std::size_t i = 0; i < input.volume_points.size(); ++i) {
      const Vector3 expected =
          rigid_displacement(input.volume_points[i], rotation, Vector3(0.5, 0, 0), Vector3(0, 0, 0.1));
      EXPECT_LT((result.displacements[i] - expected).norm(), 1e-9)
          << (exact ? "exact" : "tree") << " point " << i;
    }
  }
}

TEST(IdwRigidFit, KabschRecoversRotationAndHandlesCollinearPoints) {
  const std::vector<Vector3> points = ellipsoid_nodes(20, 15);
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(1.0, Vector3(0.2, -1, 0.4).normalized()).toRotationMatrix();
  std::vector<Vector3> displacements;
  for (const Vector3& x : points) displacements.push_back(rotation * x - x);
  std::vector<Index> indices(points.size());
  for (std::size_t k = 0; k < indices.size(); ++k) indices[k] = static_cast<Index>(k);
  std::vector<double> weights(points.size(), 1.0);
  weights[0] = 7.0;
  const RigidFit fit =
      fit_rigid_motion(points, displacements, indices.data(), weights.data(), 20, FitDimension::spatial);
  EXPECT_LT((fit.rotation - rotation).norm(), 1e-12);

  const std::vector<Vector3> line = {Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(2, 0, 0)};
  const std::vector<Vector3> turned = {Vector3(0, 0, 0), Vector3(-1, 1, 0), Vector3(-2, 2, 0)};
  const RigidFit line_fit =
      fit_rigid_motion(line, turned, indices.data(), weights.data(), 3, FitDimension::spatial);
  EXPECT_LT((line_fit.rotation * Vector3::UnitX() - Vector3::UnitY()).norm(), 1e-12);
  EXPECT_NEAR(line_fit.rotation.determinant(), 1.0, 1e-12);
}

TEST(IdwInvalidInput, ThrowsOneClearError) {
  IdwInput input;
  input.volume_points = {Vector3(1, 2, 3)};
  EXPECT_THROW(idw_deform(input), Error);  // no boundary nodes

  IdwBody body;
  body.name = "flap";
  body.positions = {Vector3(0, 0, 0), Vector3(1, 0, 0)};
  body.displacements = {Vector3(0, 0, 1)};
  input.bodies = {body};
  try {
    idw_deform(input);
    FAIL() << "mismatched displacements accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("'flap' has 1 displacements for 2 nodes"), std::string::npos);
  }
  input.bodies[0].displacements.push_back(Vector3(0, 0, 1));
  IdwOptions options;
  options.rotation_exponent = -1.0;
  EXPECT_THROW(idw_deform(input, options), Error);
  options = IdwOptions{};
  options.exponent = 0.0;
  EXPECT_THROW(idw_deform(input, options), Error);
  input.bodies[0].rotations = {Eigen::Matrix3d::Identity(), 2.0 * Eigen::Matrix3d::Identity()};
  EXPECT_THROW(idw_deform(input), Error);
  input.bodies[0].rotations.clear();
  input.volume_points.push_back(Vector3(std::nan(""), 0, 0));
  EXPECT_THROW(idw_deform(input), Error);
  input.volume_points.pop_back();
  input.symmetry_planes.push_back({Vector3::Zero(), 0.0});
  EXPECT_THROW(idw_deform(input), Error);
}

}  // namespace
}  // namespace mixmesh::deform
