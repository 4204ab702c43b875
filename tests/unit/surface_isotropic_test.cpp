// The isotropic (all-triangle) wing surface of the hybrid baseline: closed except at
// the root, consistently outward, the same wing as the mixed surface (area, volume)
// and edges near the requested length.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include "mixmesh/core/error.hpp"
#include "mixmesh/geometry/airfoil.hpp"
#include "mixmesh/geometry/planform.hpp"
#include "mixmesh/surface/isotropic_surface.hpp"
#include "mixmesh/surface/surface_conversion.hpp"
#include "mixmesh/surface/wing_surface.hpp"

using namespace mixmesh;

namespace {

const std::string onera_file = std::string(MIXMESH_SOURCE_DIR) + "/cases/airfoils/onera_d.dat";

WingDefinition onera_m6() {
  ClassicPlanform planform;
  planform.root_chord = 0.8059;
  planform.semi_span = 1.1963;
  planform.leading_edge_sweep_degrees = 30.0;
  planform.trailing_edge_sweep_degrees = 15.8;
  return classic_wing(planform, read_airfoil_file(onera_file));
}

// Twisted, tapered, with dihedral and an open (blunt) trailing edge.
WingDefinition blunt_naca_wing() {
  ClassicPlanform planform;
  planform.root_chord = 1.0;
  planform.semi_span = 2.0;
  planform.leading_edge_sweep_degrees = 20.0;
  planform.taper = 0.5;
  planform.tip_twist_degrees = -3.0;
  planform.dihedral_degrees = 3.0;
  NacaOptions naca;
  naca.points_per_side = 81;
  naca.closed_trailing_edge = false;
  return classic_wing(planform, naca_airfoil("2412", naca));
}

SurfaceOptions coarse_options() {
  SurfaceOptions options;
  options.chordwise_cells = 100;
  options.spanwise_cells = 40;
  options.wake.enabled = false;
  return options;
}

// Triangles of every wall patch of a surface, quads split in two.
std::vector<std::array<Index, 3>> wall_triangles(const SurfaceMesh& surface) {
  std::vector<std::array<Index, 3>> triangles;
  const MixedMesh mesh = to_mixed_mesh(surface);
  for (std::size_t f = 0; f < mesh.face_count(FaceType::triangle); ++f) {
    const Index* n = mesh.face(FaceType::triangle, f);
    triangles.push_back({n[0], n[1], n[2]});
  }
  for (std::size_t f = 0; f < mesh.face_count(FaceType::quad); ++f) {
    const Index* n = mesh.face(FaceType::quad, f);
    triangles.push_back({n[0], n[1], n[2]});
    triangles.push_back({n[0], n[2], n[3]});
  }
  return triangles;
}

struct Integrals {
  double area = 0.0;
  double volume = 0.0;  // the integral of x n_x: the enclosed volume, the open root (n_x = 0) adds nothing
};

Integrals integrals(const SurfaceMesh& surface) {
  Integrals result;
  for (const auto& t : wall_triangles(surface)) {
    const Vector3& a = surface.points[static_cast<std::size_t>(t[0])];
    const Vector3& b = surface.points[static_cast<std::size_t>(t[1])];
    const Vector3& c = surface.points[static_cast<std::size_t>(t[2])];
    const Vector3 normal = 0.5 * (b - a).cross(c - a);
    result.area += normal.norm();
    result.volume += (a.x() + b.x() + c.x()) / 3.0 * normal.x();
  }
  return result;
}

std::vector<double> edge_lengths(const SurfaceMesh& surface) {
  std::map<std::pair<Index, Index>, double> edges;
  for (const TrianglePatch& patch : surface.unstructured) {
    if (patch.name != "wing") continue;
    for (std::size_t k = 0; k < patch.triangles.size(); k += 3)
      for (int e = 0; e < 3; ++e) {
        const Index a = patch.triangles[k + e], b = patch.triangles[k + (e + 1) % 3];
        edges[{std::min(a, b), std::max(a, b)}] =
            (surface.points[static_cast<std::size_t>(a)] - surface.points[static_cast<std::size_t>(b)])
                .norm();
      }
  }
  std::vector<double> lengths;
  for (const auto& [key, length] : edges) lengths.push_back(length);
  return lengths;
}

// Every directed edge once and its reverse once (closed, consistently oriented),
// except the root loop, whose edges have no partner and lie in y = 0.
void expect_closed_except_root(const SurfaceMesh& surface) {
  std::map<std::pair<Index, Index>, int> directed;
  for (const TrianglePatch& patch : surface.unstructured)
    for (std::size_t k = 0; k < patch.triangles.size(); k += 3)
      for (int e = 0; e < 3; ++e) ++directed[{patch.triangles[k + e], patch.triangles[k + (e + 1) % 3]}];
  int root_edges = 0;
  for (const auto& [edge, count] : directed) {
    ASSERT_EQ(count, 1) << "edge " << edge.first << "-" << edge.second << " used twice in one direction";
    if (directed.count({edge.second, edge.first}) != 0) continue;
    ++root_edges;
    EXPECT_EQ(surface.points[static_cast<std::size_t>(edge.first)].y(), 0.0);
    EXPECT_EQ(surface.points[static_cast<std::size_t>(edge.second)].y(), 0.0);
  }
  EXPECT_GT(root_edges, 10);
}

}  // namespace

TEST(IsotropicSurface, DefaultEdgeIsTheMidSpanChordwiseEdgeOfTheMixedSurface) {
  const SurfaceOptions options = coarse_options();
  const SurfaceMesh mixed = generate_wing_surface(onera_m6(), options);
  const StructuredPatch& wing = mixed.structured.front();
  // The mixed surface's mean chordwise edge on the j line nearest mid-span.
  int middle = 0;
  for (int j = 0; j < wing.nj; ++j)
    if (std::abs(mixed.points[static_cast<std::size_t>(wing.node(0, j))].y() - 0.59815) <
        std::abs(mixed.points[static_cast<std::size_t>(wing.node(0, middle))].y() - 0.59815))
      middle = j;
  double perimeter = 0.0;
  for (int i = 0; i + 1 < wing.ni; ++i)
    perimeter += (mixed.points[static_cast<std::size_t>(wing.node(i + 1, middle))] -
                  mixed.points[static_cast<std::size_t>(wing.node(i, middle))])
                     .norm();
  EXPECT_NEAR(default_isotropic_edge_length(onera_m6(), options), perimeter / options.chordwise_cells,
              0.02 * perimeter / options.chordwise_cells);
}

TEST(IsotropicSurface, OneraM6ClosedOutwardAndTheSameWingAsTheMixedSurface) {
  const SurfaceOptions options = coarse_options();
  const SurfaceMesh surface = generate_isotropic_wing_surface(onera_m6(), options, 0.0);
  ASSERT_EQ(surface.structured.size(), 0u);
  ASSERT_EQ(surface.unstructured.size(), 2u);
  EXPECT_EQ(surface.unstructured[0].role, PatchRole::wall);
  EXPECT_EQ(surface.unstructured[1].role, PatchRole::wall);
  EXPECT_GT(surface.symmetry_tolerance, 0.0);
  EXPECT_EQ(surface.symmetry_y, 0.0);
  expect_closed_except_root(surface);

  const Integrals isotropic = integrals(surface);
  const Integrals mixed = integrals(generate_wing_surface(onera_m6(), options));
  EXPECT_NEAR(isotropic.area, mixed.area, 0.005 * mixed.area);
  // Positive enclosed volume with consistent orientation: every face points outward.
  EXPECT_GT(isotropic.volume, 0.0);
  EXPECT_NEAR(isotropic.volume, mixed.volume, 0.01 * mixed.volume);
  for (const Vector3& point : surface.points) {
    EXPECT_GE(point.y(), 0.0);
    EXPECT_LE(point.y(), 1.1963 + 1e-12);
  }
}

TEST(IsotropicSurface, EdgesNearTheTargetLength) {
  const double target = 0.02;
  const SurfaceMesh surface = generate_isotropic_wing_surface(onera_m6(), coarse_options(), target);
  std::vector<double> lengths = edge_lengths(surface);
  ASSERT_GT(lengths.size(), 1000u);
  std::sort(lengths.begin(), lengths.end());
  const double mean = std::accumulate(lengths.begin(), lengths.end(), 0.0) / lengths.size();
  EXPECT_NEAR(mean, target, 0.1 * target);
  // Roughly isotropic: the middle 90 % of the edges within a factor ~1.6 of the target.
  EXPECT_GT(lengths[lengths.size() / 20], 0.6 * target);
  EXPECT_LT(lengths[lengths.size() * 19 / 20], 1.6 * target);
  // A finer target gives proportionally more triangles (area / edge^2).
  const SurfaceMesh finer = generate_isotropic_wing_surface(onera_m6(), coarse_options(), 0.5 * target);
  const double ratio = static_cast<double>(finer.unstructured[0].triangles.size()) /
                       static_cast<double>(surface.unstructured[0].triangles.size());
  EXPECT_NEAR(ratio, 4.0, 0.4);
}

TEST(IsotropicSurface, BluntTwistedWingIsClosedAtASharpTrailingEdge) {
  SurfaceOptions options = coarse_options();
  options.tip.rounded = true;
  const SurfaceMesh surface = generate_isotropic_wing_surface(blunt_naca_wing(), options, 0.03);
  expect_closed_except_root(surface);
  EXPECT_GT(integrals(surface).volume, 0.0);
  // The rounded tip bulges outward past the tip plane.
  double largest_y = 0.0;
  for (const Vector3& point : surface.points) largest_y = std::max(largest_y, point.y());
  EXPECT_GT(largest_y, 2.0);
}

TEST(IsotropicSurface, RejectsBadInput) {
  EXPECT_THROW(generate_isotropic_wing_surface(onera_m6(), coarse_options(), -0.01), Error);
  EXPECT_THROW(generate_isotropic_wing_surface(onera_m6(), coarse_options(), 1e-5), Error);
  WingDefinition broken = onera_m6();
  broken.stations.back().chord = -1.0;
  EXPECT_THROW(generate_isotropic_wing_surface(broken, coarse_options(), 0.02), Error);
  SurfaceOptions no_cells = coarse_options();
  no_cells.chordwise_cells = 0;
  EXPECT_THROW(default_isotropic_edge_length(onera_m6(), no_cells), Error);
}
