// The wing surface mesh: topology (closed, outward, shared seams), shape (no
// degenerate or folded faces) and geometry (areas, volume and sections against values
// computed here independently from the airfoil data and the planform).
#include <gtest/gtest.h>
#include <set>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "mixmesh/core/error.hpp"
#include "mixmesh/geometry/airfoil.hpp"
#include "mixmesh/geometry/planform.hpp"
#include "mixmesh/surface/surface_conversion.hpp"
#include "mixmesh/surface/wing_surface.hpp"

using namespace mixmesh;

namespace {

constexpr double root_chord = 0.8059;
constexpr double semi_span = 1.1963;
const double leading_edge_slope = std::tan(30.0 * M_PI / 180.0);
const double trailing_edge_slope = std::tan(15.8 * M_PI / 180.0);
const double tip_chord = root_chord + semi_span * (trailing_edge_slope - leading_edge_slope);

const std::string onera_file = std::string(MIXMESH_SOURCE_DIR) + "/cases/airfoils/onera_d.dat";

// The ONERA D data as written in the file (Selig order, unit chord), read here
// without the library so the reference values do not share its code.
std::vector<Vector2> onera_data() {
  std::ifstream stream(onera_file);
  std::string line;
  std::getline(stream, line);
  std::vector<Vector2> points;
  double x = 0.0, z = 0.0;
  while (stream >> x >> z) points.emplace_back(x, z);
  return points;
}

WingDefinition onera_m6() {
  ClassicPlanform planform;
  planform.root_chord = root_chord;
  planform.semi_span = semi_span;
  planform.leading_edge_sweep_degrees = 30.0;
  planform.trailing_edge_sweep_degrees = 15.8;
  return classic_wing(planform, read_airfoil_file(onera_file));
}

WingDefinition small_naca_wing(const std::string& digits, double twist_degrees = 0.0) {
  ClassicPlanform planform;
  planform.root_chord = 1.0;
  planform.semi_span = 2.0;
  planform.leading_edge_sweep_degrees = 20.0;
  planform.taper = 0.5;
  planform.tip_twist_degrees = twist_degrees;
  planform.dihedral_degrees = 3.0;
  NacaOptions naca;
  naca.points_per_side = 81;
  return classic_wing(planform, naca_airfoil(digits, naca));
}

SurfaceOptions coarse_options() {
  SurfaceOptions options;
  options.chordwise_cells = 60;
  options.spanwise_cells = 12;
  options.leading_edge_spacing = 0.004;
  options.trailing_edge_spacing = 0.008;
  options.root_spacing = 0.04;
  options.tip_spacing = 0.02;
  return options;
}

// Faces of the closed wing (all wall patches) and of the wake, as node lists.
struct FaceSets {
  std::vector<std::vector<Index>> wall;
  std::vector<std::vector<Index>> wake;
};

FaceSets faces_of(const SurfaceMesh& surface) {
  FaceSets sets;
  for (const StructuredPatch& patch : surface.structured) {
    for (int j = 0; j + 1 < patch.nj; ++j) {
      for (int i = 0; i + 1 < patch.ni; ++i) {
        std::vector<Index> quad = {patch.node(i, j), patch.node(i + 1, j), patch.node(i + 1, j + 1),
                                   patch.node(i, j + 1)};
        (patch.role == PatchRole::wake ? sets.wake : sets.wall).push_back(quad);
      }
    }
  }
  for (const TrianglePatch& patch : surface.unstructured) {
    for (std::size_t t = 0; t < patch.triangles.size(); t += 3) {
      sets.wall.push_back({patch.triangles[t], patch.triangles[t + 1], patch.triangles[t + 2]});
    }
  }
  return sets;
}

Vector3 area_vector(const std::vector<Vector3>& points, const std::vector<Index>& face) {
  Vector3 sum = Vector3::Zero();
  for (std::size_t k = 0; k < face.size(); ++k) {
    sum += points[static_cast<std::size_t>(face[k])].cross(
        points[static_cast<std::size_t>(face[(k + 1) % face.size()])]);
  }
  return 0.5 * sum;
}

// Enclosed volume by the divergence theorem with F = (0, 0, z): the symmetry plane
// (normal along y) adds nothing, so the open root does not matter. Faces are split into
// triangles (a fan from the first node).
double enclosed_volume(const std::vector<Vector3>& points, const std::vector<std::vector<Index>>& faces) {
  double volume = 0.0;
  for (const auto& face : faces) {
    const Vector3& a = points[static_cast<std::size_t>(face[0])];
    for (std::size_t k = 1; k + 1 < face.size(); ++k) {
      const Vector3& b = points[static_cast<std::size_t>(face[k])];
      const Vector3& c = points[static_cast<std::size_t>(face[k + 1])];
      volume += 0.5 * (b - a).cross(c - a).z() * (a.z() + b.z() + c.z()) / 3.0;
    }
  }
  return volume;
}

double triangulated_area(const std::vector<Vector3>& points, const std::vector<Index>& face) {
  double area = 0.0;
  const Vector3& a = points[static_cast<std::size_t>(face[0])];
  for (std::size_t k = 1; k + 1 < face.size(); ++k) {
    area += 0.5 * (points[static_cast<std::size_t>(face[k])] - a)
                      .cross(points[static_cast<std::size_t>(face[k + 1])] - a)
                      .norm();
  }
  return area;
}

// Every wall edge is used exactly twice in opposite directions, except root edges
// (both nodes on y = 0), used once.
void expect_closed_and_consistently_oriented(const SurfaceMesh& surface) {
  const FaceSets sets = faces_of(surface);
  std::map<std::pair<Index, Index>, int> directed;
  for (const auto& face : sets.wall) {
    for (std::size_t k = 0; k < face.size(); ++k) ++directed[{face[k], face[(k + 1) % face.size()]}];
  }
  int root_edges = 0;
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1) << "edge " << edge.first << "-" << edge.second << " used twice in one direction";
    const bool reverse = directed.count({edge.second, edge.first}) == 1;
    const bool on_root = surface.points[static_cast<std::size_t>(edge.first)].y() == 0.0 &&
                         surface.points[static_cast<std::size_t>(edge.second)].y() == 0.0;
    if (on_root && !reverse) {
      ++root_edges;
    } else {
      EXPECT_TRUE(reverse) << "free edge " << edge.first << "-" << edge.second;
    }
  }
  int expected_root_edges = surface.structured.front().ni - 1;
  for (const StructuredPatch& patch : surface.structured) {
    if (patch.name == "base") expected_root_edges += patch.ni - 1;
  }
  EXPECT_EQ(root_edges, expected_root_edges);
}

// The airfoil polyline distance of a unit-chord point.
double distance_to_polyline(const std::vector<Vector2>& polyline, const Vector2& point) {
  double nearest = 1e300;
  for (std::size_t k = 0; k + 1 < polyline.size(); ++k) {
    const Vector2 segment = polyline[k + 1] - polyline[k];
    const double t = std::clamp((point - polyline[k]).dot(segment) / segment.squaredNorm(), 0.0, 1.0);
    nearest = std::min(nearest, (polyline[k] + t * segment - point).norm());
  }
  return nearest;
}

}  // namespace

TEST(WingSurface, FollowsThePatchContract) {
  const SurfaceOptions options = coarse_options();
  const SurfaceMesh surface = generate_wing_surface(small_naca_wing("2412"), options);
  ASSERT_EQ(surface.structured.size(), 2u);
  const StructuredPatch& wing = surface.structured[0];
  const StructuredPatch& wake = surface.structured[1];
  EXPECT_EQ(wing.name, "wing");
  EXPECT_EQ(wing.role, PatchRole::wall);
  EXPECT_EQ(wing.ni, options.chordwise_cells + 1);
  EXPECT_EQ(wing.nj, options.spanwise_cells + 1);
  EXPECT_EQ(wing.leading_edge_i, options.chordwise_cells / 2);
  EXPECT_EQ(wake.name, "wake");
  EXPECT_EQ(wake.role, PatchRole::wake);
  EXPECT_EQ(wake.nj, wing.nj);
  ASSERT_EQ(surface.unstructured.size(), 1u);
  EXPECT_EQ(surface.unstructured[0].name, "tip");
  EXPECT_GT(surface.symmetry_tolerance, 0.0);
  EXPECT_EQ(surface.symmetry_y, 0.0);
  for (int j = 0; j < wing.nj; ++j) {
    EXPECT_EQ(wing.node(0, j), wing.node(wing.ni - 1, j)) << "sharp trailing edge is one node";
    EXPECT_EQ(wake.node(0, j), wing.node(0, j)) << "wake starts at the trailing edge";
    // i runs along the lower surface first: the node before the leading edge is below it.
    const Vector3& lower = surface.points[static_cast<std::size_t>(wing.node(wing.leading_edge_i / 2, j))];
    const Vector3& upper =
        surface.points[static_cast<std::size_t>(wing.node(3 * wing.leading_edge_i / 2, j))];
    EXPECT_LT(lower.z(), upper.z());
    for (int i = 1; i < wake.ni; ++i) {
      EXPECT_GT(surface.points[static_cast<std::size_t>(wake.node(i, j))].x(),
                surface.points[static_cast<std::size_t>(wake.node(i - 1, j))].x());
    }
  }
  for (int i = 0; i < wing.ni; ++i)
    EXPECT_EQ(surface.points[static_cast<std::size_t>(wing.node(i, 0))].y(), 0.0);
  // Every node is used and none is duplicated by coordinates.
  std::vector<int> uses(surface.points.size(), 0);
  for (const auto& face : faces_of(surface).wall)
    for (Index node : face) ++uses[static_cast<std::size_t>(node)];
  for (const auto& face : faces_of(surface).wake)
    for (Index node : face) ++uses[static_cast<std::size_t>(node)];
  for (std::size_t node = 0; node < uses.size(); ++node) EXPECT_GT(uses[node], 0) << "unused node " << node;
  std::map<std::array<double, 3>, int> coordinates;
  for (const Vector3& point : surface.points) ++coordinates[{point.x(), point.y(), point.z()}];
  EXPECT_EQ(coordinates.size(), surface.points.size());
}

TEST(WingSurface, IsClosedExceptAtTheRootAndOrientedOutward) {
  for (const std::string digits : {"0012", "2412", "23012", "23112"}) {
    SCOPED_TRACE(digits);
    const SurfaceMesh surface = generate_wing_surface(small_naca_wing(digits, -3.0), coarse_options());
    expect_closed_and_consistently_oriented(surface);
    EXPECT_GT(enclosed_volume(surface.points, faces_of(surface).wall), 0.0);
  }
}

TEST(WingSurface, HasNoDegenerateOrFoldedFaces) {
  const SurfaceMesh surface = generate_wing_surface(onera_m6(), coarse_options());
  const FaceSets sets = faces_of(surface);
  for (const auto& face : sets.wall) {
    const Vector3 normal = area_vector(surface.points, face);
    EXPECT_GT(normal.norm(), 1e-10);
    if (face.size() == 4) {
      // Both diagonal splits of a quad face the same way: the quad is not folded.
      const auto& p = surface.points;
      const Vector3 first = (p[face[1]] - p[face[0]]).cross(p[face[2]] - p[face[0]]);
      const Vector3 second = (p[face[2]] - p[face[0]]).cross(p[face[3]] - p[face[0]]);
      const Vector3 third = (p[face[2]] - p[face[1]]).cross(p[face[3]] - p[face[1]]);
      const Vector3 fourth = (p[face[3]] - p[face[1]]).cross(p[face[0]] - p[face[1]]);
      EXPECT_GT(first.dot(second), 0.0);
      EXPECT_GT(third.dot(fourth), 0.0);
    } else {
      // Tip triangles lie in the tip plane and face away from the wing (+y).
      EXPECT_GT(normal.normalized().y(), 1.0 - 1e-12);
      for (Index node : face) EXPECT_NEAR(surface.points[node].y(), semi_span, 1e-12);
    }
  }
  for (const auto& face : sets.wake)
    EXPECT_GT(area_vector(surface.points, face).normalized().z(), 1.0 - 1e-12);
  // Neighbouring wing faces across i (except across the trailing edge) turn by less than 60 degrees.
  const StructuredPatch& wing = surface.structured[0];
  for (int j = 0; j + 1 < wing.nj; ++j) {
    for (int i = 0; i + 2 < wing.ni; ++i) {
      const Vector3 a = area_vector(surface.points, {wing.node(i, j), wing.node(i + 1, j),
                                                     wing.node(i + 1, j + 1), wing.node(i, j + 1)});
      const Vector3 b = area_vector(surface.points, {wing.node(i + 1, j), wing.node(i + 2, j),
                                                     wing.node(i + 2, j + 1), wing.node(i + 1, j + 1)});
      EXPECT_GT(a.normalized().dot(b.normalized()), 0.5) << "i " << i << " j " << j;
    }
  }
}

TEST(WingSurface, TipCapSharesTheTipSectionAndHasAMinimumAngle) {
  const SurfaceOptions options;  // the case's resolution
  const SurfaceMesh surface = generate_wing_surface(onera_m6(), options);
  const StructuredPatch& wing = surface.structured[0];
  std::map<Index, int> tip_uses;
  double smallest_angle = 180.0;
  int below_bound = 0;
  const auto& triangles = surface.unstructured[0].triangles;
  for (std::size_t t = 0; t < triangles.size(); t += 3) {
    double smallest_here = 180.0;
    for (int corner = 0; corner < 3; ++corner) {
      ++tip_uses[triangles[t + corner]];
      const Vector3& p = surface.points[triangles[t + corner]];
      const Vector3 u = surface.points[triangles[t + (corner + 1) % 3]] - p;
      const Vector3 v = surface.points[triangles[t + (corner + 2) % 3]] - p;
      smallest_here = std::min(smallest_here, std::acos(u.normalized().dot(v.normalized())) * 180.0 / M_PI);
    }
    smallest_angle = std::min(smallest_angle, smallest_here);
    if (smallest_here < options.tip.minimum_angle_degrees) ++below_bound;
  }
  for (int i = 0; i < wing.ni; ++i)
    EXPECT_EQ(tip_uses.count(wing.node(i, wing.nj - 1)), 1u) << "tip node " << i;
  // Refined triangles respect the angle bound; a few on the outline, which is never split,
  // keep smaller angles (the sharp trailing edge itself is about 13 degrees).
  EXPECT_GT(smallest_angle, 10.0);
  EXPECT_LT(below_bound, static_cast<int>(triangles.size() / 3 / 50));
}

TEST(WingSurface, OneraM6AreasAndVolumeMatchIndependentIntegrals) {
  SurfaceOptions options;  // the paper's resolution: 200 x 80 wing faces
  const SurfaceMesh surface = generate_wing_surface(onera_m6(), options);
  const FaceSets sets = faces_of(surface);
  EXPECT_EQ(sets.wall.size() - surface.unstructured[0].triangles.size() / 3, 16000u);

  // Reference values from the airfoil data and the planform alone.
  const std::vector<Vector2> data = onera_data();
  double section_area = 0.0;
  for (std::size_t k = 0; k + 1 < data.size(); ++k) {
    section_area += 0.5 * (data[k].x() * data[k + 1].y() - data[k + 1].x() * data[k].y());
  }
  section_area = std::abs(section_area);
  const double chord_slope = (tip_chord - root_chord) / semi_span;
  const double reference_volume = section_area * semi_span *
                                  (root_chord * root_chord + root_chord * tip_chord + tip_chord * tip_chord) /
                                  3.0;
  // Wetted area of x = le(y) + c(y) X(t), z = c(y) Z(t): |r_t x r_y| integrated with
  // the midpoint rule per data segment and Simpson's rule in y.
  const auto strip = [&](double y) {
    const double chord = root_chord + chord_slope * y;
    double length = 0.0;
    for (std::size_t k = 0; k + 1 < data.size(); ++k) {
      const Vector2 d = data[k + 1] - data[k];
      const Vector2 middle = 0.5 * (data[k + 1] + data[k]);
      const double shear =
          d.y() * (leading_edge_slope + chord_slope * middle.x()) - d.x() * chord_slope * middle.y();
      length += std::sqrt(d.squaredNorm() + shear * shear);
    }
    return chord * length;
  };
  const int intervals = 64;
  double wetted = 0.0;
  for (int k = 0; k <= intervals; ++k) {
    const double weight = (k == 0 || k == intervals) ? 1.0 : (k % 2 == 1 ? 4.0 : 2.0);
    wetted += weight * strip(semi_span * k / intervals);
  }
  wetted *= semi_span / intervals / 3.0;
  const double planform_area = 0.5 * (root_chord + tip_chord) * semi_span;

  double mesh_wetted = 0.0, mesh_projected = 0.0, mesh_tip = 0.0;
  for (const auto& face : sets.wall) {
    if (face.size() == 4) {
      mesh_wetted += triangulated_area(surface.points, face);
      mesh_projected += 0.5 * std::abs(area_vector(surface.points, face).z());
    } else {
      mesh_tip += triangulated_area(surface.points, face);
    }
  }
  EXPECT_NEAR(mesh_wetted / wetted, 1.0, 0.005);
  EXPECT_NEAR(mesh_projected / planform_area, 1.0, 0.005);
  EXPECT_NEAR(mesh_tip / (section_area * tip_chord * tip_chord), 1.0, 0.005);
  EXPECT_NEAR(enclosed_volume(surface.points, sets.wall) / reference_volume, 1.0, 0.005);
}

TEST(WingSurface, OneraM6PressureStationCutsReproduceTheAirfoil) {
  const SurfaceMesh surface = generate_wing_surface(onera_m6(), SurfaceOptions{});
  const StructuredPatch& wing = surface.structured[0];
  const std::vector<Vector2> data = onera_data();
  for (double fraction : {0.20, 0.44, 0.65, 0.80, 0.90, 0.95, 0.99}) {
    SCOPED_TRACE(fraction);
    const double y = fraction * semi_span;
    const double chord = root_chord + (tip_chord - root_chord) * fraction;
    const double leading_edge = y * leading_edge_slope;
    int j = 0;
    while (surface.points[wing.node(0, j + 1)].y() < y) ++j;
    std::vector<Vector2> cut;
    for (int i = 0; i < wing.ni; ++i) {
      const Vector3& a = surface.points[wing.node(i, j)];
      const Vector3& b = surface.points[wing.node(i, j + 1)];
      const Vector3 point = a + (y - a.y()) / (b.y() - a.y()) * (b - a);
      cut.emplace_back((point.x() - leading_edge) / chord, point.z() / chord);
    }
    double worst = 0.0;
    for (const Vector2& point : cut) worst = std::max(worst, distance_to_polyline(data, point));
    for (const Vector2& point : data) worst = std::max(worst, distance_to_polyline(cut, point));
    EXPECT_LT(worst, 1e-4);
  }
}

namespace {

// A NACA 0012 wing of taper 0.6 whose section keeps its open trailing edge.
WingDefinition open_edged_wing(double semi_span) {
  NacaOptions open;
  open.closed_trailing_edge = false;
  open.points_per_side = 81;
  ClassicPlanform planform;
  planform.taper = 0.6;
  planform.semi_span = semi_span;
  return classic_wing(planform, naca_airfoil("0012", open));
}

}  // namespace

TEST(WingSurface, BluntTrailingEdgeIsClosedOrKeptAsABase) {
  WingDefinition wing = open_edged_wing(1.0);
  const SurfaceMesh closed = generate_wing_surface(wing, coarse_options());
  EXPECT_EQ(closed.structured[0].node(0, 3), closed.structured[0].node(closed.structured[0].ni - 1, 3));
  expect_closed_and_consistently_oriented(closed);

  wing.blunt_trailing_edge = TrailingEdge::base;
  const SurfaceMesh based = generate_wing_surface(wing, coarse_options());
  ASSERT_EQ(based.structured.size(), 3u);
  const StructuredPatch& base = based.structured[1];
  EXPECT_EQ(base.name, "base");
  EXPECT_EQ(base.ni, coarse_options().base_cells + 1);
  EXPECT_NE(based.structured[0].node(0, 3), based.structured[0].node(based.structured[0].ni - 1, 3));
  EXPECT_EQ(based.structured[2].node(0, 3), base.node(base.ni / 2, 3));
  expect_closed_and_consistently_oriented(based);
  EXPECT_GT(enclosed_volume(based.points, faces_of(based).wall), 0.0);
}

// A base 1.5 mm thick at the tip under spanwise faces about a metre long: four faces
// across it would be 0.4 mm wide, 2,500 times shorter than the spanwise faces, and the
// split layer's pyramids beside them flat; it gets two. With base_face_aspect 0, four.
TEST(WingSurface, BaseUnderLongSpanwiseFacesGetsFewerFaces) {
  WingDefinition wing = open_edged_wing(10.0);
  wing.blunt_trailing_edge = TrailingEdge::base;
  SurfaceOptions options = coarse_options();
  const SurfaceMesh fewer = generate_wing_surface(wing, options);
  ASSERT_EQ(fewer.structured.size(), 3u);
  EXPECT_EQ(fewer.structured[1].name, "base");
  EXPECT_EQ(fewer.structured[1].ni, 3);
  EXPECT_EQ(fewer.structured[2].node(0, 3), fewer.structured[1].node(1, 3)) << "the wake leaves the middle";
  expect_closed_and_consistently_oriented(fewer);

  options.base_face_aspect = 0.0;
  const SurfaceMesh all = generate_wing_surface(wing, options);
  EXPECT_EQ(all.structured[1].ni, options.base_cells + 1);
  expect_closed_and_consistently_oriented(all);
}

// Where the wake leaves a base's middle at the tip, the march splits the cap triangle
// there that straddles the sheet's plane. Left to the refinement that triangle had an
// edge on the base (two cap triangles at the node), and its column's corner on the base
// edge was straight and folded; the cap now has edges leaving the node above and below
// the plane, and the straddling triangle touches the base at that node only.
TEST(WingSurface, CapAtABasesWakeNodeStraddlesTheSheetOffTheBase) {
  NacaOptions open;
  open.closed_trailing_edge = false;
  open.points_per_side = 81;
  for (const double sweep : {0.0, 37.5}) {
    ClassicPlanform planform;
    planform.taper = 0.85;
    planform.leading_edge_sweep_degrees = sweep;
    WingDefinition wing = classic_wing(planform, naca_airfoil("0018", open));
    wing.blunt_trailing_edge = TrailingEdge::base;
    SurfaceOptions options;
    options.chordwise_cells = 80;
    options.spanwise_cells = 12;
    const SurfaceMesh surface = generate_wing_surface(wing, options);
    ASSERT_EQ(surface.structured.size(), 3u);
    const StructuredPatch& base = surface.structured[1];
    const StructuredPatch& wake = surface.structured[2];
    const Index node = wake.node(0, wake.nj - 1);
    std::set<Index> base_nodes;
    for (int i = 0; i < base.ni; ++i) base_nodes.insert(base.node(i, base.nj - 1));
    const double sheet_z = surface.points[static_cast<std::size_t>(node)].z();
    int straddling = 0, fan = 0;
    for (const TrianglePatch& patch : surface.unstructured)
      for (std::size_t t = 0; t < patch.triangles.size(); t += 3) {
        std::vector<Index> others;
        for (std::size_t k = 0; k < 3; ++k)
          if (patch.triangles[t + k] != node) others.push_back(patch.triangles[t + k]);
        if (others.size() != 2) continue;
        ++fan;
        const double first = surface.points[static_cast<std::size_t>(others[0])].z() - sheet_z;
        const double second = surface.points[static_cast<std::size_t>(others[1])].z() - sheet_z;
        if (first * second >= 0.0) continue;
        ++straddling;
        EXPECT_EQ(base_nodes.count(others[0]) + base_nodes.count(others[1]), 0u) << "sweep " << sweep;
      }
    EXPECT_GE(fan, 3) << "sweep " << sweep;
    EXPECT_EQ(straddling, 1) << "sweep " << sweep;
    expect_closed_and_consistently_oriented(surface);
  }
}

TEST(WingSurface, ConversionMarksLowerUpperTipAndWake) {
  const SurfaceMesh surface = generate_wing_surface(small_naca_wing("0012"), coarse_options());
  const MixedMesh mesh = to_mixed_mesh(surface);
  EXPECT_EQ(mesh.cell_count(), 0u);
  const int lower = mesh.find_marker("wing_lower"), upper = mesh.find_marker("wing_upper");
  const int tip = mesh.find_marker("tip"), wake = mesh.find_marker("wake");
  ASSERT_GE(lower, 0);
  ASSERT_GE(upper, 0);
  ASSERT_GE(tip, 0);
  ASSERT_GE(wake, 0);
  std::map<int, int> counts;
  for (int marker : mesh.faces(FaceType::quad).markers) ++counts[marker];
  const SurfaceOptions options = coarse_options();
  EXPECT_EQ(counts[lower], options.chordwise_cells / 2 * options.spanwise_cells);
  EXPECT_EQ(counts[upper], options.chordwise_cells / 2 * options.spanwise_cells);
  EXPECT_EQ(counts[wake], (surface.structured[1].ni - 1) * options.spanwise_cells);
  EXPECT_EQ(mesh.face_count(FaceType::triangle), surface.unstructured[0].triangles.size() / 3);
  // Lower faces face down, upper faces up (on average over the surface).
  double lower_z = 0.0, upper_z = 0.0;
  for (std::size_t f = 0; f < mesh.face_count(FaceType::quad); ++f) {
    const Index* nodes = mesh.face(FaceType::quad, f);
    const double z = area_vector(mesh.points, {nodes[0], nodes[1], nodes[2], nodes[3]}).z();
    if (mesh.faces(FaceType::quad).markers[f] == lower) lower_z += z;
    if (mesh.faces(FaceType::quad).markers[f] == upper) upper_z += z;
  }
  EXPECT_LT(lower_z, 0.0);
  EXPECT_GT(upper_z, 0.0);
}

TEST(WingSurface, RejectsOptionsThatCannotGiveAMesh) {
  const WingDefinition wing = small_naca_wing("0012");
  SurfaceOptions options = coarse_options();
  options.chordwise_cells = 4;
  EXPECT_THROW(generate_wing_surface(wing, options), Error);
  options = coarse_options();
  options.leading_edge_spacing = 2.0;  // longer than a surface
  EXPECT_THROW(generate_wing_surface(wing, options), Error);
  options = coarse_options();
  options.wake.length = -1.0;
  EXPECT_THROW(generate_wing_surface(wing, options), Error);
  options = coarse_options();
  options.tip.minimum_angle_degrees = 35.0;
  EXPECT_THROW(generate_wing_surface(wing, options), Error);
  WingDefinition negative = wing;
  negative.stations[1].chord = -0.2;
  EXPECT_THROW(generate_wing_surface(negative, coarse_options()), Error);
}

TEST(WingSurface, StationsAreNodeRowsAndTwistRaisesTheLeadingEdge) {
  NacaOptions naca;
  naca.points_per_side = 81;
  WingDefinition wing;
  wing.airfoils = {naca_airfoil("2412", naca), naca_airfoil("0010", naca)};
  wing.twist_axis = 0.25;
  SpanStation root, kink, tip;
  root.chord = 2.0;
  kink.y = 1.3;
  kink.chord = 1.4;
  kink.leading_edge_x = 0.5;
  kink.leading_edge_z = 0.05;
  kink.twist_degrees = 2.0;
  tip.y = 3.0;
  tip.chord = 0.6;
  tip.leading_edge_x = 1.6;
  tip.leading_edge_z = 0.2;
  tip.twist_degrees = 5.0;
  tip.airfoil = 1;
  wing.stations = {root, kink, tip};
  const SurfaceMesh surface = generate_wing_surface(wing, coarse_options());
  expect_closed_and_consistently_oriented(surface);
  const StructuredPatch& patch = surface.structured[0];
  int kink_row = -1;
  for (int j = 0; j < patch.nj; ++j) {
    if (surface.points[patch.node(0, j)].y() == kink.y) kink_row = j;
  }
  ASSERT_GE(kink_row, 0) << "the kink station is a node row";
  // Leading edge of a twisted station: rotated about the quarter chord, nose up.
  const auto leading_edge_z = [](const SpanStation& station) {
    return station.leading_edge_z + station.chord * 0.25 * std::sin(station.twist_degrees * M_PI / 180.0);
  };
  EXPECT_NEAR(surface.points[patch.node(patch.leading_edge_i, kink_row)].z(), leading_edge_z(kink), 1e-12);
  EXPECT_NEAR(surface.points[patch.node(patch.leading_edge_i, patch.nj - 1)].z(), leading_edge_z(tip), 1e-12);
  // The tip row is the symmetric 0010 section: its thickness is 10 % of the tip chord.
  double thickest = 0.0;
  for (int i = 1; i < patch.leading_edge_i; ++i) {
    const Vector3 lower = surface.points[patch.node(i, patch.nj - 1)];
    const Vector3 upper = surface.points[patch.node(patch.ni - 1 - i, patch.nj - 1)];
    thickest = std::max(thickest, (upper - lower).norm());
  }
  EXPECT_NEAR(thickest / tip.chord, 0.10, 2e-3);
}

TEST(WingSurface, RoundedTipAddsAHalfBodyOfRevolution) {
  SurfaceOptions options;  // the case's resolution
  const SurfaceMesh flat = generate_wing_surface(onera_m6(), options);
  options.tip.rounded = true;
  const SurfaceMesh rounded = generate_wing_surface(onera_m6(), options);
  expect_closed_and_consistently_oriented(rounded);
  ASSERT_EQ(rounded.points.size(), flat.points.size());
  // Only the interior cap nodes move, and only outward.
  for (std::size_t node = 0; node < flat.points.size(); ++node) {
    EXPECT_EQ(rounded.points[node].x(), flat.points[node].x());
    EXPECT_EQ(rounded.points[node].z(), flat.points[node].z());
    EXPECT_GE(rounded.points[node].y(), flat.points[node].y());
  }
  // The added volume is the half body of revolution: integral of pi h(x)^2 / 2 over the
  // tip chord, h the half-thickness of the (symmetric) tip section from the data.
  const std::vector<Vector2> data = onera_data();
  double half_body = 0.0;
  for (std::size_t k = 0; k + 1 < data.size(); ++k) {
    if (data[k].y() <= 0.0 || data[k + 1].y() <= 0.0) continue;  // upper surface segments
    const double h = 0.5 * (data[k].y() + data[k + 1].y()) * tip_chord;
    half_body += 0.5 * M_PI * h * h * std::abs(data[k + 1].x() - data[k].x()) * tip_chord;
  }
  const double added = enclosed_volume(rounded.points, faces_of(rounded).wall) -
                       enclosed_volume(flat.points, faces_of(flat).wall);
  // Flat triangles under-fill the half-circles; a finer cap converges to the half body.
  EXPECT_GT(added / half_body, 0.85);
  EXPECT_LT(added / half_body, 1.0);
  options.tip.maximum_edge = 0.002;
  const SurfaceMesh fine = generate_wing_surface(onera_m6(), options);
  const double fine_added =
      enclosed_volume(fine.points, faces_of(fine).wall) - enclosed_volume(flat.points, faces_of(flat).wall);
  EXPECT_GT(fine_added, added);
  EXPECT_NEAR(fine_added / half_body, 1.0, 0.03);
}
